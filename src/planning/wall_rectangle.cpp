#include <scantling/planning/wall_rectangle.hpp>

#include <Eigen/Geometry>
#include <cmath>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::planning {
namespace {

// |n_z| above this is a floor or ceiling (~82° from vertical): "up" on it is ill-conditioned.
constexpr double kMaxNormalZ = 0.99;

void require_finite(const Eigen::Vector3d& v, std::string_view prefix, std::string_view field) {
    if (!v.allFinite()) {
        throw ConfigError(fmt::format("{}.{} = ({}, {}, {}), expected finite", prefix, field, v.x(),
                                      v.y(), v.z()));
    }
}

}  // namespace

void WallRectangle::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_finite(corner_world_m, prefix, "corner_world_m");
    require_finite(normal_world, prefix, "normal_world");
    const double norm = normal_world.norm();
    if (norm == 0.0 || std::abs(normal_world.z()) > kMaxNormalZ * norm) {
        throw ConfigError(fmt::format(
            "{}.normal_world = ({}, {}, {}), expected a non-zero normal with |n_z| <= {} |n| "
            "(a wall, not a floor or ceiling)",
            prefix, normal_world.x(), normal_world.y(), normal_world.z(), kMaxNormalZ));
    }
    require_positive(width_m, prefix, "width_m");
    require_positive(height_m, prefix, "height_m");
}

WallAxes wall_axes(const WallRectangle& rectangle) {
    const Eigen::Vector3d n = rectangle.normal_world.normalized();
    const Eigen::Vector3d up = (Eigen::Vector3d::UnitZ() - n.z() * n).normalized();
    return {up.cross(n), up, n};
}

Eigen::Vector3d point_in_front(const WallRectangle& rectangle, const WallAxes& axes, double a_m,
                               double b_m, double standoff_m) {
    return rectangle.corner_world_m + a_m * axes.right_world + b_m * axes.up_world +
           standoff_m * axes.normal_world;
}

}  // namespace scantling::planning
