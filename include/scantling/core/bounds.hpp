#pragma once
/// @file Axis-aligned bounding boxes.

#include <Eigen/Core>
#include <limits>
#include <span>

namespace scantling {

/// Axis-aligned box; empty (min > max) until a point is added.
struct Aabb {
    Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

    bool empty() const { return (min.array() > max.array()).any(); }
    void extend(const Eigen::Vector3d& p) {
        min = min.cwiseMin(p);
        max = max.cwiseMax(p);
    }
    Eigen::Vector3d size() const {
        return empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(max - min);
    }
    Eigen::Vector3d center() const { return 0.5 * (min + max); }
};

/// Bounds of a set of points; empty box for an empty span.
Aabb compute_bounds(std::span<const Eigen::Vector3d> points);

}  // namespace scantling
