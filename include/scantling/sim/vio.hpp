#pragma once
/// @file
/// Visual-inertial odometry (Intel RealSense T265 class): the body pose in a gravity-aligned
/// odometry frame with drift that grows with the distance travelled, worse where the camera
/// sees few features, with dropouts. SPEC §7 (VIO for relative motion), §10.
///
/// Frames: the odometry frame `odom` is fixed at the first step: its origin is the first true
/// body position and its yaw the first true body yaw, z up (VIO observes gravity), so
/// T_odom_body starts at zero position and yaw with the true roll and pitch. The VIO is assumed
/// calibrated: it reports the body pose, not its camera's.
///
/// Drift model: the estimate is T_world_body_est = E · T_world_body with a drift transform E
/// (yaw about z plus translation). Per step, with d the true distance travelled since the last
/// step and s = 1 + poor_features_drift_gain · (1 − feature_quality):
///   yaw drift += N(0, (s · yaw_random_walk_rad_per_sqrt_m)² · d), applied about the current
///   estimated position (later motion is rotated by it: position error then grows faster);
///   position drift += N(0, (s · position_random_walk_m_per_sqrt_m)² · d) per axis.
/// On top, each sample carries white jitter (position_jitter_m, attitude_jitter_rad per
/// axis) and the body velocity white noise velocity_sigma_mps.
/// Covariance: the 6×6 covariance of the error of T_odom_body in the ordering of core/se3.hpp,
/// (δp [m], δθ [rad]) with p_est = p + δp and R_est = exp(δθ) · R, both in the odom frame:
/// the drift propagated linearly (yaw error rotates later displacements) plus the jitter.
/// Dropouts: a dropout starts with probability 1 − exp(−dropout_rate_per_s · Δt) per step
/// (not during one) and lasts dropout_duration_s; feature quality below lost_feature_quality
/// also loses tracking. Invalid samples still carry the (drifting) pose; drift keeps growing.
/// Determinism: each step draws 1 uniform (dropout) then 3 + 1 drift normals, 3 + 3 jitter
/// normals and 3 velocity normals, in that order, whatever the outcome.

#include <Eigen/Geometry>
#include <string_view>

#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/sim/motion_state.hpp>

namespace scantling::sim {

/// Defaults: T265-like, drift ≈ 1 % of the distance travelled in good conditions.
struct VioConfig {
    double rate_hz = 30.0;                            ///< samples per second (caller steps)
    double position_random_walk_m_per_sqrt_m = 0.02;  ///< per axis, 1σ after 1 m
    double yaw_random_walk_rad_per_sqrt_m = 0.003;    ///< ≈ 0.17° after 1 m
    double poor_features_drift_gain = 4.0;            ///< drift × (1 + gain) at feature quality 0
    double lost_feature_quality = 0.05;  ///< tracking lost below this quality, in [0, 1]
    double position_jitter_m = 0.002;    ///< white noise per axis per sample
    double attitude_jitter_rad = 0.002;  ///< white noise per axis per sample
    double velocity_sigma_mps = 0.01;    ///< white noise per axis on v_body
    double dropout_rate_per_s = 0.01;    ///< dropout starts per second of tracking
    double dropout_duration_s = 1.0;     ///< length of a dropout

    /// Throws ConfigError naming the field ("vio.rate_hz = 0, expected > 0").
    void validate(std::string_view prefix = "vio") const;
};

/// The same config with drift, jitter, noise and dropouts off (and tracking never lost).
VioConfig noiseless(VioConfig config);

struct VioSample {
    double stamp_s = 0.0;
    Eigen::Isometry3d T_odom_body = Eigen::Isometry3d::Identity();
    Eigen::Vector3d v_body_mps = Eigen::Vector3d::Zero();           ///< body velocity, body frame
    Matrix6d covariance = Matrix6d::Zero();                         ///< of (δp, δθ), odom frame
    Eigen::Matrix3d velocity_covariance = Eigen::Matrix3d::Zero();  ///< of v_body_mps
    bool valid = false;            ///< false during a dropout or lost tracking
    double feature_quality = 1.0;  ///< the feature quality this sample was simulated with
};

/// VIO with its drift state. Not thread-safe; one simulator per VIO.
class VioSimulator {
  public:
    /// Validates the config (ConfigError).
    explicit VioSimulator(VioConfig config = {});

    /// One sample at `truth.stamp_s`. `feature_quality` in [0, 1] (1 = well lit, textured:
    /// e.g. the fraction of expected stereo points the caller sees). Throws InputError for a
    /// quality outside [0, 1], a stamp earlier than the previous one or non-finite truth.
    VioSample step(const MotionState& truth, double feature_quality, Rng& rng);

    /// The true pose of the odometry frame in the world (identity before the first step).
    const Eigen::Isometry3d& T_world_odom() const { return T_world_odom_; }

    /// True distance travelled so far, metres.
    double distance_travelled_m() const { return distance_m_; }

    const VioConfig& config() const { return config_; }

  private:
    void start(const MotionState& truth);
    void update_dropout(double stamp_s, double dt_s, double feature_quality, double uniform);
    void propagate_drift(const Eigen::Vector3d& p_world, double scale, Rng& rng);
    VioSample output(const MotionState& truth, Rng& rng) const;

    VioConfig config_;
    bool started_ = false;
    double previous_stamp_s_ = 0.0;
    Eigen::Vector3d previous_p_world_ = Eigen::Vector3d::Zero();
    Eigen::Isometry3d T_world_odom_ = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d E_drift_ = Eigen::Isometry3d::Identity();   // estimate = E · truth, world
    Eigen::Matrix4d drift_covariance_ = Eigen::Matrix4d::Zero();  // (δp world, δyaw)
    double distance_m_ = 0.0;
    double dropout_until_s_ = -1.0;
    bool tracking_ = true;
};

}  // namespace scantling::sim
