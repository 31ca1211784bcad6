#include <scantling/core/error.hpp>
#include <scantling/sim/rov_dynamics.hpp>

#include "detail/sensor_checks.hpp"
#include "detail/vehicle_common.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace scantling::sim {
namespace {

// |1/τ_T − 1/τ_i| · dt below which the two poles are treated as one (double pole).
constexpr double kEqualPoles = 1e-8;
// Thrust pole of an immediate thruster (τ_T = 0).
constexpr double kNoThrustLag = std::numeric_limits<double>::infinity();

const RovDynamicsConfig& validated(const RovDynamicsConfig& config) {
    config.validate();
    return config;
}

/// One axis, one step of dt: closed-form solution of Ṫ = b (T_c − T), ν̇ = T − d ν.
/// b = +inf (τ_T = 0) means T = T_c throughout.
void axis_step(double& nu, double& thrust, double thrust_cmd, double d, double b, double dt) {
    const double nu_ss = thrust_cmd / d;
    const double e_d = std::exp(-d * dt);
    if (!std::isfinite(b)) {
        nu = nu_ss + (nu - nu_ss) * e_d;
        thrust = thrust_cmd;
        return;
    }
    const double e_b = std::exp(-b * dt);
    const double thrust_error = thrust - thrust_cmd;
    const double coupling = std::abs(d - b) * dt < kEqualPoles ? dt * e_d : (e_b - e_d) / (d - b);
    nu = nu_ss + (nu - nu_ss) * e_d + thrust_error * coupling;
    thrust = thrust_cmd + thrust_error * e_b;
}

}  // namespace

void RovDynamicsConfig::validate(std::string_view prefix) const {
    detail::require_step(prefix, dt_s);
    for (int i = 0; i < 4; ++i) {
        detail::require_positive(prefix, fmt::format("damping_time_constant_s[{}]", i),
                                 damping_time_constant_s[i]);
        detail::require_positive(prefix, fmt::format("max_command[{}]", i), max_command[i]);
    }
    detail::require_non_negative(prefix, "thrust_time_constant_s", thrust_time_constant_s);
    current.validate(detail::sub(prefix, "current"));
    if (pushes.size() > kMaxRovPushes) {
        throw ConfigError(fmt::format("{}.pushes: {} entries, expected at most {}", prefix,
                                      pushes.size(), kMaxRovPushes));
    }
    for (std::size_t i = 0; i < pushes.size(); ++i) {
        const std::string item = fmt::format("pushes[{}]", i);
        const RovPush& push = pushes[i];
        if (!(std::isfinite(push.start_s) && push.start_s >= 0.0)) {
            throw ConfigError(fmt::format("{}.{}.start_s = {}, expected finite >= 0", prefix, item,
                                          push.start_s));
        }
        detail::require_positive(prefix, item + ".duration_s", push.duration_s);
        if (!push.acceleration_world_mps2.allFinite()) {
            throw ConfigError(
                fmt::format("{}.{}.acceleration_world_mps2 is not finite", prefix, item));
        }
    }
}

RovDynamics::RovDynamics(const RovDynamicsConfig& config,
                         const Eigen::Isometry3d& T_world_body_start, std::uint64_t seed,
                         double start_s)
    : config_(validated(config)),
      current_(config_.current, Rng(seed).split(2).next_u64(), "rov.current"),
      start_s_(start_s) {
    if (!T_world_body_start.matrix().allFinite() || !std::isfinite(start_s)) {
        throw InputError("RovDynamics: start pose or start time is not finite");
    }
    yaw_rad_ = detail::yaw_of(T_world_body_start.linear());
    state_.stamp_s = start_s;
    state_.T_world_body.linear() =
        Eigen::AngleAxisd(yaw_rad_, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    state_.T_world_body.translation() = T_world_body_start.translation();
    state_.v_world_mps = world_velocity();
}

Eigen::Vector3d RovDynamics::world_velocity() const {
    return state_.T_world_body.linear() * nu_.head<3>() + current_.value();
}

void RovDynamics::add_pushes(double dt_s) {
    const double t0 = state_.stamp_s;
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(yaw_rad_, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    for (const RovPush& push : config_.pushes) {
        // The share of this step inside the push's window: its velocity change.
        const double overlap_s =
            std::min(t0 + dt_s, push.start_s + push.duration_s) - std::max(t0, push.start_s);
        if (overlap_s > 0.0)
            nu_.head<3>() += R.transpose() * push.acceleration_world_mps2 * overlap_s;
    }
}

const MotionState& RovDynamics::step(const RovCommand& command) {
    const Eigen::Vector4d raw(command.surge_mps, command.sway_mps, command.heave_mps,
                              command.yaw_rate_radps);
    if (!raw.allFinite()) throw InputError("RovDynamics::step: command is not finite");
    const double dt = config_.dt_s;
    const Eigen::Vector4d cmd = raw.cwiseMax(-config_.max_command).cwiseMin(config_.max_command);
    const double b =
        config_.thrust_time_constant_s > 0.0 ? 1.0 / config_.thrust_time_constant_s : kNoThrustLag;
    const Eigen::Vector3d v0 = state_.v_world_mps;
    const double r0 = nu_[3];
    for (int i = 0; i < 4; ++i) {
        const double d = 1.0 / config_.damping_time_constant_s[i];
        axis_step(nu_[i], thrust_[i], cmd[i] * d, d, b, dt);
    }
    add_pushes(dt);
    yaw_rad_ += 0.5 * (r0 + nu_[3]) * dt;
    current_.step(dt);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw_rad_, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = state_.T_world_body.translation();
    const Eigen::Vector3d v1 = T.linear() * nu_.head<3>() + current_.value();
    T.translation() += 0.5 * (v0 + v1) * dt;
    ++steps_;
    state_ = detail::next_state(state_, detail::stamp_at(start_s_, steps_, dt), T, v1, dt);
    return state_;
}

}  // namespace scantling::sim
