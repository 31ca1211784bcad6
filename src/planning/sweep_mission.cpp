#include <scantling/planning/sweep_mission.hpp>

#include <string>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>

#include "detail/stations.hpp"

namespace scantling::planning {

void SweepConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_non_negative(standoff_m, prefix, "standoff_m");
    require_positive(line_spacing_m, prefix, "line_spacing_m");
    require_positive(waypoint_tolerance_m, prefix, "waypoint_tolerance_m");
}

WaypointPath plan_sweep(const WallRectangle& rectangle, const SweepConfig& config) {
    config.validate("sweep");
    rectangle.validate("sweep.rectangle");
    const WallAxes axes = wall_axes(rectangle);
    const std::vector<double> rows =
        detail::even_stations(rectangle.height_m, config.line_spacing_m, "sweep", "line_spacing_m");
    const std::optional<double> yaw =
        config.face_wall ? std::optional<double>(yaw_facing(-axes.normal_world)) : std::nullopt;
    WaypointPath path;
    path.waypoints.reserve(2 * rows.size());
    bool left_to_right = true;
    for (auto row = rows.rbegin(); row != rows.rend(); ++row) {  // top to bottom
        const double a_from = left_to_right ? 0.0 : rectangle.width_m;
        for (const double a : {a_from, rectangle.width_m - a_from}) {
            path.waypoints.push_back({point_in_front(rectangle, axes, a, *row, config.standoff_m),
                                      yaw, config.waypoint_tolerance_m});
        }
        left_to_right = !left_to_right;
    }
    return path;
}

}  // namespace scantling::planning
