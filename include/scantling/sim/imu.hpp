#pragma once
/// @file
/// Inertial measurement unit: specific force and angular rate with white noise, turn-on biases
/// and bias random walks. SPEC §1 (every platform carries an IMU), §10.
///
/// Frames: the IMU measures in its own frame, mounted at `T_body_sensor` (body ← sensor).
/// Gravity is g_world = (0, 0, −gravity_mps2). For a sensor at the body origin:
///   f_sensor = R_body_sensorᵀ R_world_bodyᵀ (a_world − g_world)   (1 g up when at rest)
///   ω_sensor = R_body_sensorᵀ ω_body.
/// A lever arm r = T_body_sensor.translation() adds α × r + ω × (ω × r) to the body-frame
/// specific force; MotionState carries no angular acceleration, so α is the finite difference
/// of ω between consecutive samples (zero at the first sample).
///
/// Noise (continuous-time densities, as in datasheets and Kalibr/VINS configs), per sample:
///   measured = ideal + bias + N(0, σ²),  σ = noise_density · √rate_hz;
///   bias_k = bias_{k−1} + N(0, random_walk² · Δt),  Δt = time since the previous sample;
///   bias_0 ~ N(0, initial_bias_sigma²) per axis, drawn when the simulator is built.
/// Determinism: the constructor draws 3 gyro then 3 accel normals (initial biases); each
/// `measure` draws 3 gyro-walk, 3 accel-walk, 3 gyro-noise and 3 accel-noise normals, in that
/// order, whatever the configuration (zero σ still consumes its draw).

#include <Eigen/Geometry>
#include <string_view>

#include <scantling/core/random.hpp>
#include <scantling/sim/motion_state.hpp>

namespace scantling::sim {

/// Defaults: consumer MEMS (Bosch BMI055/BMI088 class, as in a RealSense T265 or a Pixhawk):
/// see consumer_mems_imu().
struct ImuConfig {
    double rate_hz = 200.0;  ///< samples per second; sets the white-noise σ
    double gyro_noise_density_radps_per_sqrt_hz = 2.4e-4;    ///< ≈ 0.014 °/s/√Hz
    double accel_noise_density_mps2_per_sqrt_hz = 1.5e-3;    ///< ≈ 150 µg/√Hz
    double gyro_bias_random_walk_radps2_per_sqrt_hz = 3e-5;  ///< gyro bias drift
    double accel_bias_random_walk_mps3_per_sqrt_hz = 5e-4;   ///< accel bias drift
    double gyro_initial_bias_sigma_radps = 0.0087;           ///< turn-on bias, ≈ 0.5 °/s
    double accel_initial_bias_sigma_mps2 = 0.05;             ///< turn-on bias, ≈ 5 mg
    double gravity_mps2 = 9.81;                              ///< |g|, along −z world
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();  ///< body ← IMU

    /// Throws ConfigError naming the field ("imu.rate_hz = 0, expected > 0").
    void validate(std::string_view prefix = "imu") const;
};

/// Consumer MEMS IMU (the defaults of ImuConfig).
ImuConfig consumer_mems_imu();

/// Industrial MEMS IMU (Analog Devices ADIS16495 class): 0.12 °/√h angle random walk,
/// 0.008 m/s/√h velocity random walk, small turn-on biases after factory calibration.
ImuConfig industrial_mems_imu();

/// The same config with every noise and bias term zero (an ideal IMU).
ImuConfig noiseless(ImuConfig config);

struct ImuSample {
    double stamp_s = 0.0;
    Eigen::Vector3d specific_force_mps2 = Eigen::Vector3d::Zero();  ///< sensor frame
    Eigen::Vector3d angular_rate_radps = Eigen::Vector3d::Zero();   ///< sensor frame
};

/// Noise-free specific force and angular rate at the body origin in the body frame:
/// f = R_world_bodyᵀ (a_world − g_world), ω = ω_body. O(1), pure.
ImuSample ideal_imu_sample(const MotionState& truth, double gravity_mps2 = 9.81);

/// An IMU with its bias state. Not thread-safe (each measure advances the biases); one
/// simulator per IMU.
class ImuSimulator {
  public:
    /// Validates the config (ConfigError) and draws the turn-on biases from `rng`.
    ImuSimulator(ImuConfig config, Rng& rng);

    /// One sample at `truth.stamp_s`. Throws InputError when the stamp is earlier than the
    /// previous sample's or the truth is not finite.
    ImuSample measure(const MotionState& truth, Rng& rng);

    /// Current biases, sensor frame (those added to the last sample).
    const Eigen::Vector3d& gyro_bias_radps() const { return gyro_bias_radps_; }
    const Eigen::Vector3d& accel_bias_mps2() const { return accel_bias_mps2_; }

    const ImuConfig& config() const { return config_; }

  private:
    double time_step_s(const MotionState& truth) const;
    void advance_biases(double dt_s, Rng& rng);
    Eigen::Vector3d lever_arm_mps2(const Eigen::Vector3d& omega_radps, double dt_s) const;

    ImuConfig config_;
    Eigen::Vector3d gyro_bias_radps_;
    Eigen::Vector3d accel_bias_mps2_;
    bool has_previous_ = false;
    double previous_stamp_s_ = 0.0;
    Eigen::Vector3d previous_omega_body_radps_ = Eigen::Vector3d::Zero();
};

}  // namespace scantling::sim
