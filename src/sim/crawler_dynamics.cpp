#include <scantling/core/error.hpp>
#include <scantling/sim/crawler_dynamics.hpp>

#include "detail/sensor_checks.hpp"
#include "detail/vehicle_common.hpp"

#include <algorithm>
#include <cmath>

namespace scantling::sim {
namespace {

const CrawlerDynamicsConfig& validated(const CrawlerDynamicsConfig& config) {
    config.validate();
    return config;
}

GustConfig slip_config(const CrawlerDynamicsConfig& c) {
    return {Eigen::Vector3d(c.slip_mean, 0.0, 0.0),
            Eigen::Vector3d(c.slip_sigma, c.lateral_slip_sigma, c.yaw_slip_sigma),
            c.slip_correlation_time_s};
}

Eigen::Matrix3d yaw_rotation(double angle_rad) {
    return Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

}  // namespace

void CrawlerDynamicsConfig::validate(std::string_view prefix) const {
    detail::require_step(prefix, dt_s);
    detail::require_non_negative(prefix, "velocity_time_constant_s", velocity_time_constant_s);
    detail::require_positive(prefix, "max_speed_mps", max_speed_mps);
    detail::require_positive(prefix, "max_yaw_rate_radps", max_yaw_rate_radps);
    detail::require(slip_mean >= 0.0 && slip_mean < 1.0, prefix, "slip_mean", slip_mean,
                    "in [0, 1)");
    detail::require_non_negative(prefix, "slip_sigma", slip_sigma);
    detail::require_non_negative(prefix, "lateral_slip_sigma", lateral_slip_sigma);
    detail::require_non_negative(prefix, "yaw_slip_sigma", yaw_slip_sigma);
    detail::require_positive(prefix, "slip_correlation_time_s", slip_correlation_time_s);
}

CrawlerDynamics::CrawlerDynamics(const CrawlerDynamicsConfig& config,
                                 const SurfaceProjector& surface,
                                 const Eigen::Isometry3d& T_world_body_start, std::uint64_t seed,
                                 double start_s)
    : config_(validated(config)),
      surface_(&surface),
      slip_(slip_config(config_), Rng(seed).split(3).next_u64(), "crawler.slip"),
      start_s_(start_s) {
    if (!T_world_body_start.matrix().allFinite() || !std::isfinite(start_s)) {
        throw InputError("CrawlerDynamics: start pose or start time is not finite");
    }
    state_.stamp_s = start_s;
    state_.T_world_body =
        settle(T_world_body_start.translation(), T_world_body_start.linear().col(0));
}

Eigen::Isometry3d CrawlerDynamics::settle(const Eigen::Vector3d& p,
                                          const Eigen::Vector3d& heading) const {
    const SurfacePoint s = surface_->project(p);
    const Eigen::Vector3d& z = s.normal;
    Eigen::Vector3d x = heading - z * z.dot(heading);
    if (x.norm() < 1e-9) {  // heading along the normal: any tangent will do
        x = z.unitOrthogonal();
    }
    x.normalize();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() << x, z.cross(x), z;
    T.translation() = s.point;
    return T;
}

Eigen::Vector3d CrawlerDynamics::slip_velocity_body(double wheel_v) const {
    const Eigen::Vector3d slip = slip_.value();
    return {wheel_v * (1.0 - slip.x()), std::abs(wheel_v) * slip.y(), 0.0};
}

const MotionState& CrawlerDynamics::step(const CrawlerCommand& command) {
    if (!std::isfinite(command.v_mps) || !std::isfinite(command.yaw_rate_radps)) {
        throw InputError("CrawlerDynamics::step: command is not finite");
    }
    const double dt = config_.dt_s;
    const double lag = detail::lag_fraction(dt, config_.velocity_time_constant_s);
    const double v_cmd = std::clamp(command.v_mps, -config_.max_speed_mps, config_.max_speed_mps);
    const double w_cmd =
        std::clamp(command.yaw_rate_radps, -config_.max_yaw_rate_radps, config_.max_yaw_rate_radps);
    // Exact step means of the lagged wheel speeds (the motion over the step).
    const double mean = detail::lag_mean_fraction(dt, config_.velocity_time_constant_s);
    const double v_mean = v_cmd + mean * (wheel_v_mps_ - v_cmd);
    const double w_mean = w_cmd + mean * (wheel_w_radps_ - w_cmd);
    wheel_v_mps_ += lag * (v_cmd - wheel_v_mps_);
    wheel_w_radps_ += lag * (w_cmd - wheel_w_radps_);
    wheel_distance_m_ += v_mean * dt;

    const Eigen::Matrix3d& R = state_.T_world_body.linear();
    const double turn_rad = w_mean * (1.0 + slip_.value().z()) * dt;
    const Eigen::Vector3d move = R * yaw_rotation(0.5 * turn_rad) * slip_velocity_body(v_mean);
    const Eigen::Vector3d heading = R * yaw_rotation(turn_rad).col(0);
    const Eigen::Isometry3d T = settle(state_.T_world_body.translation() + move * dt, heading);
    slip_.step(dt);
    const Eigen::Vector3d v_world = T.linear() * slip_velocity_body(wheel_v_mps_);
    ++steps_;
    state_ = detail::next_state(state_, detail::stamp_at(start_s_, steps_, dt), T, v_world, dt);
    state_.wheel_forward_mps = wheel_v_mps_;
    state_.wheel_yaw_rate_radps = wheel_w_radps_;
    return state_;
}

}  // namespace scantling::sim
