// VIO velocity integrated with the IMU's attitude into odometry poses.
#include <gtest/gtest.h>

#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/localization/velocity_odometry.hpp>

namespace scantling::localization {
namespace {

io::VioRecord sample(double stamp_s, const Eigen::Vector3d& v_body_mps, bool valid = true) {
    io::VioRecord r;
    r.stamp_s = stamp_s;
    r.valid = valid;
    r.v_body_mps = v_body_mps;
    r.T_odom_body.translation() = Eigen::Vector3d(100, 100, 100);  // must be ignored
    return r;
}

Eigen::Matrix3d yaw(double rad) {
    return Eigen::AngleAxisd(rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

TEST(VelocityOdometry, IntegratesTheBodyVelocityInTheImuAttitude) {
    VelocityOdometry odometry;
    const Eigen::Vector3d forward(1.0, 0.0, 0.0);
    io::VioRecord out;
    for (int k = 0; k <= 30; ++k) out = odometry.integrate(sample(k / 30.0, forward), yaw(M_PI_2));
    // 1 s at 1 m/s along body x, which the attitude turns to world y.
    EXPECT_TRUE(out.valid);
    EXPECT_NEAR(out.T_odom_body.translation().x(), 0.0, 1e-12);
    EXPECT_NEAR(out.T_odom_body.translation().y(), 1.0, 1e-12);
    EXPECT_TRUE(out.T_odom_body.linear().isApprox(yaw(M_PI_2)));
    EXPECT_EQ(out.v_body_mps, forward);
}

TEST(VelocityOdometry, TrapezoidFollowsATurn) {
    // Yaw 0 then π/2: the step between averages the two world velocities.
    VelocityOdometry odometry;
    odometry.integrate(sample(0.0, {1, 0, 0}), yaw(0.0));
    const io::VioRecord out = odometry.integrate(sample(0.1, {1, 0, 0}), yaw(M_PI_2));
    EXPECT_NEAR(out.T_odom_body.translation().x(), 0.05, 1e-12);
    EXPECT_NEAR(out.T_odom_body.translation().y(), 0.05, 1e-12);
}

TEST(VelocityOdometry, HeadingFollowsTheVioNotTheGyroBiasAndSurvivesAVioReset) {
    // The IMU's yaw drifts 0.5°/s (a consumer gyro's turn-on bias); the VIO holds its heading,
    // then resets its yaw by 1 rad at 1 s while the body keeps going straight.
    VelocityOdometry odometry;
    io::VioRecord out;
    for (int k = 0; k <= 60; ++k) {
        const double t = k / 30.0;
        io::VioRecord s = sample(t, {1, 0, 0});
        if (t > 1.0) s.T_odom_body.linear() = yaw(1.0);
        out = odometry.integrate(s, yaw(0.5 * M_PI / 180.0 * t));
    }
    // Straight along x for 2 s: the gyro's 1° and the VIO's reset both left out (the reset
    // step takes the gyro's 0.017° instead).
    EXPECT_NEAR(out.T_odom_body.translation().x(), 2.0, 1e-3);
    EXPECT_NEAR(out.T_odom_body.translation().y(), 0.0, 1e-3);
    EXPECT_LT(Eigen::AngleAxisd(out.T_odom_body.linear()).angle(), 0.001);
}

TEST(VelocityOdometry, HoldsThroughDropoutsGapsAndMissingAttitude) {
    VelocityOdometry odometry;
    const Eigen::Vector3d v(1, 0, 0);
    EXPECT_FALSE(odometry.integrate(sample(0.0, v), std::nullopt).valid);  // no IMU yet
    odometry.integrate(sample(0.1, v), yaw(0.0));
    odometry.integrate(sample(0.2, v), yaw(0.0));  // +0.1 m
    const io::VioRecord lost = odometry.integrate(sample(0.3, v, false), yaw(0.0));
    EXPECT_FALSE(lost.valid);
    EXPECT_NEAR(lost.T_odom_body.translation().x(), 0.1, 1e-12);
    // Valid again: nothing integrated across the invalid sample, then +0.1 m.
    EXPECT_NEAR(odometry.integrate(sample(0.4, v), yaw(0.0)).T_odom_body.translation().x(), 0.1,
                1e-12);
    EXPECT_NEAR(odometry.integrate(sample(0.5, v), yaw(0.0)).T_odom_body.translation().x(), 0.2,
                1e-12);
    // A 1 s gap (> max_step_s) is not integrated across; a sample back in time changes nothing.
    EXPECT_NEAR(odometry.integrate(sample(1.5, v), yaw(0.0)).T_odom_body.translation().x(), 0.2,
                1e-12);
    EXPECT_NEAR(odometry.integrate(sample(1.0, v), yaw(0.0)).T_odom_body.translation().x(), 0.2,
                1e-12);
    EXPECT_NEAR(odometry.integrate(sample(1.6, v), yaw(0.0)).T_odom_body.translation().x(), 0.3,
                1e-12);
    const Eigen::Vector3d nan(std::nan(""), 0, 0);
    EXPECT_FALSE(odometry.integrate(sample(1.7, nan), yaw(0.0)).valid);
    EXPECT_THROW(VelocityOdometry(VelocityOdometryConfig{.max_step_s = 0.0}), ConfigError);
}

}  // namespace
}  // namespace scantling::localization
