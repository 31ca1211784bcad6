#include <scantling/planning/hull_relative_adapter.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include <scantling/core/angles.hpp>
#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::planning {
namespace {

constexpr double kUnitTolerance = 1e-6;

Eigen::Vector2d horizontal(const Eigen::Vector3d& p) { return p.head<2>(); }

Eigen::Vector2d unit_at(double yaw_rad) { return {std::cos(yaw_rad), std::sin(yaw_rad)}; }

double angle_of(const Eigen::Vector2d& v) { return std::atan2(v.y(), v.x()); }

void require_finite(const Eigen::Vector3d& v, const char* field) {
    if (!v.allFinite()) {
        throw InputError(fmt::format("hull_adapter.adapt: {} = ({}, {}, {}), expected finite",
                                     field, v.x(), v.y(), v.z()));
    }
}

void check_observation(const HullLineObservation& o) {
    if (!o.point_world_m.allFinite() || !o.normal_world.allFinite() ||
        std::abs(o.normal_world.norm() - 1.0) > kUnitTolerance) {
        throw InputError(fmt::format(
            "hull_adapter.adapt: observation point ({}, {}) / normal ({}, {}), expected finite "
            "values and a unit normal",
            o.point_world_m.x(), o.point_world_m.y(), o.normal_world.x(), o.normal_world.y()));
    }
}

double clamp_abs(double value, double limit, bool& clamped) {
    if (std::abs(value) <= limit) return value;
    clamped = true;
    return std::copysign(limit, value);
}

}  // namespace

HullLineObservation hull_line_in_world(double distance_m, double angle_rad,
                                       const Eigen::Vector2d& p_sonar_world_m,
                                       double yaw_sonar_rad) {
    if (!std::isfinite(distance_m) || distance_m < 0.0 || !std::isfinite(angle_rad) ||
        !p_sonar_world_m.allFinite() || !std::isfinite(yaw_sonar_rad)) {
        throw InputError(fmt::format(
            "hull_line_in_world: distance {} m, angle {} rad, sonar ({}, {}) yaw {} rad: expected "
            "finite values and a distance >= 0",
            distance_m, angle_rad, p_sonar_world_m.x(), p_sonar_world_m.y(), yaw_sonar_rad));
    }
    const Eigen::Vector2d n = unit_at(yaw_sonar_rad + angle_rad);
    return {.point_world_m = p_sonar_world_m + distance_m * n, .normal_world = n};
}

void HullRelativeAdapterConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(stand_off_m, prefix, "stand_off_m");
    require(std::isfinite(gain) && gain > 0.0 && gain <= 1.0, prefix, "gain", gain, "in (0, 1]");
    require_positive(max_shift_per_scan_m, prefix, "max_shift_per_scan_m");
    require_positive(max_turn_per_scan_rad, prefix, "max_turn_per_scan_rad");
}

HullRelativeAdapter::HullRelativeAdapter(WaypointPath path, const HullRelativeAdapterConfig& config)
    : path_(std::move(path)), config_(config) {
    config_.validate();
    validate(path_);
    for (std::size_t i = 0; i < path_.waypoints.size(); ++i) {
        if (!path_.waypoints[i].yaw_rad) {
            throw ConfigError(fmt::format(
                "path.waypoints[{}].yaw_rad is missing: the hull adapter needs the heading that "
                "faces the hull at every waypoint",
                i));
        }
    }
}

Eigen::Vector2d HullRelativeAdapter::pivot(const Eigen::Vector3d& p_vehicle_world_m,
                                           std::size_t next_index) const {
    const Waypoint& next = path_.waypoints[next_index];
    const Eigen::Vector2d along = unit_at(*next.yaw_rad + std::numbers::pi / 2.0);
    const Eigen::Vector2d w = horizontal(next.p_world_m);
    return w + along * (horizontal(p_vehicle_world_m) - w).dot(along);
}

AdaptationStep HullRelativeAdapter::adapt(const HullLineObservation& observation,
                                          const Eigen::Vector3d& p_vehicle_world_m,
                                          std::size_t next_index) {
    check_observation(observation);
    require_finite(p_vehicle_world_m, "p_vehicle_world_m");
    const Eigen::Vector2d& n = observation.normal_world;
    const Eigen::Vector2d& q = observation.point_world_m;
    AdaptationStep step;
    step.stand_off_measured_m = n.dot(q - horizontal(p_vehicle_world_m));
    if (next_index >= path_.waypoints.size()) return step;

    const double expected_rad = *path_.waypoints[next_index].yaw_rad;
    step.turn_rad = clamp_abs(config_.gain * wrap_angle_rad(angle_of(n) - expected_rad),
                              config_.max_turn_per_scan_rad, step.clamped);
    // The pivot does not move under the turn, so the shift is measured there.
    const Eigen::Vector2d c = pivot(p_vehicle_world_m, next_index);
    const double k = -config_.stand_off_m - n.dot(c - q);
    step.shift_m = clamp_abs(config_.gain * k, config_.max_shift_per_scan_m, step.clamped);

    const Eigen::Rotation2Dd turn(step.turn_rad);
    for (std::size_t i = next_index; i < path_.waypoints.size(); ++i) {
        Waypoint& w = path_.waypoints[i];
        const Eigen::Vector2d moved = c + turn * (horizontal(w.p_world_m) - c) + step.shift_m * n;
        w.p_world_m.head<2>() = moved;
        w.yaw_rad = wrap_angle_rad(*w.yaw_rad + step.turn_rad);
        ++step.waypoints_moved;
    }
    return step;
}

}  // namespace scantling::planning
