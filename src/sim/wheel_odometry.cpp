#include <scantling/sim/wheel_odometry.hpp>

#include "detail/motion_checks.hpp"
#include "detail/sensor_checks.hpp"

#include <cmath>

namespace scantling::sim {

void WheelOdometryConfig::validate(std::string_view prefix) const {
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require_non_negative(prefix, "speed_noise_fraction", speed_noise_fraction);
    detail::require_non_negative(prefix, "speed_noise_mps", speed_noise_mps);
    detail::require_non_negative(prefix, "yaw_rate_noise_fraction", yaw_rate_noise_fraction);
    detail::require_non_negative(prefix, "yaw_rate_noise_radps", yaw_rate_noise_radps);
    detail::require(
        std::isfinite(scale_error_sigma) && scale_error_sigma >= 0.0 && scale_error_sigma < 0.2,
        prefix, "scale_error_sigma", scale_error_sigma, "in [0, 0.2)");
    detail::require_non_negative(prefix, "slip_event_rate_per_s", slip_event_rate_per_s);
    detail::require_non_negative(prefix, "slip_event_duration_s", slip_event_duration_s);
    detail::require_non_negative(prefix, "slip_max_speed_excess", slip_max_speed_excess);
    detail::require_non_negative(prefix, "slip_yaw_rate_sigma_radps", slip_yaw_rate_sigma_radps);
}

WheelOdometryConfig noiseless(WheelOdometryConfig config) {
    config.speed_noise_fraction = config.speed_noise_mps = 0.0;
    config.yaw_rate_noise_fraction = config.yaw_rate_noise_radps = 0.0;
    config.scale_error_sigma = 0.0;
    config.slip_event_rate_per_s = 0.0;
    return config;
}

Eigen::Isometry3d integrate_unicycle(const Eigen::Isometry3d& T_odom_body, double forward_speed_mps,
                                     double yaw_rate_radps, double dt_s) {
    const double dyaw_rad = yaw_rate_radps * dt_s;
    const double ds_m = forward_speed_mps * dt_s;
    // Chord of the arc: length 2 r sin(θ/2) at half the heading change (sinc form near θ = 0).
    const double half = 0.5 * dyaw_rad;
    const double chord_m = std::abs(half) < 1e-9 ? ds_m : ds_m * std::sin(half) / half;
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    step.translation() = Eigen::Vector3d(chord_m * std::cos(half), chord_m * std::sin(half), 0.0);
    step.linear() = Eigen::AngleAxisd(dyaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T_odom_body * step;
}

WheelOdometrySimulator::WheelOdometrySimulator(WheelOdometryConfig config, Rng& rng)
    : config_(config) {
    config_.validate();
    scale_error_ = rng.normal(0.0, config_.scale_error_sigma);
}

void WheelOdometrySimulator::update_slip(double stamp_s, Rng& rng) {
    const double dt_s = started_ ? stamp_s - previous_stamp_s_ : 0.0;
    const double start_u = rng.uniform();
    const double excess = config_.slip_max_speed_excess * rng.uniform();
    const double yaw_rate_radps = rng.normal(0.0, config_.slip_yaw_rate_sigma_radps);
    const bool in_slip = stamp_s < slip_until_s_;
    if (!in_slip && start_u < 1.0 - std::exp(-config_.slip_event_rate_per_s * dt_s)) {
        slip_until_s_ = stamp_s + config_.slip_event_duration_s;
        slip_ = excess;
        slip_yaw_rate_radps_ = yaw_rate_radps;
    }
    if (stamp_s >= slip_until_s_) slip_ = slip_yaw_rate_radps_ = 0.0;
}

WheelOdometrySample WheelOdometrySimulator::measure(const MotionState& truth, Rng& rng) {
    detail::check_motion(truth, "wheel_odometry");
    if (started_) detail::check_stamp_order(truth.stamp_s, previous_stamp_s_, "wheel_odometry");
    update_slip(truth.stamp_s, rng);
    started_ = true;
    previous_stamp_s_ = truth.stamp_s;

    // A crawler's encoders count the wheels' turns: the slip is what odometry does not see.
    const double v_mps = truth.wheel_forward_mps.value_or(
        (truth.T_world_body.linear().transpose() * truth.v_world_mps).x());
    const double omega_radps = truth.wheel_yaw_rate_radps.value_or(truth.omega_body_radps.z());
    const double speed_factor = 1.0 + slip_ + rng.normal(0.0, config_.speed_noise_fraction);
    const double speed_noise = rng.normal(0.0, config_.speed_noise_mps);
    const double rate_factor = 1.0 + rng.normal(0.0, config_.yaw_rate_noise_fraction);
    const double rate_noise = rng.normal(0.0, config_.yaw_rate_noise_radps);

    WheelOdometrySample sample;
    sample.stamp_s = truth.stamp_s;
    sample.forward_speed_mps = (1.0 + scale_error_) * v_mps * speed_factor + speed_noise;
    sample.yaw_rate_radps = omega_radps * rate_factor + slip_yaw_rate_radps_ + rate_noise;
    sample.slipping = truth.stamp_s < slip_until_s_;
    return sample;
}

}  // namespace scantling::sim
