#include <scantling/core/error.hpp>
#include <scantling/sim/mav_dynamics.hpp>

#include "detail/sensor_checks.hpp"
#include "detail/vehicle_common.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace scantling::sim {
namespace {

// Below this specific thrust (m/s²) the tilt is undefined (free fall): stay level.
constexpr double kMinThrustMps2 = 1e-6;

const MavDynamicsConfig& validated(const MavDynamicsConfig& config) {
    config.validate();
    return config;
}

std::uint64_t wind_seed(std::uint64_t seed) { return Rng(seed).split(1).next_u64(); }

}  // namespace

void MavDynamicsConfig::validate(std::string_view prefix) const {
    detail::require_step(prefix, dt_s);
    detail::require_positive(prefix, "velocity_time_constant_s", velocity_time_constant_s);
    detail::require_non_negative(prefix, "yaw_rate_time_constant_s", yaw_rate_time_constant_s);
    detail::require_positive(prefix, "max_speed_mps", max_speed_mps);
    detail::require_positive(prefix, "max_accel_mps2", max_accel_mps2);
    detail::require_positive(prefix, "max_yaw_rate_radps", max_yaw_rate_radps);
    detail::require_non_negative(prefix, "drag_coefficient_per_s", drag_coefficient_per_s);
    detail::require_non_negative(prefix, "attitude_time_constant_s", attitude_time_constant_s);
    detail::require_positive(prefix, "gravity_mps2", gravity_mps2);
    wind.validate(detail::sub(prefix, "wind"));
}

Eigen::Vector3d mav_steady_velocity_mps(const MavDynamicsConfig& config,
                                        const Eigen::Vector3d& v_cmd_world_mps,
                                        const Eigen::Vector3d& wind_world_mps) {
    const double c_tau = config.drag_coefficient_per_s * config.velocity_time_constant_s;
    const Eigen::Vector3d v_cmd = detail::clamp_norm(v_cmd_world_mps, config.max_speed_mps);
    return (v_cmd + c_tau * wind_world_mps) / (1.0 + c_tau);
}

MavDynamics::MavDynamics(const MavDynamicsConfig& config,
                         const Eigen::Isometry3d& T_world_body_start, std::uint64_t seed,
                         double start_s)
    : config_(validated(config)),
      wind_(config_.wind, wind_seed(seed), "mav.wind"),
      start_s_(start_s) {
    if (!T_world_body_start.matrix().allFinite() || !std::isfinite(start_s)) {
        throw InputError("MavDynamics: start pose or start time is not finite");
    }
    yaw_rad_ = detail::yaw_of(T_world_body_start.linear());
    state_.stamp_s = start_s;
    state_.T_world_body.linear() = attitude(thrust_dir_, yaw_rad_);
    state_.T_world_body.translation() = T_world_body_start.translation();
}

Eigen::Vector3d MavDynamics::next_velocity(const Eigen::Vector3d& v_cmd,
                                           const Eigen::Vector3d& wind) const {
    const double dt = config_.dt_s;
    const double tau = config_.velocity_time_constant_s;
    const double c = config_.drag_coefficient_per_s;
    const Eigen::Vector3d& v = state_.v_world_mps;
    const Eigen::Vector3d demand = (v_cmd - v) / tau;
    if (demand.norm() > config_.max_accel_mps2) {
        // Saturated loop: full authority towards the command, held over the step.
        const Eigen::Vector3d a_loop = demand.normalized() * config_.max_accel_mps2;
        return v + dt * (a_loop + c * (wind - v));
    }
    // Exact solution of the linear ODE: decays to v_ss at rate 1/τ + c.
    const double rate = 1.0 / tau + c;
    const Eigen::Vector3d v_ss = (v_cmd / tau + c * wind) / rate;
    return v_ss + (v - v_ss) * std::exp(-rate * dt);
}

Eigen::Matrix3d MavDynamics::attitude(const Eigen::Vector3d& z_b, double yaw_rad) const {
    const Eigen::Vector3d x_c(std::cos(yaw_rad), std::sin(yaw_rad), 0.0);
    Eigen::Vector3d y_b = z_b.cross(x_c);
    // Tilted by 90° towards the heading: fall back to the lateral axis of the heading.
    if (y_b.norm() < 1e-9) y_b = Eigen::Vector3d(-std::sin(yaw_rad), std::cos(yaw_rad), 0.0);
    y_b.normalize();
    Eigen::Matrix3d R;
    R << y_b.cross(z_b), y_b, z_b;
    return R;
}

void MavDynamics::advance_yaw(double yaw_rate_cmd_radps) {
    const double dt = config_.dt_s;
    const double tau = config_.yaw_rate_time_constant_s;
    const double r_cmd =
        std::clamp(yaw_rate_cmd_radps, -config_.max_yaw_rate_radps, config_.max_yaw_rate_radps);
    // Exact step mean of the lagged rate, so a lag-free yaw turns by r_cmd · dt.
    yaw_rad_ += (r_cmd + (yaw_rate_radps_ - r_cmd) * detail::lag_mean_fraction(dt, tau)) * dt;
    yaw_rate_radps_ += (r_cmd - yaw_rate_radps_) * detail::lag_fraction(dt, tau);
}

void MavDynamics::advance_tilt(const Eigen::Vector3d& thrust_mps2) {
    const double n = thrust_mps2.norm();
    if (n < kMinThrustMps2) return;
    const double lag = detail::lag_fraction(config_.dt_s, config_.attitude_time_constant_s);
    const Eigen::Vector3d blended = thrust_dir_ + lag * (thrust_mps2 / n - thrust_dir_);
    // A thrust flipping straight over can cancel the blend: jump to it instead.
    thrust_dir_ = blended.norm() > 1e-9 ? blended.normalized() : Eigen::Vector3d(thrust_mps2 / n);
}

const MotionState& MavDynamics::step(const MavCommand& command) {
    if (!command.v_world_mps.allFinite() || !std::isfinite(command.yaw_rate_radps)) {
        throw InputError("MavDynamics::step: command is not finite");
    }
    const double dt = config_.dt_s;
    const Eigen::Vector3d wind = wind_.value();
    const Eigen::Vector3d v_cmd = detail::clamp_norm(command.v_world_mps, config_.max_speed_mps);
    const Eigen::Vector3d v0 = state_.v_world_mps;
    const Eigen::Vector3d v1 = next_velocity(v_cmd, wind);
    advance_yaw(command.yaw_rate_radps);
    const Eigen::Vector3d a_drag = config_.drag_coefficient_per_s * (wind - 0.5 * (v0 + v1));
    advance_tilt((v1 - v0) / dt - a_drag + Eigen::Vector3d(0, 0, config_.gravity_mps2));
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = attitude(thrust_dir_, yaw_rad_);
    T.translation() = state_.T_world_body.translation() + 0.5 * (v0 + v1) * dt;
    ++steps_;
    state_ = detail::next_state(state_, detail::stamp_at(start_s_, steps_, dt), T, v1, dt);
    wind_.step(dt);
    return state_;
}

}  // namespace scantling::sim
