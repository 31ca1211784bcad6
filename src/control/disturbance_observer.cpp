// Wind compensation under the position loop (disturbance_observer.hpp).
#include <scantling/control/disturbance_observer.hpp>

#include <cmath>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::control {

void DisturbanceObserverConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(velocity_time_constant_s, prefix, "velocity_time_constant_s");
    require_positive(bandwidth_radps, prefix, "bandwidth_radps");
    require_non_negative(max_compensation_mps, prefix, "max_compensation_mps");
    require_positive(max_gap_s, prefix, "max_gap_s");
    require_non_negative(drag_coefficient_per_s, prefix, "drag_coefficient_per_s");
    require_positive(max_accel_mps2, prefix, "max_accel_mps2");
    // Below (1/τ + c)/2 the double pole needs L₁ < 0: the observer would undo the vehicle's
    // own damping.
    const double minimum = 0.5 * (1.0 / velocity_time_constant_s + drag_coefficient_per_s);
    if (bandwidth_radps < minimum) {
        throw ConfigError(
            fmt::format("{}.bandwidth_radps = {}, expected ≥ (1/velocity_time_constant_s + "
                        "drag_coefficient_per_s)/2 = {:.3f}",
                        prefix, bandwidth_radps, minimum));
    }
}

DisturbanceObserver::DisturbanceObserver(const DisturbanceObserverConfig& config)
    : config_((config.validate(), config)) {}

void DisturbanceObserver::reset() {
    v_hat_mps_.setZero();
    d_hat_mps2_.setZero();
    u_mps_.setZero();
    last_t_s_.reset();
}

void DisturbanceObserver::observe(const Eigen::Vector3d& v_world_mps, double t_s) {
    if (!v_world_mps.allFinite() || !std::isfinite(t_s)) {
        throw InputError(fmt::format(
            "disturbance_observer.observe: velocity ({}, {}, {}) at t = {}, expected finite",
            v_world_mps.x(), v_world_mps.y(), v_world_mps.z(), t_s));
    }
    const double dt = last_t_s_ ? t_s - *last_t_s_ : 0.0;
    if (last_t_s_ && dt <= 0.0) return;
    last_t_s_ = t_s;
    if (dt == 0.0 || dt > config_.max_gap_s) {
        v_hat_mps_ = v_world_mps;  // nothing to integrate over: start from the measurement
        return;
    }
    const double tau = config_.velocity_time_constant_s;
    const double c = config_.drag_coefficient_per_s;
    const double omega = config_.bandwidth_radps;
    const double l1 = 2.0 * omega - 1.0 / tau - c;
    Eigen::Vector3d a_loop = (u_mps_ - v_hat_mps_) / tau;
    if (a_loop.norm() > config_.max_accel_mps2) a_loop *= config_.max_accel_mps2 / a_loop.norm();
    const Eigen::Vector3d predicted = v_hat_mps_ + dt * (a_loop - c * v_hat_mps_ + d_hat_mps2_);
    const Eigen::Vector3d error = v_world_mps - predicted;
    v_hat_mps_ = predicted + dt * l1 * error;
    d_hat_mps2_ += dt * omega * omega * error;
}

Eigen::Vector3d DisturbanceObserver::compensation_mps(
    const Eigen::Vector3d& v_desired_world_mps) const {
    const double tau = config_.velocity_time_constant_s;
    const Eigen::Vector3d compensation =
        tau * (config_.drag_coefficient_per_s * v_desired_world_mps - d_hat_mps2_);
    const double norm = compensation.norm();
    const double limit = config_.max_compensation_mps;
    return norm > limit ? Eigen::Vector3d(compensation * (limit / norm)) : compensation;
}

Eigen::Vector3d DisturbanceObserver::command(const Eigen::Vector3d& v_desired_world_mps) {
    if (!v_desired_world_mps.allFinite()) {
        throw InputError(fmt::format(
            "disturbance_observer.command: desired velocity ({}, {}, {}), expected finite",
            v_desired_world_mps.x(), v_desired_world_mps.y(), v_desired_world_mps.z()));
    }
    u_mps_ = v_desired_world_mps + compensation_mps(v_desired_world_mps);
    return u_mps_;
}

}  // namespace scantling::control
