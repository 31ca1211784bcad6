#include <scantling/core/error.hpp>
#include <scantling/sim/legged_base.hpp>

#include "detail/sensor_checks.hpp"
#include "detail/vehicle_common.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

const LeggedBaseConfig& validated(const LeggedBaseConfig& config) {
    config.validate();
    return config;
}

}  // namespace

void LeggedBaseConfig::validate(std::string_view prefix) const {
    detail::require_step(prefix, dt_s);
    detail::require_positive(prefix, "velocity_time_constant_s", velocity_time_constant_s);
    detail::require_positive(prefix, "max_speed_mps", max_speed_mps);
    detail::require_positive(prefix, "max_accel_mps2", max_accel_mps2);
    detail::require_positive(prefix, "max_yaw_rate_radps", max_yaw_rate_radps);
    detail::require_non_negative(prefix, "bounce_amplitude_m", bounce_amplitude_m);
    detail::require_positive(prefix, "step_frequency_hz", step_frequency_hz);
}

LeggedBase::LeggedBase(const LeggedBaseConfig& config, const Eigen::Isometry3d& T_world_body_start,
                       double start_s)
    : config_(validated(config)), start_s_(start_s) {
    if (!T_world_body_start.matrix().allFinite() || !std::isfinite(start_s)) {
        throw InputError("LeggedBase: start pose or start time is not finite");
    }
    yaw_rad_ = detail::yaw_of(T_world_body_start.linear());
    z0_m_ = T_world_body_start.translation().z();
    state_.stamp_s = start_s;
    state_.T_world_body.linear() =
        Eigen::AngleAxisd(yaw_rad_, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    state_.T_world_body.translation() = T_world_body_start.translation();
}

Eigen::Vector2d LeggedBase::next_velocity(const Eigen::Vector2d& v_cmd) const {
    const double dt = config_.dt_s;
    const Eigen::Vector2d v = state_.v_world_mps.head<2>();
    const Eigen::Vector2d demand = (v_cmd - v) / config_.velocity_time_constant_s;
    if (demand.norm() > config_.max_accel_mps2) {
        return v + dt * config_.max_accel_mps2 * demand.normalized();
    }
    return v_cmd + (v - v_cmd) * std::exp(-dt / config_.velocity_time_constant_s);
}

void LeggedBase::advance_yaw(double yaw_rate_cmd_radps) {
    const double dt = config_.dt_s;
    const double tau = config_.velocity_time_constant_s;
    const double r_cmd =
        std::clamp(yaw_rate_cmd_radps, -config_.max_yaw_rate_radps, config_.max_yaw_rate_radps);
    yaw_rad_ += (r_cmd + (yaw_rate_radps_ - r_cmd) * detail::lag_mean_fraction(dt, tau)) * dt;
    yaw_rate_radps_ += (r_cmd - yaw_rate_radps_) * detail::lag_fraction(dt, tau);
}

Eigen::Vector2d LeggedBase::advance_bounce(double speed0_mps, double speed1_mps) {
    const LeggedBaseConfig& c = config_;
    const double w = 2.0 * std::numbers::pi * c.step_frequency_hz;
    const double s0 = std::min(1.0, speed0_mps / c.max_speed_mps);
    const double s1 = std::min(1.0, speed1_mps / c.max_speed_mps);
    phase_rad_ = std::fmod(phase_rad_ + w * c.dt_s, 2.0 * std::numbers::pi);
    const double sin_phase = std::sin(phase_rad_);
    const double ds = (s1 - s0) / c.dt_s;
    const double A = c.bounce_amplitude_m;
    return {A * s1 * sin_phase, A * (ds * sin_phase + s1 * w * std::cos(phase_rad_))};
}

const MotionState& LeggedBase::step(const LeggedCommand& command) {
    const Eigen::Vector3d raw(command.forward_mps, command.lateral_mps, command.yaw_rate_radps);
    if (!raw.allFinite()) throw InputError("LeggedBase::step: command is not finite");
    const double dt = config_.dt_s;
    const Eigen::Vector2d v_body =
        detail::clamp_norm(Eigen::Vector3d(raw.x(), raw.y(), 0.0), config_.max_speed_mps).head<2>();
    const Eigen::Vector2d v0 = state_.v_world_mps.head<2>();
    const Eigen::Vector2d v1 = next_velocity(Eigen::Rotation2Dd(yaw_rad_) * v_body);
    advance_yaw(raw.z());
    const Eigen::Vector2d bounce = advance_bounce(v0.norm(), v1.norm());
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw_rad_, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector2d p_xy = state_.T_world_body.translation().head<2>() + 0.5 * (v0 + v1) * dt;
    T.translation() << p_xy, z0_m_ + bounce.x();
    ++steps_;
    state_ = detail::next_state(state_, detail::stamp_at(start_s_, steps_, dt), T,
                                Eigen::Vector3d(v1.x(), v1.y(), bounce.y()), dt);
    return state_;
}

}  // namespace scantling::sim
