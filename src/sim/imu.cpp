#include <scantling/sim/imu.hpp>

#include <scantling/sim/sensor_mount.hpp>

#include "detail/motion_checks.hpp"
#include "detail/sensor_checks.hpp"

#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

}  // namespace

void ImuConfig::validate(std::string_view prefix) const {
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require_non_negative(prefix, "gyro_noise_density_radps_per_sqrt_hz",
                                 gyro_noise_density_radps_per_sqrt_hz);
    detail::require_non_negative(prefix, "accel_noise_density_mps2_per_sqrt_hz",
                                 accel_noise_density_mps2_per_sqrt_hz);
    detail::require_non_negative(prefix, "gyro_bias_random_walk_radps2_per_sqrt_hz",
                                 gyro_bias_random_walk_radps2_per_sqrt_hz);
    detail::require_non_negative(prefix, "accel_bias_random_walk_mps3_per_sqrt_hz",
                                 accel_bias_random_walk_mps3_per_sqrt_hz);
    detail::require_non_negative(prefix, "gyro_initial_bias_sigma_radps",
                                 gyro_initial_bias_sigma_radps);
    detail::require_non_negative(prefix, "accel_initial_bias_sigma_mps2",
                                 accel_initial_bias_sigma_mps2);
    detail::require_non_negative(prefix, "gravity_mps2", gravity_mps2);
    validate_mount(T_body_sensor, prefix);
}

ImuConfig consumer_mems_imu() { return ImuConfig{}; }

ImuConfig industrial_mems_imu() {
    ImuConfig config;
    config.gyro_noise_density_radps_per_sqrt_hz = 0.12 * kDeg / 60.0;  // °/√h → rad/s/√Hz
    config.accel_noise_density_mps2_per_sqrt_hz = 0.008 / 60.0;        // m/s/√h → m/s²/√Hz
    config.gyro_bias_random_walk_radps2_per_sqrt_hz = 1e-6;
    config.accel_bias_random_walk_mps3_per_sqrt_hz = 1e-5;
    config.gyro_initial_bias_sigma_radps = 0.001;
    config.accel_initial_bias_sigma_mps2 = 0.005;
    return config;
}

ImuConfig noiseless(ImuConfig config) {
    config.gyro_noise_density_radps_per_sqrt_hz = 0.0;
    config.accel_noise_density_mps2_per_sqrt_hz = 0.0;
    config.gyro_bias_random_walk_radps2_per_sqrt_hz = 0.0;
    config.accel_bias_random_walk_mps3_per_sqrt_hz = 0.0;
    config.gyro_initial_bias_sigma_radps = 0.0;
    config.accel_initial_bias_sigma_mps2 = 0.0;
    return config;
}

ImuSample ideal_imu_sample(const MotionState& truth, double gravity_mps2) {
    const Eigen::Vector3d g_world(0.0, 0.0, -gravity_mps2);
    ImuSample sample;
    sample.stamp_s = truth.stamp_s;
    sample.specific_force_mps2 =
        truth.T_world_body.linear().transpose() * (truth.a_world_mps2 - g_world);
    sample.angular_rate_radps = truth.omega_body_radps;
    return sample;
}

ImuSimulator::ImuSimulator(ImuConfig config, Rng& rng) : config_(std::move(config)) {
    config_.validate();
    gyro_bias_radps_ = rng.normal3(config_.gyro_initial_bias_sigma_radps);
    accel_bias_mps2_ = rng.normal3(config_.accel_initial_bias_sigma_mps2);
}

double ImuSimulator::time_step_s(const MotionState& truth) const {
    detail::check_motion(truth, "imu");
    if (has_previous_) detail::check_stamp_order(truth.stamp_s, previous_stamp_s_, "imu");
    return has_previous_ ? truth.stamp_s - previous_stamp_s_ : 0.0;
}

void ImuSimulator::advance_biases(double dt_s, Rng& rng) {
    const double sqrt_dt = std::sqrt(dt_s);
    gyro_bias_radps_ += rng.normal3(config_.gyro_bias_random_walk_radps2_per_sqrt_hz * sqrt_dt);
    accel_bias_mps2_ += rng.normal3(config_.accel_bias_random_walk_mps3_per_sqrt_hz * sqrt_dt);
}

Eigen::Vector3d ImuSimulator::lever_arm_mps2(const Eigen::Vector3d& omega_radps,
                                             double dt_s) const {
    // Rigid body: a_sensor = a_body + α × r + ω × (ω × r), α by finite difference of ω.
    const Eigen::Vector3d alpha_radps2 =
        dt_s > 0.0 ? Eigen::Vector3d((omega_radps - previous_omega_body_radps_) / dt_s)
                   : Eigen::Vector3d::Zero();
    const Eigen::Vector3d r = config_.T_body_sensor.translation();
    return alpha_radps2.cross(r) + omega_radps.cross(omega_radps.cross(r));
}

ImuSample ImuSimulator::measure(const MotionState& truth, Rng& rng) {
    const double dt_s = time_step_s(truth);
    advance_biases(dt_s, rng);
    const double sqrt_rate = std::sqrt(config_.rate_hz);
    const Eigen::Vector3d gyro_noise =
        rng.normal3(config_.gyro_noise_density_radps_per_sqrt_hz * sqrt_rate);
    const Eigen::Vector3d accel_noise =
        rng.normal3(config_.accel_noise_density_mps2_per_sqrt_hz * sqrt_rate);

    const Eigen::Vector3d& omega = truth.omega_body_radps;
    const Eigen::Vector3d f_body =
        ideal_imu_sample(truth, config_.gravity_mps2).specific_force_mps2 +
        lever_arm_mps2(omega, dt_s);
    has_previous_ = true;
    previous_stamp_s_ = truth.stamp_s;
    previous_omega_body_radps_ = omega;

    const Eigen::Matrix3d R_sensor_body = config_.T_body_sensor.linear().transpose();
    ImuSample sample;
    sample.stamp_s = truth.stamp_s;
    sample.specific_force_mps2 = R_sensor_body * f_body + accel_bias_mps2_ + accel_noise;
    sample.angular_rate_radps = R_sensor_body * omega + gyro_bias_radps_ + gyro_noise;
    return sample;
}

}  // namespace scantling::sim
