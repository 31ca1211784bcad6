#pragma once
/// @file
/// The drone's local state estimator, SPEC §4: an error-state EKF that integrates the IMU and
/// fuses LiDAR-odometry pose increments, the down-looking range finder and the barometer.
///
/// Frames: odom is the start pose's gravity-aligned frame (z up, gravity −9.81 m/s² along z);
/// body is the vehicle; the IMU and the range finder are mounted by T_body_imu, T_body_sensor.
/// Nominal state: p_odom, v_odom, R_odom_body, accelerometer and gyro biases (body frame) and
/// the barometer's bias. Error state (16 + 6): δp, δθ, δv, δb_a, δb_g, δb_baro, then a clone
/// (δp₀, δθ₀) of the pose at the start of a sweep. δθ is a world-frame (left) perturbation:
/// R_true = exp(δθ) · R, p_true = p + δp (the convention of FusedState in pose_filter.hpp).
///
/// Prediction: each IMU sample advances the state from the filter time to its stamp with the
/// average of it and the previous sample (trapezoid), biases subtracted, the centripetal lever
/// arm of the mount removed (angular acceleration × lever arm is neglected: it needs a
/// differentiated gyro). A step longer than max_imu_gap_s is a gap: predicted all the same,
/// with extra acceleration and angular-rate noise, and reported (ImuPredictionStatus::kGap).
///
/// LiDAR increments (stochastic cloning): clone_pose(t₀) copies the pose and its covariance
/// rows at the sweep start; update_increment(t₀ → t₁) compares T_body0_body1 with
/// h = T_odom_body(t₀)⁻¹ · T_odom_body(t₁), which correlates the two poses correctly, and
/// re-clones at t₁ so that chained sweeps need one clone_pose only. The increment's 6×6
/// information is never inverted: it is projected onto its eigenvectors whose eigenvalues
/// exceed information_relative_threshold × the largest, each a 1-D measurement of variance
/// 1/λ, so a degenerate direction (a corridor's axis) carries no weight at all.
///
/// Height: the range finder's ray (sensor +z) hits a horizontal floor at floor_height_m in odom:
/// range = (p_z + (R t_body_sensor)_z − floor_height_m) / cos(tilt of the ray). The floor height
/// is a config, not a state: the caller knows where the odom frame starts above the floor (0 =
/// the start height is the odom origin, so set the start pose's z to the height above floor).
/// A χ² gate rejects a range that disagrees (stepping over a box), reported as kRejected.
/// The barometer measures p_z + b_baro with b_baro a random walk (weather, ground effect): the
/// first sample initialises b_baro (correlated with p_z), later ones update both.
///
/// Underwater (an ROV): a DVL measures the velocity over the seabed in its own frame, mounted
/// by T_body_velocity_sensor: v_sensor = R_bsᵀ (Rᵀ v + ω × t_bs), with ω the bias-corrected
/// gyro rate of the held sample (the lever arm's rotational velocity; that one sample's white
/// noise, density² / IMU interval, is added to the DVL's covariance). A pressure sensor gives
/// p_z directly (no bias state: water pressure is an absolute depth). Both are χ²-gated.
///
/// Timing: a measurement newer than the filter time predicts to its stamp with the last IMU
/// sample held; one up to max_measurement_delay_s older is applied at the filter time (error
/// ≤ speed × delay); older ones are refused (kTooOld). An IMU sample older than the filter time
/// but newer than the last IMU sample only replaces the held sample.
///
/// Thread-safety: not thread-safe; one filter per vehicle. Deterministic.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <numbers>
#include <optional>
#include <string_view>

#include <scantling/core/se3.hpp>
#include <scantling/io/recording.hpp>

namespace scantling::localization {

using Matrix9d = Eigen::Matrix<double, 9, 9>;

/// The state at the filter time, at the IMU rate (the local EKF: odom frame; the global EKF:
/// world frame, fields named odom then mean world).
struct DroneState {
    double stamp_s = 0.0;
    Eigen::Isometry3d T_odom_body = Eigen::Isometry3d::Identity();
    Eigen::Vector3d v_odom_mps = Eigen::Vector3d::Zero();
    Eigen::Vector3d a_odom_mps2 = Eigen::Vector3d::Zero();  ///< gravity removed, bias corrected
    Eigen::Vector3d omega_body_radps = Eigen::Vector3d::Zero();  ///< bias corrected
    Eigen::Vector3d accel_bias_mps2 = Eigen::Vector3d::Zero();   ///< body frame
    Eigen::Vector3d gyro_bias_radps = Eigen::Vector3d::Zero();   ///< body frame
    /// Covariance of (δp, δθ, δv): p_true = p + δp, R_true = exp(δθ) · R, v_true = v + δv.
    Matrix9d covariance = Matrix9d::Zero();
};

/// A LiDAR-odometry pose increment between two sweep stamps.
struct PoseIncrement {
    double start_stamp_s = 0.0;  ///< t₀: the clone's stamp
    double end_stamp_s = 0.0;    ///< t₁
    Eigen::Isometry3d T_body0_body1 = Eigen::Isometry3d::Identity();
    /// Information of a left twist ε = (ρ, ω) in the body0 frame (1/m², 1/rad²): the true
    /// increment is se3_exp(ε) · T_body0_body1. Positive semi-definite; null directions allowed.
    Matrix6d information = Matrix6d::Zero();
};

/// One barometric altitude (metres, up; its own datum, the bias state absorbs the offset).
struct BarometerMeasurement {
    double stamp_s = 0.0;
    double altitude_m = 0.0;
    double sigma_m = 0.5;  ///< white noise of this sample, > 0
};

/// A velocity over ground measured in a sensor frame mounted on the body (a DVL's bottom-lock
/// velocity): v_sensor = R_body_sensorᵀ (R_odom_bodyᵀ v_odom + ω_body × t_body_sensor).
struct BodyVelocityMeasurement {
    double stamp_s = 0.0;
    Eigen::Vector3d v_sensor_mps = Eigen::Vector3d::Zero();
    Eigen::Matrix3d covariance_mps2 =
        Eigen::Matrix3d::Identity() *
        1e-4;  ///< of v_sensor, sensor axes; symmetric positive definite
};

/// The vehicle's height in the odom frame from a pressure sensor: z_odom = surface_z_odom − depth.
/// Unlike the barometer there is no bias state: water pressure gives depth absolutely (the
/// caller converts depth to odom z with the surface's height in odom).
struct DepthMeasurement {
    double stamp_s = 0.0;
    double z_odom_m = 0.0;  ///< the body origin's z in odom, m
    double sigma_m = 0.02;  ///< > 0
};

/// A heading in odom: a compass, or the direction of a straight structure whose direction is
/// known (the ROV's hull line, mission/rov_stack.hpp). Yaw of R = R_z(ψ) R_y(θ) R_x(φ).
struct YawMeasurement {
    double stamp_s = 0.0;
    double yaw_odom_rad = 0.0;  ///< any value; the residual is wrapped to (−π, π]
    double sigma_rad = 0.05;    ///< > 0
};

enum class ImuPredictionStatus { kOk, kFirst, kGap, kOutOfOrder, kNotInitialized };
std::string_view to_string(ImuPredictionStatus status);

/// What a measurement did. kRejected = failed its χ² gate (an outlier).
enum class UpdateStatus {
    kApplied,
    kRejected,
    kTooOld,
    kInvalid,        ///< flagged invalid or outside the sensor's window (range, tilt)
    kNoClone,        ///< no clone at the increment's start stamp
    kNoInformation,  ///< every direction of the information is (near) null
    kUnknownAnchor,  ///< a UWB anchor id the config does not list
    kNoLocal,        ///< global EKF: no local state near the measurement's stamp
    kNotInitialized,
};
std::string_view to_string(UpdateStatus status);

struct UpdateResult {
    UpdateStatus status = UpdateStatus::kNotInitialized;
    double mahalanobis_squared = 0.0;  ///< of the innovation (0 when not evaluated)
    int dof = 0;                       ///< measurement dimensions used
};

struct LocalEkfCounters {
    std::size_t imu_samples = 0;
    std::size_t imu_gaps = 0;
    std::size_t imu_out_of_order = 0;
    std::size_t increments_applied = 0;
    std::size_t increments_rejected = 0;  ///< χ² gate, no clone, no information, too old
    std::size_t ranges_applied = 0;
    std::size_t ranges_rejected = 0;  ///< χ² gate only (invalid samples are not counted)
    std::size_t barometer_applied = 0;
    std::size_t barometer_rejected = 0;
    std::size_t velocity_applied = 0;
    std::size_t velocity_rejected = 0;  ///< χ² gate only
    std::size_t depth_applied = 0;
    std::size_t depth_rejected = 0;  ///< χ² gate only
    std::size_t yaw_applied = 0;
    std::size_t yaw_rejected = 0;  ///< χ² gate only
};

struct LocalEkfConfig {
    Eigen::Isometry3d T_body_imu = Eigen::Isometry3d::Identity();  ///< IMU mount
    double gravity_mps2 = 9.81;
    /// IMU white noise and bias random walks (continuous-time densities). A consumer MEMS IMU
    /// (ICM-20602 class: 1e-3 m/s²/√Hz, 7e-5 rad/s/√Hz) inflated ×10 for a multirotor's
    /// vibration, as VIO packages configure them.
    double accel_noise_density_mps2_per_sqrt_hz = 0.01;
    double gyro_noise_density_radps_per_sqrt_hz = 7e-4;
    double accel_bias_random_walk_mps3_per_sqrt_hz = 1e-3;
    double gyro_bias_random_walk_radps2_per_sqrt_hz = 1e-5;
    /// Initial uncertainty. Position and yaw are 0: the odom frame is defined by the start pose.
    double initial_position_sigma_m = 0.0;
    double initial_tilt_sigma_rad = 0.01;  ///< roll, pitch from levelling (0.1 m/s² / g)
    double initial_yaw_sigma_rad = 0.0;
    double initial_velocity_sigma_mps = 0.05;  ///< on the ground or hovering
    double initial_accel_bias_sigma_mps2 = 0.1;
    double initial_gyro_bias_sigma_radps = 0.01;  ///< turn-on bias after a factory calibration
    /// A step between IMU samples longer than this is a gap, s, > 0 (10 periods at 200 Hz).
    double max_imu_gap_s = 0.05;
    /// During a gap the held sample is stale: random walk of velocity (m/s per √s) and
    /// attitude (rad per √s) added, a drone's typical acceleration and turn rate.
    double gap_acceleration_sigma_mps2 = 2.0;
    double gap_angular_rate_sigma_radps = 0.5;
    /// How much older than the filter time a measurement may be and still be applied, s.
    double max_measurement_delay_s = 0.01;
    /// Information eigenvalues below this × the largest are dropped, in (0, 1).
    double information_relative_threshold = 1e-6;
    /// χ² gate of the increments at 99.9 % for their dimension; false = no gate.
    bool gate_increments = true;
    /// Range finder: ray along the sensor's +z; default mount: looking straight down.
    Eigen::Isometry3d T_body_sensor{Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX())};
    double range_sigma_m = 0.03;      ///< a TFmini-class LiDAR range finder at < 6 m
    double min_range_m = 0.1;         ///< closer: the sensor's blind zone
    double max_range_m = 8.0;         ///< farther: unreliable returns
    double max_range_tilt_rad = 0.5;  ///< the ray's angle from vertical, beyond: refused
    double floor_height_m = 0.0;      ///< the floor's z in odom (see the file comment)
    double range_gate_chi2 = 10.83;   ///< 1 DoF, 99.9 %
    /// Barometer bias random walk, m per √s: indoor pressure drifts ~1 m in 10 min.
    double barometer_bias_random_walk_m_per_sqrt_s = 0.04;
    double barometer_gate_chi2 = 10.83;  ///< 1 DoF, 99.9 %
    /// Body-velocity sensor (a DVL): its frame on the body; the measured velocity is in its axes
    /// and at its origin, so an offset mount adds the lever arm's ω × t to the body's velocity.
    Eigen::Isometry3d T_body_velocity_sensor = Eigen::Isometry3d::Identity();
    double velocity_gate_chi2 = 16.27;  ///< 3 DoF, 99.9 %
    double depth_gate_chi2 = 10.83;     ///< 1 DoF, 99.9 %
    double yaw_gate_chi2 = 10.83;       ///< 1 DoF, 99.9 %

    /// Throws ConfigError naming the field ("local_ekf.max_imu_gap_s = 0, expected finite > 0").
    void validate(std::string_view prefix = "local_ekf") const;
};

class LocalEkf {
  public:
    static constexpr int kStateDim = 22;  ///< 16 + the 6 clone states
    using StateMatrix = Eigen::Matrix<double, kStateDim, kStateDim>;

    /// Validates the config (ConfigError).
    explicit LocalEkf(LocalEkfConfig config = {});

    /// Starts at `stamp_s` from a pose (odom frame: usually the levelled start attitude at the
    /// origin, z = height above floor) and velocity, with the config's initial covariance.
    /// InputError on a non-finite input.
    void initialize(double stamp_s, const Eigen::Isometry3d& T_odom_body,
                    const Eigen::Vector3d& v_odom_mps = Eigen::Vector3d::Zero());

    /// Predicts to the sample's stamp. InputError on a non-finite value; a stamp at or before
    /// the previous sample's is refused (kOutOfOrder, ignored).
    ImuPredictionStatus add_imu(const io::ImuRecord& sample);

    /// Clones the pose at `stamp_s` (a sweep's start), replacing any previous clone.
    UpdateStatus clone_pose(double stamp_s);
    /// Fuses a LiDAR increment whose start is the clone's stamp; re-clones at its end.
    UpdateResult update_increment(const PoseIncrement& increment);
    /// Fuses the down-looking range (invalid records: kInvalid). InputError on a valid NaN.
    UpdateResult update_range(const io::RangeRecord& range);
    UpdateResult update_barometer(const BarometerMeasurement& altitude);
    /// Fuses a DVL velocity. InputError on a non-finite value or a covariance that is not
    /// symmetric positive definite.
    UpdateResult update_body_velocity(const BodyVelocityMeasurement& velocity);
    /// Fuses a pressure depth as odom z. InputError on a non-finite value or sigma_m <= 0.
    UpdateResult update_depth(const DepthMeasurement& depth);
    /// Fuses a heading; InputError on a non-finite value or sigma <= 0.
    UpdateResult update_yaw(const YawMeasurement& yaw);

    bool initialized() const { return initialized_; }
    double stamp_s() const { return stamp_s_; }
    /// The state at the filter time (InputError-free; meaningless before initialize()).
    DroneState state() const;
    const StateMatrix& full_covariance() const { return P_; }
    const LocalEkfCounters& counters() const { return counters_; }
    const LocalEkfConfig& config() const { return config_; }

  private:
    struct Nominal {
        Eigen::Vector3d p_odom = Eigen::Vector3d::Zero();
        Eigen::Vector3d v_odom = Eigen::Vector3d::Zero();
        Eigen::Matrix3d R_odom_body = Eigen::Matrix3d::Identity();
        Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
        Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
        double barometer_bias_m = 0.0;
        Eigen::Vector3d clone_p_odom = Eigen::Vector3d::Zero();
        Eigen::Matrix3d clone_R_odom_body = Eigen::Matrix3d::Identity();
    };
    struct BodyRates {
        Eigen::Vector3d specific_force_mps2 = Eigen::Vector3d::Zero();
        Eigen::Vector3d angular_rate_radps = Eigen::Vector3d::Zero();
    };

    BodyRates to_body(const io::ImuRecord& sample) const;
    void predict(double dt_s, const BodyRates& rates, bool gap);
    void propagate_covariance(double dt_s, const Eigen::Vector3d& a_body, bool gap);
    /// Brings the filter to a measurement's stamp; nullopt when it may be applied.
    std::optional<UpdateStatus> advance_to(double stamp_s);
    /// Gated EKF update (Joseph form); returns the result with its χ².
    UpdateResult correct(const Eigen::MatrixXd& H, const Eigen::VectorXd& residual,
                         const Eigen::MatrixXd& noise, double gate_chi2);
    void inject(const Eigen::Matrix<double, kStateDim, 1>& dx);
    void initialize_barometer_bias(const BarometerMeasurement& altitude);
    UpdateResult fuse_increment(const PoseIncrement& increment);

    LocalEkfConfig config_;
    bool initialized_ = false;
    double stamp_s_ = 0.0;
    Nominal x_;
    StateMatrix P_ = StateMatrix::Zero();
    std::optional<io::ImuRecord> last_imu_;
    BodyRates held_;
    double imu_interval_s_ = 0.0;  ///< between the last two IMU samples (0: fewer than two)
    std::optional<double> clone_stamp_s_;
    bool barometer_initialized_ = false;
    LocalEkfCounters counters_;
};

/// Jacobian of the increment h = T_0⁻¹ T_1's left twist (body0 frame) with respect to
/// (δp₁, δθ₁, δp₀, δθ₀) in the filter's convention (columns in that order).
Eigen::Matrix<double, 6, 12> increment_jacobian(const Eigen::Isometry3d& T_odom_body0,
                                                const Eigen::Isometry3d& T_odom_body1);

/// Predicted range of a downward ray and its Jacobian with respect to (δp, δθ).
struct RangePrediction {
    double range_m = 0.0;
    double cos_tilt = 0.0;  ///< of the ray against −z (≤ 0: the ray does not look down)
    Eigen::Matrix<double, 1, 6> jacobian = Eigen::Matrix<double, 1, 6>::Zero();
};
RangePrediction predict_range(const Eigen::Isometry3d& T_odom_body,
                              const Eigen::Isometry3d& T_body_sensor, double floor_height_m);

/// Predicted velocity in a body-mounted sensor's axes and its Jacobians (filter convention):
/// v_sensor = R_bsᵀ (Rᵀ v + ω × t_bs), ω = the bias-corrected body rate.
struct BodyVelocityPrediction {
    Eigen::Vector3d v_sensor_mps = Eigen::Vector3d::Zero();
    Eigen::Matrix3d d_theta = Eigen::Matrix3d::Zero();      ///< ∂/∂δθ (left, odom)
    Eigen::Matrix3d d_velocity = Eigen::Matrix3d::Zero();   ///< ∂/∂δv (odom)
    Eigen::Matrix3d d_gyro_bias = Eigen::Matrix3d::Zero();  ///< ∂/∂δb_g (ω = ω_imu − b_g)
};
BodyVelocityPrediction predict_body_velocity(const Eigen::Matrix3d& R_odom_body,
                                             const Eigen::Vector3d& v_odom_mps,
                                             const Eigen::Vector3d& omega_body_radps,
                                             const Eigen::Isometry3d& T_body_sensor);

/// χ² quantile at 99.9 % for 1 to 6 degrees of freedom.
double chi2_quantile_999(int dof);

}  // namespace scantling::localization
