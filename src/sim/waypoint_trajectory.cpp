#include <scantling/core/error.hpp>
#include <scantling/sim/waypoint_trajectory.hpp>

#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace scantling::sim {
namespace {

// Horizontal leg length below which kFaceTravel keeps the heading (a vertical climb).
constexpr double kVerticalLegM = 1e-6;

/// The larger of rate / limit for two quantities moving together: normalised limit of σ.
double normalised_limit(double distance, double limit, double angle, double angle_limit) {
    double sigma_limit = std::numeric_limits<double>::infinity();
    if (distance > 0.0) sigma_limit = limit / distance;
    if (angle > 0.0) sigma_limit = std::min(sigma_limit, angle_limit / angle);
    return sigma_limit;
}

void validate_waypoint(const Waypoint& w, const std::string& prefix) {
    if (!w.position_m.allFinite()) {
        throw ConfigError(fmt::format("{}.position_m = ({}, {}, {}), expected finite", prefix,
                                      w.position_m.x(), w.position_m.y(), w.position_m.z()));
    }
    detail::require(std::isfinite(w.yaw_rad), prefix, "yaw_rad", w.yaw_rad, "finite");
    detail::require_non_negative(prefix, "dwell_s", w.dwell_s);
}

}  // namespace

void WaypointTrajectoryConfig::validate(std::string_view prefix) const {
    detail::require(!waypoints.empty(), prefix, "waypoints", 0.0, ">= 1 waypoint");
    for (std::size_t i = 0; i < waypoints.size(); ++i) {
        validate_waypoint(waypoints[i], fmt::format("{}.waypoints[{}]", prefix, i));
    }
    detail::require_positive(prefix, "max_speed_mps", max_speed_mps);
    detail::require_positive(prefix, "max_accel_mps2", max_accel_mps2);
    detail::require_positive(prefix, "max_yaw_rate_radps", max_yaw_rate_radps);
    detail::require_positive(prefix, "max_yaw_accel_radps2", max_yaw_accel_radps2);
}

WaypointTrajectory::WaypointTrajectory(WaypointTrajectoryConfig config)
    : config_(std::move(config)) {
    config_.validate();
    const auto& wps = config_.waypoints;
    double yaw = wps.front().yaw_rad;
    arrival_s_.push_back(0.0);
    add_dwell(wps.front().position_m, yaw, wps.front().dwell_s);
    for (std::size_t i = 1; i < wps.size(); ++i) {
        const Eigen::Vector3d& p0 = wps[i - 1].position_m;
        const Eigen::Vector3d& p1 = wps[i].position_m;
        if (config_.yaw_mode == YawMode::kFaceTravel) {
            const Eigen::Vector3d d = p1 - p0;
            const double heading =
                d.head<2>().norm() > kVerticalLegM ? std::atan2(d.y(), d.x()) : yaw;
            add_motion(p0, p0, yaw, heading);  // turn on the spot
            yaw = heading;
            add_motion(p0, p1, yaw, yaw);
        } else {
            add_motion(p0, p1, yaw, wps[i].yaw_rad);
            yaw = wps[i].yaw_rad;
        }
        arrival_s_.push_back(end_time_s());
        add_dwell(p1, yaw, wps[i].dwell_s);
    }
}

double WaypointTrajectory::end_time_s() const {
    return legs_.empty() ? 0.0 : legs_.back().start_s + legs_.back().duration_s;
}

void WaypointTrajectory::add_motion(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                    double yaw0, double yaw1) {
    Leg leg;
    leg.start_s = end_time_s();
    leg.p0 = p0;
    leg.dp = p1 - p0;
    leg.yaw0_rad = yaw0;
    leg.dyaw_rad = wrap_angle(yaw1 - yaw0);
    const double distance = leg.dp.norm();
    const double angle = std::abs(leg.dyaw_rad);
    if (distance == 0.0 && angle == 0.0) return;
    const double v =
        normalised_limit(distance, config_.max_speed_mps, angle, config_.max_yaw_rate_radps);
    const double a =
        normalised_limit(distance, config_.max_accel_mps2, angle, config_.max_yaw_accel_radps2);
    leg.sigma = plan_rest_to_rest(1.0, v, a, config_.shape);
    leg.duration_s = leg.sigma.duration_s();
    legs_.push_back(leg);
}

void WaypointTrajectory::add_dwell(const Eigen::Vector3d& p, double yaw, double dwell_s) {
    if (dwell_s <= 0.0) return;
    Leg leg;
    leg.start_s = end_time_s();
    leg.duration_s = dwell_s;
    leg.p0 = p;
    leg.yaw0_rad = yaw;
    legs_.push_back(leg);
}

double WaypointTrajectory::duration_s() const { return end_time_s(); }

double WaypointTrajectory::arrival_time_s(std::size_t i) const {
    if (i >= arrival_s_.size()) {
        throw InputError(fmt::format("WaypointTrajectory::arrival_time_s: waypoint {} of {}", i,
                                     arrival_s_.size()));
    }
    return arrival_s_[i];
}

MotionState WaypointTrajectory::at(double t_s) const {
    if (legs_.empty()) {  // one waypoint, no dwell: at rest forever
        const Waypoint& w = config_.waypoints.front();
        const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
        return level_state(t_s, w.position_m, zero, zero, w.yaw_rad, 0.0);
    }
    const auto after = std::upper_bound(legs_.begin(), legs_.end(), t_s,
                                        [](double t, const Leg& leg) { return t < leg.start_s; });
    const Leg& leg = after == legs_.begin() ? legs_.front() : *(after - 1);
    const ProfileSample s = sample(leg.sigma, t_s - leg.start_s);
    return level_state(t_s, leg.p0 + leg.dp * s.s, leg.dp * s.ds, leg.dp * s.dds,
                       leg.yaw0_rad + leg.dyaw_rad * s.s, leg.dyaw_rad * s.ds);
}

}  // namespace scantling::sim
