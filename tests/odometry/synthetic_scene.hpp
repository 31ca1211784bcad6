#pragma once
// Analytic LiDAR sweeps of a room with pillars (axis-aligned boxes), for odometry tests that
// need exact geometry without the simulator (tests may not include sim: see tests/arch).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <scantling/core/point_cloud.hpp>
#include <scantling/core/random.hpp>
#include <vector>

namespace scantling::odometry::test {

struct Box {
    Eigen::Vector3d min;
    Eigen::Vector3d max;
};

/// Entry and exit distances of the ray o + t d through `box` (empty interval when it misses).
inline std::pair<double, double> slab(const Box& box, const Eigen::Vector3d& o,
                                      const Eigen::Vector3d& d) {
    double t0 = -std::numeric_limits<double>::infinity();
    double t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d(a)) < 1e-12) {
            if (o(a) < box.min(a) || o(a) > box.max(a)) return {1.0, 0.0};
            continue;
        }
        double ta = (box.min(a) - o(a)) / d(a);
        double tb = (box.max(a) - o(a)) / d(a);
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return {t0, t1};
}

/// A hall (seen from inside) with solid boxes (pillars, crates) inside it.
struct Scene {
    Box hall;
    std::vector<Box> solids;

    /// Distance along unit `d` from `o` to the first surface (inf when none).
    double cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d) const {
        double best = slab(hall, o, d).second;
        for (const Box& b : solids) {
            const auto [t0, t1] = slab(b, o, d);
            if (t0 <= t1 && t0 > 1e-6) best = std::min(best, t0);
        }
        return best;
    }
};

/// A 48 m x 30 m x 8 m hall with a grid of 0.6 m pillars and a few crates: plenty of vertical
/// edges in every direction.
inline Scene hall_scene() {
    Scene s;
    s.hall = {{-24, -15, 0}, {24, 15, 8}};
    for (int i = -3; i <= 3; ++i) {
        for (int j = -2; j <= 2; ++j) {
            if (j == 0) continue;  // the aisle the sensor drives along
            const Eigen::Vector3d c(6.5 * i + 0.7 * j, 5.0 * j, 0.0);
            s.solids.push_back(
                {c + Eigen::Vector3d(-0.3, -0.3, 0), c + Eigen::Vector3d(0.3, 0.3, 8)});
        }
    }
    s.solids.push_back({{-10, 2, 0}, {-8.5, 3.2, 1.5}});
    s.solids.push_back({{4, -3.5, 0}, {6, -2.4, 2.2}});
    s.solids.push_back({{12, 1.8, 0}, {13, 3, 3}});
    return s;
}

struct SweepSpec {
    int rings = 64;
    int columns = 1024;
    double min_elevation_deg = -25.0;
    double max_elevation_deg = 15.0;
    double noise_m = 0.01;
    double max_range_m = 100.0;
};

/// One sweep in the sensor frame, ring-major, with rings and per-column times (0.1 s sweep).
inline PointCloud scan(const Scene& scene, const Eigen::Isometry3d& T_world_sensor,
                       const SweepSpec& spec, Rng& rng) {
    PointCloud cloud;
    const double kPi = 3.14159265358979323846;
    for (int r = 0; r < spec.rings; ++r) {
        const double el =
            (spec.min_elevation_deg +
             (spec.max_elevation_deg - spec.min_elevation_deg) * r / std::max(1, spec.rings - 1)) *
            kPi / 180.0;
        for (int c = 0; c < spec.columns; ++c) {
            const double az = 2.0 * kPi * c / spec.columns - kPi;
            const Eigen::Vector3d d_s(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                      std::sin(el));
            const Eigen::Vector3d d_w = T_world_sensor.linear() * d_s;
            const double t = scene.cast(T_world_sensor.translation(), d_w);
            if (!std::isfinite(t) || t > spec.max_range_m) continue;
            const double range = t + spec.noise_m * rng.normal();
            cloud.points.push_back(range * d_s);
            cloud.rings.push_back(static_cast<std::uint16_t>(r));
            cloud.times_s.push_back(static_cast<float>(0.1 * c / spec.columns));
        }
    }
    return cloud;
}

}  // namespace scantling::odometry::test
