#pragma once
// Small helpers of the surface planners (surface_rectangle.cpp, surface_tasks.cpp, detour.cpp),
// written once.

#include <Eigen/Core>
#include <string>

#include <fmt/format.h>

namespace scantling::planning::detail {

/// `v` with its part along the unit `normal` removed: a direction on the surface.
inline Eigen::Vector3d tangent(const Eigen::Vector3d& v, const Eigen::Vector3d& normal) {
    return v - v.dot(normal) * normal;
}

/// "(x, y, z)" to the millimetre, for error messages.
inline std::string point_text(const Eigen::Vector3d& p) {
    return fmt::format("({:.3f}, {:.3f}, {:.3f})", p.x(), p.y(), p.z());
}

}  // namespace scantling::planning::detail
