#pragma once
/// @file
/// Wheel (or leg) odometry of a ground base: forward speed and yaw rate in the body frame,
/// with noise, a wheel-radius scale error and slip. SPEC §6 (crawler: the particle filter fuses
/// IMU, UWB and wheel odometry), §1 (legged base), §10.
///
/// Frames: the body x axis is the driving direction, z the normal of the surface driven on
/// (a crawler on a vertical hull has z horizontal). forward speed = x of R_world_bodyᵀ v_world,
/// yaw rate = z of ω_body; for a crawler, whose state carries its wheels' own motion
/// (MotionState::wheel_forward_mps), the wheels' speed and turn rate instead: its encoders do
/// not see the surface slip of crawler_dynamics.hpp.
/// Noise, per sample: v' = (1 + scale_error) · v · (1 + slip + N(0, speed_noise_fraction²))
/// + N(0, speed_noise_mps²); ω' = ω · (1 + N(0, yaw_rate_noise_fraction²)) + slip_yaw_rate
/// + N(0, yaw_rate_noise_radps²). scale_error ~ N(0, scale_error_sigma²) is drawn once.
/// Slip events start with probability 1 − exp(−slip_event_rate_per_s · Δt) per sample (not
/// during one) and last slip_event_duration_s, with slip ~ U(0, slip_max_speed_excess) (the
/// wheels turn faster than the base moves) and slip_yaw_rate ~ N(0, slip_yaw_rate_sigma²)
/// drawn at the start; outside events both are 0.
/// Determinism: the constructor draws 1 normal; each `measure` draws 2 uniforms and 1 normal
/// (slip) then 2 speed and 2 yaw-rate normals, in that order, whatever the outcome.

#include <Eigen/Geometry>
#include <string_view>

#include <scantling/core/random.hpp>
#include <scantling/sim/motion_state.hpp>

namespace scantling::sim {

/// Defaults: a magnetic crawler's wheel encoders (a few % noise, occasional slip on paint).
struct WheelOdometryConfig {
    double rate_hz = 50.0;                    ///< samples per second (caller steps)
    double speed_noise_fraction = 0.02;       ///< multiplicative 1σ on the forward speed
    double speed_noise_mps = 0.002;           ///< additive 1σ on the forward speed
    double yaw_rate_noise_fraction = 0.05;    ///< multiplicative 1σ on the yaw rate
    double yaw_rate_noise_radps = 0.005;      ///< additive 1σ on the yaw rate
    double scale_error_sigma = 0.01;          ///< 1σ of the constant wheel-radius error
    double slip_event_rate_per_s = 0.05;      ///< slip events per second
    double slip_event_duration_s = 0.5;       ///< length of a slip event
    double slip_max_speed_excess = 0.5;       ///< slip fraction drawn in [0, this)
    double slip_yaw_rate_sigma_radps = 0.05;  ///< 1σ of the yaw-rate error during a slip

    /// Throws ConfigError naming the field ("wheel_odometry.rate_hz = 0, expected > 0").
    void validate(std::string_view prefix = "wheel_odometry") const;
};

/// The same config with every noise, scale and slip term zero.
WheelOdometryConfig noiseless(WheelOdometryConfig config);

struct WheelOdometrySample {
    double stamp_s = 0.0;
    double forward_speed_mps = 0.0;  ///< along body x
    double yaw_rate_radps = 0.0;     ///< about body z
    bool slipping = false;           ///< ground truth: inside a slip event (for evaluation)
};

/// Dead reckoning: T_odom_body advanced by `dt_s` of constant forward speed and yaw rate
/// (exact arc of a unicycle in the body's x-y plane). O(1), pure.
Eigen::Isometry3d integrate_unicycle(const Eigen::Isometry3d& T_odom_body, double forward_speed_mps,
                                     double yaw_rate_radps, double dt_s);

/// Odometry with its slip and scale state. Not thread-safe; one simulator per base.
class WheelOdometrySimulator {
  public:
    /// Validates the config (ConfigError) and draws the scale error from `rng`.
    WheelOdometrySimulator(WheelOdometryConfig config, Rng& rng);

    /// One sample at `truth.stamp_s`. Throws InputError for non-finite truth or a stamp
    /// earlier than the previous one.
    WheelOdometrySample measure(const MotionState& truth, Rng& rng);

    double scale_error() const { return scale_error_; }
    const WheelOdometryConfig& config() const { return config_; }

  private:
    void update_slip(double stamp_s, Rng& rng);

    WheelOdometryConfig config_;
    double scale_error_ = 0.0;
    bool started_ = false;
    double previous_stamp_s_ = 0.0;
    double slip_until_s_ = -1.0;
    double slip_ = 0.0;
    double slip_yaw_rate_radps_ = 0.0;
};

}  // namespace scantling::sim
