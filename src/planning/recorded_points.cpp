#include <scantling/planning/recorded_points.hpp>

#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::planning {
namespace {

void require_finite_point(const Eigen::Vector3d& p, std::string_view what) {
    if (!p.allFinite()) {
        throw InputError(
            fmt::format("{} = ({}, {}, {}), expected finite", what, p.x(), p.y(), p.z()));
    }
}

}  // namespace

void RecordedPoints::record(const std::string& name, const RecordedPoint& point) {
    if (name.empty()) throw InputError("recorded point name is empty, expected a name");
    require_finite_point(point.p_world_m, fmt::format("recorded point '{}' p_world_m", name));
    if (point.yaw_rad && !std::isfinite(*point.yaw_rad)) {
        throw InputError(
            fmt::format("recorded point '{}' yaw_rad = {}, expected finite", name, *point.yaw_rad));
    }
    points_.insert_or_assign(name, point);
}

const RecordedPoint& RecordedPoints::at(std::string_view name) const {
    const auto it = points_.find(name);
    if (it == points_.end()) {
        throw InputError(
            fmt::format("recorded point '{}' is unknown (recorded: {})", name,
                        points_.empty() ? "none" : fmt::format("{}", fmt::join(names(), ", "))));
    }
    return it->second;
}

bool RecordedPoints::contains(std::string_view name) const { return points_.contains(name); }

std::vector<std::string> RecordedPoints::names() const {
    std::vector<std::string> result;
    result.reserve(points_.size());
    for (const auto& entry : points_) result.push_back(entry.first);
    return result;
}

void GoToConfig::validate(std::string_view prefix) const {
    config_checks::require_positive(waypoint_tolerance_m, prefix, "waypoint_tolerance_m");
}

WaypointPath plan_go_to_point(const RecordedPoints& points, std::string_view name,
                              const GoToConfig& config) {
    config.validate("go_to");
    const RecordedPoint& point = points.at(name);
    return WaypointPath{{Waypoint{point.p_world_m, point.yaw_rad, config.waypoint_tolerance_m}}};
}

WaypointPath plan_go_home(const Eigen::Vector3d& p_takeoff_world_m, const GoToConfig& config) {
    config.validate("go_home");
    require_finite_point(p_takeoff_world_m, "go_home take-off point p_world_m");
    return WaypointPath{{Waypoint{p_takeoff_world_m, std::nullopt, config.waypoint_tolerance_m}}};
}

}  // namespace scantling::planning
