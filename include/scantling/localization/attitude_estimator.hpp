#pragma once
/// @file
/// Roll and pitch from an IMU (the "IMU attitude" of SPEC §7's attitude gate): a complementary
/// filter (Mahony et al., 2008, passive form) integrating the gyro and pulling the estimated up
/// direction towards the accelerometer's when the specific force is close to gravity. Yaw is
/// the gyro's integral only (unobservable here, and the gate never reads it).
///
/// Frames: the IMU is taken as mounted in the body frame (rotate samples first otherwise).
/// Thread-safety: not thread-safe. Deterministic.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <deque>
#include <optional>
#include <string_view>

#include <scantling/io/recording.hpp>

namespace scantling::localization {

struct AttitudeEstimatorConfig {
    /// Rate at which the accelerometer corrects the tilt, 1/s, > 0: a time constant of 2 s
    /// averages out a drone's short accelerations yet follows gyro bias drift.
    double accel_gain_per_s = 0.5;
    /// Skip the correction when | |f| − g | exceeds this, m/s², > 0 (the vehicle is accelerating).
    double max_accel_deviation_mps2 = 1.5;
    double gravity_mps2 = 9.81;  ///< > 0
    /// A gap between samples longer than this restarts the filter from the accelerometer, s, > 0.
    double max_gap_s = 0.1;
    double history_s = 10.0;  ///< how far back attitude_at answers, s, > 0

    void validate(std::string_view prefix = "attitude") const;
};

/// What add() did with a sample.
enum class ImuStatus { kOk, kFirst, kGapRestart, kOutOfOrder, kInvalid };
std::string_view to_string(ImuStatus status);

class AttitudeEstimator {
  public:
    explicit AttitudeEstimator(AttitudeEstimatorConfig config = {});

    /// kOutOfOrder (stamp not after the last) and kInvalid (non-finite) samples are ignored.
    ImuStatus add(const io::ImuRecord& sample);

    /// R_world_body at `stamp_s` (nearest earlier sample), roll and pitch meaningful; nullopt
    /// before the first sample or older than the history.
    std::optional<Eigen::Matrix3d> attitude_at(double stamp_s) const;

  private:
    struct Sample {
        double stamp_s = 0.0;
        Eigen::Quaterniond q_world_body = Eigen::Quaterniond::Identity();
    };
    Eigen::Quaterniond from_accelerometer(const Eigen::Vector3d& f) const;

    AttitudeEstimatorConfig config_;
    std::deque<Sample> history_;
};

}  // namespace scantling::localization
