#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/sim/wheel_odometry.hpp>

#include "motion_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace scantling::sim {
namespace {

constexpr double kExact = 1e-9;
constexpr double kRate_hz = 50.0;

// A unicycle driving a circle of radius r at speed v, counter-clockwise from (r, 0, 0).
MotionState circle_drive(double t_s, double radius_m = 3.0, double speed_mps = 0.6) {
    const double w = speed_mps / radius_m;
    const double yaw = w * t_s + std::numbers::pi / 2.0;
    MotionState m;
    m.stamp_s = t_s;
    m.T_world_body.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    m.T_world_body.translation() =
        radius_m * Eigen::Vector3d(std::cos(w * t_s), std::sin(w * t_s), 0.0);
    m.v_world_mps = speed_mps * Eigen::Vector3d(std::cos(yaw), std::sin(yaw), 0.0);
    m.a_world_mps2 = -w * w * m.T_world_body.translation();
    m.omega_body_radps = Eigen::Vector3d(0.0, 0.0, w);
    return m;
}

TEST(WheelOdometry, DeadReckoningNoiselessSamplesRetracesTheCircle) {
    Rng rng(1);
    WheelOdometrySimulator odometry(noiseless(WheelOdometryConfig{}), rng);
    Eigen::Isometry3d T = circle_drive(0.0).T_world_body;
    const int steps = 1000;  // 20 s: two thirds of the circle
    for (int k = 0; k < steps; ++k) {
        const WheelOdometrySample s = odometry.measure(circle_drive(k / kRate_hz), rng);
        EXPECT_NEAR(s.forward_speed_mps, 0.6, kExact);
        EXPECT_NEAR(s.yaw_rate_radps, 0.2, kExact);
        T = integrate_unicycle(T, s.forward_speed_mps, s.yaw_rate_radps, 1.0 / kRate_hz);
    }
    const Eigen::Isometry3d truth = circle_drive(steps / kRate_hz).T_world_body;
    EXPECT_NEAR((T.translation() - truth.translation()).norm(), 0.0, kExact);
    EXPECT_NEAR(so3_log(T.linear().transpose() * truth.linear()).norm(), 0.0, kExact);
}

TEST(WheelOdometry, ACrawlersEncodersCountTheWheelsNotTheSlippedMotion) {
    // The body slides 5 % short of its wheels and turns 10 % more (crawler_dynamics.hpp's
    // slip): the encoders report the wheels' own speed and turn rate.
    Rng rng(1);
    WheelOdometrySimulator odometry(noiseless(WheelOdometryConfig{}), rng);
    MotionState m = circle_drive(0.0);
    m.wheel_forward_mps = 0.6 / 0.95;
    m.wheel_yaw_rate_radps = 0.2 / 1.1;
    const WheelOdometrySample s = odometry.measure(m, rng);
    EXPECT_NEAR(s.forward_speed_mps, 0.6 / 0.95, kExact);
    EXPECT_NEAR(s.yaw_rate_radps, 0.2 / 1.1, kExact);
}

TEST(WheelOdometry, SlipEventsComeAtTheirRateAndOverstateTheSpeed) {
    WheelOdometryConfig config = noiseless(WheelOdometryConfig{});
    config.slip_event_rate_per_s = 0.1;
    config.slip_yaw_rate_sigma_radps = 0.0;
    Rng rng(2);
    WheelOdometrySimulator odometry(config, rng);
    int events = 0, slipping = 0;
    bool was_slipping = false;
    const int steps = 50 * 2000;  // 2000 s
    for (int k = 0; k < steps; ++k) {
        const MotionState m = circle_drive(k / kRate_hz);
        const WheelOdometrySample s = odometry.measure(m, rng);
        events += s.slipping && !was_slipping;
        slipping += s.slipping;
        was_slipping = s.slipping;
        if (s.slipping) {
            EXPECT_GE(s.forward_speed_mps, 0.6);
            EXPECT_LT(s.forward_speed_mps, 0.6 * (1.0 + config.slip_max_speed_excess));
        } else {
            EXPECT_NEAR(s.forward_speed_mps, 0.6, kExact);
        }
    }
    // Events start only outside events: λ T / (1 + λ d) ≈ 190.5, Poisson 4σ ≈ 55.
    const double expected = 0.1 * 2000.0 / 1.05;
    EXPECT_NEAR(events, expected, 4.0 * std::sqrt(expected));
    EXPECT_NEAR(static_cast<double>(slipping) / events, 25.0, 1.0);  // 0.5 s = 25 samples
}

TEST(WheelOdometry, SpeedNoiseAndScaleErrorHaveTheConfiguredSpread) {
    WheelOdometryConfig config = noiseless(WheelOdometryConfig{});
    config.speed_noise_fraction = 0.02;
    Rng rng(3);
    WheelOdometrySimulator odometry(config, rng);
    const int n = 10000;
    double sq = 0.0;
    for (int k = 0; k < n; ++k) {
        sq += std::pow(
            odometry.measure(circle_drive(k / kRate_hz), rng).forward_speed_mps / 0.6 - 1.0, 2);
    }
    EXPECT_NEAR(std::sqrt(sq / n), 0.02, 4.0 * 0.02 / std::sqrt(2.0 * n));
    const int bases = 2000;
    double scale_sq = 0.0;
    for (int i = 0; i < bases; ++i) {
        Rng r(100 + i);
        scale_sq += std::pow(WheelOdometrySimulator(WheelOdometryConfig{}, r).scale_error(), 2);
    }
    EXPECT_NEAR(std::sqrt(scale_sq / bases), 0.01, 4.0 * 0.01 / std::sqrt(2.0 * bases));
}

TEST(WheelOdometry, SameSeedGivesIdenticalSamples) {
    Rng a(4), b(4);
    WheelOdometrySimulator oa(WheelOdometryConfig{}, a), ob(WheelOdometryConfig{}, b);
    for (int k = 0; k < 500; ++k) {
        const WheelOdometrySample sa = oa.measure(circle_drive(k / kRate_hz), a);
        const WheelOdometrySample sb = ob.measure(circle_drive(k / kRate_hz), b);
        EXPECT_EQ(sa.forward_speed_mps, sb.forward_speed_mps);
        EXPECT_EQ(sa.yaw_rate_radps, sb.yaw_rate_radps);
    }
}

TEST(WheelOdometry, BadConfigAndInputThrow) {
    Rng rng(5);
    WheelOdometryConfig c;
    c.slip_event_duration_s = -1.0;
    try {
        WheelOdometrySimulator odometry(c, rng);
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("wheel_odometry.slip_event_duration_s = -1"),
                  std::string::npos)
            << e.what();
    }
    c = WheelOdometryConfig{};
    c.scale_error_sigma = 0.5;
    EXPECT_THROW(WheelOdometrySimulator(c, rng), ConfigError);
    WheelOdometrySimulator odometry(WheelOdometryConfig{}, rng);
    odometry.measure(circle_drive(1.0), rng);
    EXPECT_THROW(odometry.measure(circle_drive(0.0), rng), InputError);
}

}  // namespace
}  // namespace scantling::sim
