#pragma once
// Clouds shared by the collision-prevention tests (body frame, metres).
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <scantling/core/point_cloud.hpp>

namespace scantling::safety::test {

using Eigen::Vector3d;
inline double deg(double degrees) { return degrees * std::numbers::pi / 180.0; }

inline PointCloud cloud_of(std::vector<Vector3d> points) {
    PointCloud cloud;
    cloud.points = std::move(points);
    return cloud;
}

/// A point at `range_m` whose angles off the x axis are atan(y/x) = h and atan(z/x) = v.
inline Vector3d off_axis(double range_m, double h_deg, double v_deg) {
    return Vector3d(1.0, std::tan(deg(h_deg)), std::tan(deg(v_deg))).normalized() * range_m;
}

/// The walls of a box of half-size `half_m` centred on the body, sampled symmetrically.
inline PointCloud box_walls(double half_m, int per_side) {
    std::vector<Vector3d> points;
    for (int i = 0; i < per_side; ++i) {
        for (int j = 0; j < per_side; ++j) {
            const double a = half_m * (2.0 * (i + 0.5) / per_side - 1.0);
            const double b = half_m * (2.0 * (j + 0.5) / per_side - 1.0);
            for (const double s : {-half_m, half_m}) {
                points.emplace_back(s, a, b);
                points.emplace_back(a, s, b);
                points.emplace_back(a, b, s);
            }
        }
    }
    return cloud_of(std::move(points));
}

/// Points of the plane n·p = distance_m, a `half_m` square around its foot point, 5 cm apart.
inline PointCloud plane_patch(const Vector3d& n, double distance_m, double half_m) {
    const Vector3d a = n.unitOrthogonal(), b = n.cross(a);
    std::vector<Vector3d> points;
    const int steps = static_cast<int>(half_m / 0.05);
    for (int i = -steps; i <= steps; ++i) {
        for (int j = -steps; j <= steps; ++j) {
            points.push_back(distance_m * n + 0.05 * i * a + 0.05 * j * b);
        }
    }
    return cloud_of(std::move(points));
}

}  // namespace scantling::safety::test
