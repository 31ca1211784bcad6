#pragma once
// A synthetic corner of a stiffened bay for landmark tests (perception and localization):
// the bottom plate, a web frame and flat-bar longitudinals, sampled like a dense depth frame.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include <scantling/core/point_cloud.hpp>
#include <scantling/core/random.hpp>

namespace scantling::test_support {

inline constexpr double kBayStep_m = 0.01;

/// Samples the rectangle origin + [0, a]·u + [0, b]·v on a grid with Gaussian noise.
inline void add_rectangle(PointCloud& cloud, Rng& rng, const Eigen::Vector3d& origin,
                          const Eigen::Vector3d& u, double a, const Eigen::Vector3d& v, double b,
                          double noise_m) {
    for (double s = 0.0; s <= a; s += kBayStep_m) {
        for (double t = 0.0; t <= b; t += kBayStep_m) {
            const Eigen::Vector3d noise(rng.normal(), rng.normal(), rng.normal());
            cloud.points.push_back(origin + s * u + t * v + noise_m * noise);
        }
    }
}

/// The bottom plate (z = 0, x in [frame_x - 2, frame_x], y in [0, 2]), the web frame's face at
/// x = frame_x (up to z = 1.5) and flat-bar stiffeners on the bottom at the given y, `height_m`
/// high and 1 cm thick, running up to the frame. Landmarks: (frame_x, y_i, height_m).
inline PointCloud bay_corner(double frame_x, const std::vector<double>& stiffener_y,
                             double height_m, double noise_m, std::uint64_t seed) {
    PointCloud cloud;
    Rng rng(seed);
    const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(),
                          z = Eigen::Vector3d::UnitZ();
    add_rectangle(cloud, rng, {frame_x - 2.0, 0.0, 0.0}, x, 2.0, y, 2.0, noise_m);
    add_rectangle(cloud, rng, {frame_x, 0.0, 0.0}, y, 2.0, z, 1.5, noise_m);
    for (const double sy : stiffener_y) {
        add_rectangle(cloud, rng, {frame_x - 2.0, sy - 0.005, 0.0}, x, 2.0, z, height_m, noise_m);
        add_rectangle(cloud, rng, {frame_x - 2.0, sy + 0.005, 0.0}, x, 2.0, z, height_m, noise_m);
        add_rectangle(cloud, rng, {frame_x - 2.0, sy - 0.005, height_m}, x, 2.0, y, 0.01, noise_m);
    }
    return cloud;
}

}  // namespace scantling::test_support
