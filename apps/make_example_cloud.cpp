// Writes the example cloud that `make run` inspects: the inside of a 4 m × 3 m × 2.5 m room
// (floor at z = 0, centred on x = y = 0) sampled every 5.5 cm (19k points) on its floor, walls and
// ceiling, with inward normals and a per-surface intensity. Deterministic: a fixed seed and a
// hand-rolled uniform mapping (std:: distributions differ between standard libraries).
#include <cstdint>
#include <cstdio>
#include <exception>
#include <random>
#include <string>

#include <scantling/core/point_cloud.hpp>
#include <scantling/io/cloud_io.hpp>

namespace {

constexpr double kLengthM = 4.0;
constexpr double kWidthM = 3.0;
constexpr double kHeightM = 2.5;
constexpr double kSpacingM = 0.055;
constexpr double kJitterM = 0.01;  ///< in-plane jitter, so the cloud is not a perfect lattice
constexpr double kNoiseM = 0.002;  ///< along the normal, like a good LiDAR's range noise
constexpr std::uint32_t kSeed = 20240601;

class Uniform {
  public:
    explicit Uniform(std::uint32_t seed) : engine_(seed) {}
    /// Uniform in [-1, 1), from the engine's 32 bits (mt19937 output is specified exactly).
    double symmetric() { return static_cast<double>(engine_()) / 2147483648.0 - 1.0; }

  private:
    std::mt19937 engine_;
};

/// One rectangular surface: origin + u * du + v * dv, normal pointing into the room.
struct Face {
    Eigen::Vector3d origin, du, dv, normal;
    float intensity;
};

void sample_face(const Face& face, Uniform& random, scantling::PointCloud& cloud) {
    const int nu = static_cast<int>(face.du.norm() / kSpacingM);
    const int nv = static_cast<int>(face.dv.norm() / kSpacingM);
    const Eigen::Vector3d eu = face.du.normalized(), ev = face.dv.normalized();
    for (int i = 0; i < nu; ++i) {
        for (int j = 0; j < nv; ++j) {
            const double u = (i + 0.5) * kSpacingM + kJitterM * random.symmetric();
            const double v = (j + 0.5) * kSpacingM + kJitterM * random.symmetric();
            cloud.points.push_back(face.origin + u * eu + v * ev +
                                   kNoiseM * random.symmetric() * face.normal);
            cloud.normals.push_back(face.normal);
            cloud.intensities.push_back(face.intensity +
                                        0.05f * static_cast<float>(random.symmetric()));
        }
    }
}

scantling::PointCloud make_room() {
    const double x0 = -kLengthM / 2, y0 = -kWidthM / 2;
    const Eigen::Vector3d ex(kLengthM, 0, 0), ey(0, kWidthM, 0), ez(0, 0, kHeightM);
    const Face faces[] = {
        {{x0, y0, 0}, ex, ey, Eigen::Vector3d::UnitZ(), 0.3f},          // floor
        {{x0, y0, kHeightM}, ex, ey, -Eigen::Vector3d::UnitZ(), 0.8f},  // ceiling
        {{x0, y0, 0}, ex, ez, Eigen::Vector3d::UnitY(), 0.5f},          // wall y = -1.5
        {{x0, -y0, 0}, ex, ez, -Eigen::Vector3d::UnitY(), 0.5f},        // wall y = +1.5
        {{x0, y0, 0}, ey, ez, Eigen::Vector3d::UnitX(), 0.6f},          // wall x = -2
        {{-x0, y0, 0}, ey, ez, -Eigen::Vector3d::UnitX(), 0.6f},        // wall x = +2
    };
    Uniform random(kSeed);
    scantling::PointCloud cloud;
    for (const Face& face : faces) sample_face(face, random, cloud);
    return cloud;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: scantling_make_example_cloud OUT.pcd\n");
        return 2;
    }
    try {
        scantling::io::write_cloud(argv[1], make_room());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "scantling_make_example_cloud: error: %s\n", e.what());
        return 2;
    }
    return 0;
}
