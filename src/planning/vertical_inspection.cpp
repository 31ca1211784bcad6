#include <scantling/planning/vertical_inspection.hpp>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>

#include "detail/stations.hpp"

namespace scantling::planning {

void VerticalInspectionConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_non_negative(standoff_m, prefix, "standoff_m");
    if (leg_spacing_m) require_positive(*leg_spacing_m, prefix, "leg_spacing_m");
    require_positive(waypoint_tolerance_m, prefix, "waypoint_tolerance_m");
}

WaypointPath plan_vertical_inspection(const WallRectangle& rectangle,
                                      const VerticalInspectionConfig& config) {
    config.validate("vertical_inspection");
    rectangle.validate("vertical_inspection.rectangle");
    const WallAxes axes = wall_axes(rectangle);
    const std::vector<double> legs =
        detail::even_stations(rectangle.width_m, config.leg_spacing_m.value_or(rectangle.width_m),
                              "vertical_inspection", "leg_spacing_m");
    const std::optional<double> yaw =
        config.face_wall ? std::optional<double>(yaw_facing(-axes.normal_world)) : std::nullopt;
    WaypointPath path;
    path.waypoints.reserve(2 * legs.size());
    bool up = true;
    for (const double a : legs) {  // left to right
        const double b_from = up ? 0.0 : rectangle.height_m;
        for (const double b : {b_from, rectangle.height_m - b_from}) {
            path.waypoints.push_back({point_in_front(rectangle, axes, a, b, config.standoff_m), yaw,
                                      config.waypoint_tolerance_m});
        }
        up = !up;
    }
    return path;
}

}  // namespace scantling::planning
