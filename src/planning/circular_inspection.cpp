#include <scantling/planning/circular_inspection.hpp>

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::planning {
namespace {

// More waypoints per turn than this is a mistake, refused before allocating.
constexpr std::size_t kMaxPointsPerTurn = 100000;

/// The ring at height z (N + 1 waypoints, facing the centre).
void append_ring(const CircleRequest& request, const CircularInspectionConfig& config, double z_m,
                 WaypointPath& path) {
    const double n = static_cast<double>(config.points_per_turn);
    const double direction = config.clockwise ? -1.0 : 1.0;
    for (std::size_t k = 0; k <= config.points_per_turn; ++k) {
        const double theta = config.start_angle_rad +
                             direction * 2.0 * std::numbers::pi * static_cast<double>(k) / n;
        const Eigen::Vector2d offset(std::cos(theta), std::sin(theta));
        const Eigen::Vector2d xy = request.centre_xy_world_m + request.radius_m * offset;
        path.waypoints.push_back({Eigen::Vector3d(xy.x(), xy.y(), z_m),
                                  yaw_facing(Eigen::Vector3d(-offset.x(), -offset.y(), 0.0)),
                                  config.waypoint_tolerance_m});
    }
}

}  // namespace

void CircleRequest::validate(std::string_view prefix) const {
    using namespace config_checks;
    if (!centre_xy_world_m.allFinite()) {
        throw ConfigError(fmt::format("{}.centre_xy_world_m = ({}, {}), expected finite", prefix,
                                      centre_xy_world_m.x(), centre_xy_world_m.y()));
    }
    require_positive(radius_m, prefix, "radius_m");
    if (heights_m.empty()) {
        throw ConfigError(
            fmt::format("{}.heights_m is empty, expected at least one height", prefix));
    }
    for (std::size_t i = 0; i < heights_m.size(); ++i) {
        require(std::isfinite(heights_m[i]), prefix, fmt::format("heights_m[{}]", i), heights_m[i],
                "finite");
    }
}

void CircularInspectionConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_count_at_least(points_per_turn, 3, prefix, "points_per_turn");
    require(points_per_turn <= kMaxPointsPerTurn, prefix, "points_per_turn",
            static_cast<double>(points_per_turn), fmt::format("<= {}", kMaxPointsPerTurn));
    require(std::isfinite(start_angle_rad), prefix, "start_angle_rad", start_angle_rad, "finite");
    require_positive(waypoint_tolerance_m, prefix, "waypoint_tolerance_m");
}

WaypointPath plan_circular_inspection(const CircleRequest& request,
                                      const CircularInspectionConfig& config) {
    config.validate("circular_inspection");
    request.validate("circular_inspection.request");
    WaypointPath path;
    path.waypoints.reserve(request.heights_m.size() * (config.points_per_turn + 1));
    for (const double z_m : request.heights_m) append_ring(request, config, z_m, path);
    return path;
}

}  // namespace scantling::planning
