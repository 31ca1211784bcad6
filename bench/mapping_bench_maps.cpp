// Synthetic maps for the hashed-cell-map benchmark: realistic coordinate distributions (long
// thin structures over a large area, or a small dense box), not realistic sensing.
#include <cmath>

#include <scantling/core/random.hpp>

#include "mapping_bench.hpp"

namespace scantling::bench {
namespace {

constexpr double kTownHalfM = 500.0;
constexpr double kBlockM = 100.0;
constexpr double kFacadeOffsetM = 12.0;
constexpr double kSurfaceNoiseM = 0.02;

/// Points of one 100 m road segment along x (or along y when `along_y`), at road line `c`.
std::vector<Eigen::Vector3d> road_segment(Rng& rng, double c, double s0, bool along_y) {
    std::vector<Eigen::Vector3d> pts;
    const auto put = [&](double along, double across, double z) {
        across += c;
        pts.push_back(along_y ? Eigen::Vector3d(across, along, z)
                              : Eigen::Vector3d(along, across, z));
    };
    for (const double side : {-1.0, 1.0}) {
        const double height_m = rng.uniform(5.0, 30.0);
        for (int i = 0; i < 4000; ++i) {
            put(rng.uniform(s0, s0 + kBlockM),
                side * kFacadeOffsetM + rng.normal(0.0, kSurfaceNoiseM),
                rng.uniform(0.0, height_m));
        }
    }
    for (int i = 0; i < 2000; ++i) {
        put(rng.uniform(s0, s0 + kBlockM), rng.uniform(-kFacadeOffsetM, kFacadeOffsetM),
            rng.normal(0.0, kSurfaceNoiseM));
    }
    for (int pole = 0; pole < 5; ++pole) {
        const double across = pole % 2 == 0 ? -10.0 : 10.0;
        for (int i = 0; i < 100; ++i) put(s0 + 20.0 * pole + 10.0, across, rng.uniform(0.0, 8.0));
    }
    return pts;
}

}  // namespace

Batches road_network_map(std::uint64_t seed) {
    Rng rng(seed);
    Batches batches;
    const int lines = static_cast<int>(2 * kTownHalfM / kBlockM) + 1;
    for (const bool along_y : {false, true}) {
        for (int line = 0; line < lines; ++line) {
            for (int seg = 0; seg + 1 < lines; ++seg) {
                batches.push_back(road_segment(rng, -kTownHalfM + kBlockM * line,
                                               -kTownHalfM + kBlockM * seg, along_y));
            }
        }
    }
    return batches;
}

Batches ballast_tank_map(std::uint64_t seed) {
    constexpr double kHx = 6.0, kHy = 4.0, kHz = 2.0;  // half extents, metres
    Rng rng(seed);
    std::vector<Eigen::Vector3d> pts;
    const auto noise = [&] { return rng.normal(0.0, 0.005); };
    for (int i = 0; i < 300000;
         ++i) {  // shell: the x, y and z faces in turn, either side at random
        Eigen::Vector3d p(rng.uniform(-kHx, kHx), rng.uniform(-kHy, kHy), rng.uniform(-kHz, kHz));
        const int axis = i % 3;
        p[axis] = (rng.uniform() < 0.5 ? -1.0 : 1.0) * (axis == 0   ? kHx
                                                        : axis == 1 ? kHy
                                                                    : kHz) +
                  noise();
        pts.push_back(p);
    }
    for (int i = 0; i < 150000; ++i) {  // web frames every 0.8 m, elliptic 0.6 x 0.8 m manholes
        const double x = -kHx + 0.8 * static_cast<double>(1 + rng.uniform_index(14));
        const double y = rng.uniform(-kHy, kHy);
        const double z = rng.uniform(-kHz, kHz);
        if (std::pow(y / 0.3, 2) + std::pow(z / 0.4, 2) < 1.0) continue;
        pts.emplace_back(x + noise(), y, z);
    }
    for (int i = 0; i < 50000; ++i) {  // longitudinal stiffeners on both sides every 0.6 m
        const double z = -kHz + 0.6 * static_cast<double>(1 + rng.uniform_index(6));
        const double y = (rng.uniform() < 0.5 ? -1.0 : 1.0) * (kHy - 0.15);
        pts.emplace_back(rng.uniform(-kHx, kHx), y + noise(), z + noise());
    }
    Batches batches;
    constexpr std::size_t kBatch = 20000;
    for (std::size_t b = 0; b < pts.size(); b += kBatch) {
        batches.emplace_back(
            pts.begin() + static_cast<std::ptrdiff_t>(b),
            pts.begin() + static_cast<std::ptrdiff_t>(std::min(b + kBatch, pts.size())));
    }
    return batches;
}

}  // namespace scantling::bench
