#pragma once
/// @file
/// VIO velocity as odometry (issue 12 item 1, "VIO (pose or velocity)"): the body velocity of a
/// VIO whose position output is not used — one that only reports velocity and attitude, or
/// whose position jumps at its own resets and loop closures — integrated into the pose samples
/// the filter takes (pose_filter.hpp):
///
///   p_k = p_{k−1} + ½ (R_{k−1} v_{k−1} + R_k v_k) Δt,   R_k = Rz(ψ_k) · tilt_k,
///
/// in an odometry frame whose origin is the first valid sample. Roll and pitch (tilt_k) are the
/// IMU's (attitude_estimator.hpp: levelled by gravity, no drift). The heading ψ follows the
/// VIO's yaw increments, because the IMU's yaw is the raw gyro's integral and a consumer gyro's
/// turn-on bias (~0.5°/s) would turn 143 s of flight by 70°; where an increment disagrees with
/// the gyro's by more than max_yaw_disagreement_rad (a VIO reset), or the VIO sample is
/// invalid, the gyro's increment is used instead. The sample's position is ignored; its `valid`
/// flag, velocity and stamps are kept. A sample is invalid (a dropout to the filter) when the
/// VIO says so, when there is no attitude yet, or when its velocity is not finite; the position
/// is then held, and integration restarts at the next valid sample (a gap of more than
/// max_step_s is never integrated across: the velocity between is unknown).
///
/// Drift: white velocity noise σ integrates to a random walk σ √(Δt · T) (1 cm/s at 30 Hz:
/// 2.2 cm after 143 s); the tilt wanders with the accelerations the IMU's complementary filter
/// cannot tell from gravity, so the filter's tilt random walk is raised (below).
///
/// Thread-safety: not thread-safe; one per odometry stream. Deterministic.

#include <Eigen/Geometry>
#include <optional>
#include <string_view>

#include <scantling/io/recording.hpp>

namespace scantling::localization {

struct VelocityOdometryConfig {
    /// Longest step integrated, seconds, > 0: 0.5 s is 15 missed samples of a 30 Hz VIO.
    double max_step_s = 0.5;
    /// Largest difference between the VIO's and the gyro's yaw increment over one step taken
    /// as the VIO's own motion, radians, > 0: the gyro's bias accounts for < 1 mrad per 30 Hz
    /// step, a VIO reset for far more.
    double max_yaw_disagreement_rad = 0.02;
    /// The IMU's roll and pitch are not a VIO's: they wander with the accelerations the
    /// complementary filter cannot tell from gravity. The filter's tilt random walk is raised
    /// to at least this in velocity mode, rad/√m travelled, > 0 (the VIO's: 3e-4).
    double tilt_random_walk_rad_per_sqrt_m = 0.003;

    void validate(std::string_view prefix = "velocity_odometry") const;
};

class VelocityOdometry {
  public:
    explicit VelocityOdometry(VelocityOdometryConfig config = {});

    /// The pose sample for `sample`, with `R_world_body` the IMU's attitude at its stamp.
    io::VioRecord integrate(const io::VioRecord& sample,
                            const std::optional<Eigen::Matrix3d>& R_world_body);

  private:
    struct Previous {
        double stamp_s = 0.0;
        Eigen::Vector3d v_odom_mps = Eigen::Vector3d::Zero();
        bool valid = false;
        std::optional<double> vio_yaw_rad;  ///< when the sample was valid
        std::optional<double> imu_yaw_rad;  ///< when there was an attitude
    };
    /// The heading step: the VIO's, or the gyro's where the VIO's is missing or disagrees.
    double yaw_step(const io::VioRecord& sample, double imu_yaw_rad) const;
    /// `sample` with the current odometry pose (nothing integrated).
    io::VioRecord held(const io::VioRecord& sample) const;

    VelocityOdometryConfig config_;
    Eigen::Vector3d p_odom_m_ = Eigen::Vector3d::Zero();
    Eigen::Matrix3d R_odom_body_ = Eigen::Matrix3d::Identity();
    std::optional<double> yaw_odom_rad_;
    std::optional<Previous> previous_;
};

}  // namespace scantling::localization
