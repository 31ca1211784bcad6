#include <gtest/gtest.h>

#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/localization/attitude_estimator.hpp>

namespace scantling::localization {
namespace {

/// IMU samples of a body at a fixed tilt spinning about the world z axis at `yaw_rate`.
io::ImuRecord spinning_sample(double t, double roll, double pitch, double yaw_rate,
                              const Eigen::Vector3d& gyro_bias) {
    const Eigen::Matrix3d R = rotation_from_euler_zyx(roll, pitch, yaw_rate * t);
    io::ImuRecord s;
    s.stamp_s = t;
    s.specific_force_mps2 = R.transpose() * Eigen::Vector3d(0, 0, 9.81);
    s.angular_rate_radps = R.transpose() * Eigen::Vector3d(0, 0, yaw_rate) + gyro_bias;
    return s;
}

Eigen::Vector2d roll_pitch(const Eigen::Matrix3d& R) {
    const Eigen::Vector3d rpy = euler_zyx_from_rotation(R);
    return {rpy.x(), rpy.y()};
}

TEST(AttitudeEstimator, KeepsRollAndPitchWhileTurningWithABiasedGyro) {
    AttitudeEstimator estimator;
    const double roll = 0.1, pitch = -0.05;
    for (int k = 0; k <= 6000; ++k) {  // 30 s at 200 Hz
        estimator.add(
            spinning_sample(0.005 * k, roll, pitch, 0.3, Eigen::Vector3d(0.005, -0.005, 0)));
    }
    const Eigen::Vector2d rp = roll_pitch(*estimator.attitude_at(30.0));
    // A bias b is held at b / gain = 0.01 rad by the accelerometer; integrating it alone
    // would give 0.15 rad after 30 s.
    EXPECT_NEAR(rp.x(), roll, 0.015);
    EXPECT_NEAR(rp.y(), pitch, 0.015);
}

TEST(AttitudeEstimator, ReportsGapsAndRefusesBackwardsTime) {
    AttitudeEstimator estimator;
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    EXPECT_EQ(estimator.add(spinning_sample(0.0, 0.1, 0.0, 0.0, zero)), ImuStatus::kFirst);
    EXPECT_EQ(estimator.add(spinning_sample(0.005, 0.1, 0.0, 0.0, zero)), ImuStatus::kOk);
    EXPECT_EQ(estimator.add(spinning_sample(0.001, 0.1, 0.0, 0.0, zero)), ImuStatus::kOutOfOrder);
    EXPECT_EQ(estimator.add(spinning_sample(1.0, 0.2, 0.0, 0.0, zero)), ImuStatus::kGapRestart);
    EXPECT_NEAR(roll_pitch(*estimator.attitude_at(1.0)).x(), 0.2, 1e-9);
    io::ImuRecord bad = spinning_sample(1.1, 0.0, 0.0, 0.0, zero);
    bad.specific_force_mps2.x() = NAN;
    EXPECT_EQ(estimator.add(bad), ImuStatus::kInvalid);
    EXPECT_FALSE(estimator.attitude_at(-1.0).has_value());
    AttitudeEstimatorConfig config;
    config.accel_gain_per_s = 0.0;
    EXPECT_THROW(AttitudeEstimator{config}, ConfigError);
}

}  // namespace
}  // namespace scantling::localization
