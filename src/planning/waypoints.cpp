#include <scantling/planning/waypoints.hpp>

#include <cmath>
#include <string>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::planning {

double yaw_facing(const Eigen::Vector3d& direction_world) {
    return std::atan2(direction_world.y(), direction_world.x());
}

void validate(const WaypointPath& path, std::string_view prefix) {
    using namespace config_checks;
    for (std::size_t i = 0; i < path.waypoints.size(); ++i) {
        const Waypoint& wp = path.waypoints[i];
        const std::string name = fmt::format("{}.waypoints[{}]", prefix, i);
        if (!wp.p_world_m.allFinite()) {
            throw ConfigError(fmt::format("{}.p_world_m = ({}, {}, {}), expected finite", name,
                                          wp.p_world_m.x(), wp.p_world_m.y(), wp.p_world_m.z()));
        }
        if (wp.yaw_rad) require(std::isfinite(*wp.yaw_rad), name, "yaw_rad", *wp.yaw_rad, "finite");
        require_positive(wp.tolerance_m, name, "tolerance_m");
    }
}

}  // namespace scantling::planning
