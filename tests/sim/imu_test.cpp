#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/sim/imu.hpp>

#include "motion_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace scantling::sim {
namespace {

using testing::at_rest;
using testing::ClimbingCircle;

constexpr double kRate_hz = 200.0;
// Trapezoidal strapdown over 10 s at 200 Hz: O(dt²) error ≈ 1e-8 m here; margin for rounding.
constexpr double kStrapdownPosition_m = 1e-5;
constexpr double kStrapdownVelocity_mps = 1e-6;
constexpr double kStrapdownAttitude_rad = 1e-9;
constexpr double kExact = 1e-12;
// Sample standard deviations of n normals have relative error ≈ 1 / √(2n); 4σ bounds.
double sigma_tolerance(double sigma, int n) { return 4.0 * sigma / std::sqrt(2.0 * n); }

struct StrapdownState {
    Eigen::Matrix3d R_world_body;
    Eigen::Vector3d v_world_mps;
    Eigen::Vector3d p_world_m;
};

// One trapezoidal strapdown step between consecutive samples a → b (gravity along −z).
StrapdownState strapdown_step(const StrapdownState& s, const ImuSample& a, const ImuSample& b,
                              double gravity_mps2) {
    const double dt = b.stamp_s - a.stamp_s;
    const Eigen::Vector3d g(0.0, 0.0, -gravity_mps2);
    StrapdownState next;
    next.R_world_body =
        s.R_world_body * so3_exp(0.5 * (a.angular_rate_radps + b.angular_rate_radps) * dt);
    const Eigen::Vector3d acc_a = s.R_world_body * a.specific_force_mps2 + g;
    const Eigen::Vector3d acc_b = next.R_world_body * b.specific_force_mps2 + g;
    next.v_world_mps = s.v_world_mps + 0.5 * dt * (acc_a + acc_b);
    next.p_world_m = s.p_world_m + s.v_world_mps * dt + dt * dt / 6.0 * (2.0 * acc_a + acc_b);
    return next;
}

TEST(Imu, IntegratingNoiseFreeSamplesOfAClimbingCircleReturnsTheMotion) {
    const ClimbingCircle circle;
    Rng rng(1);
    ImuSimulator imu(noiseless(consumer_mems_imu()), rng);
    const MotionState start = circle.at(0.0);
    StrapdownState state{start.T_world_body.linear(), start.v_world_mps,
                         start.T_world_body.translation()};
    ImuSample previous = imu.measure(start, rng);
    const int steps = 2000;  // 10 s: more than 3/4 of a turn
    for (int k = 1; k <= steps; ++k) {
        const ImuSample sample = imu.measure(circle.at(k / kRate_hz), rng);
        state = strapdown_step(state, previous, sample, imu.config().gravity_mps2);
        previous = sample;
    }
    const MotionState end = circle.at(steps / kRate_hz);
    EXPECT_LT((state.p_world_m - end.T_world_body.translation()).norm(), kStrapdownPosition_m);
    EXPECT_LT((state.v_world_mps - end.v_world_mps).norm(), kStrapdownVelocity_mps);
    EXPECT_LT(so3_log(state.R_world_body.transpose() * end.T_world_body.linear()).norm(),
              kStrapdownAttitude_rad);
    // The motion really moved: 2 m climbed, heading turned by 5 rad.
    EXPECT_NEAR(end.T_world_body.translation().z(), 2.0, kExact);
}

TEST(Imu, AtRestMeasuresOneGUpwardsInTheSensorFrame) {
    ImuConfig config = noiseless(consumer_mems_imu());
    // Sensor x = body z (a rotation of −90° about body y): gravity's reaction lies on sensor x.
    config.T_body_sensor.linear() =
        Eigen::AngleAxisd(-std::numbers::pi / 2.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
    Rng rng(2);
    ImuSimulator imu(config, rng);
    const ImuSample s = imu.measure(at_rest(0.0, {1.0, 2.0, 3.0}), rng);
    EXPECT_NEAR((s.specific_force_mps2 - Eigen::Vector3d(9.81, 0.0, 0.0)).norm(), 0.0, kExact);
    EXPECT_NEAR(s.angular_rate_radps.norm(), 0.0, kExact);
}

TEST(Imu, LeverArmAddsTheCentripetalAcceleration) {
    ImuConfig config = noiseless(consumer_mems_imu());
    config.gravity_mps2 = 0.0;
    config.T_body_sensor.translation() = Eigen::Vector3d(0.5, 0.0, 0.0);
    Rng rng(3);
    ImuSimulator imu(config, rng);
    MotionState spin = at_rest(0.0, Eigen::Vector3d::Zero());
    spin.omega_body_radps = Eigen::Vector3d(0.0, 0.0, 2.0);
    imu.measure(spin, rng);
    spin.stamp_s = 0.005;  // constant rate: no tangential term
    const ImuSample s = imu.measure(spin, rng);
    EXPECT_NEAR((s.specific_force_mps2 - Eigen::Vector3d(-2.0, 0.0, 0.0)).norm(), 0.0, kExact);
}

TEST(Imu, WhiteNoiseHasDensityTimesSqrtRate) {
    ImuConfig config = consumer_mems_imu();
    config.gyro_bias_random_walk_radps2_per_sqrt_hz =
        config.accel_bias_random_walk_mps3_per_sqrt_hz = 0.0;
    Rng rng(4);
    ImuSimulator imu(config, rng);
    const int n = 10000;
    Eigen::Vector3d gyro_sq = Eigen::Vector3d::Zero(), accel_sq = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k) {
        const ImuSample s = imu.measure(at_rest(k / kRate_hz, Eigen::Vector3d::Zero()), rng);
        gyro_sq += (s.angular_rate_radps - imu.gyro_bias_radps()).cwiseAbs2();
        accel_sq += (s.specific_force_mps2 - Eigen::Vector3d(0, 0, 9.81) - imu.accel_bias_mps2())
                        .cwiseAbs2();
    }
    const double gyro_sigma = config.gyro_noise_density_radps_per_sqrt_hz * std::sqrt(kRate_hz);
    const double accel_sigma = config.accel_noise_density_mps2_per_sqrt_hz * std::sqrt(kRate_hz);
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(std::sqrt(gyro_sq[a] / n), gyro_sigma, sigma_tolerance(gyro_sigma, n));
        EXPECT_NEAR(std::sqrt(accel_sq[a] / n), accel_sigma, sigma_tolerance(accel_sigma, n));
    }
}

TEST(Imu, TurnOnBiasAndBiasRandomWalkHaveTheConfiguredSpread) {
    const ImuConfig config = consumer_mems_imu();
    const int imus = 400, samples = 201;  // 1 s of walk each
    double initial_sq = 0.0, walked_gyro_sq = 0.0, walked_accel_sq = 0.0;
    for (int i = 0; i < imus; ++i) {
        Rng rng(1000 + i);
        ImuSimulator imu(config, rng);
        const Eigen::Vector3d gyro0 = imu.gyro_bias_radps(), accel0 = imu.accel_bias_mps2();
        initial_sq += gyro0.squaredNorm();
        for (int k = 0; k < samples; ++k) {
            imu.measure(at_rest(k / kRate_hz, Eigen::Vector3d::Zero()), rng);
        }
        walked_gyro_sq += (imu.gyro_bias_radps() - gyro0).squaredNorm();
        walked_accel_sq += (imu.accel_bias_mps2() - accel0).squaredNorm();
    }
    const int n = 3 * imus;
    const double gyro_walk = config.gyro_bias_random_walk_radps2_per_sqrt_hz;  // × √(1 s)
    const double accel_walk = config.accel_bias_random_walk_mps3_per_sqrt_hz;
    EXPECT_NEAR(std::sqrt(initial_sq / n), config.gyro_initial_bias_sigma_radps,
                sigma_tolerance(config.gyro_initial_bias_sigma_radps, n));
    EXPECT_NEAR(std::sqrt(walked_gyro_sq / n), gyro_walk, sigma_tolerance(gyro_walk, n));
    EXPECT_NEAR(std::sqrt(walked_accel_sq / n), accel_walk, sigma_tolerance(accel_walk, n));
}

TEST(Imu, SameSeedGivesIdenticalSamples) {
    const ClimbingCircle circle;
    Rng a(7), b(7);
    ImuSimulator imu_a(consumer_mems_imu(), a), imu_b(consumer_mems_imu(), b);
    for (int k = 0; k < 50; ++k) {
        const ImuSample sa = imu_a.measure(circle.at(k / kRate_hz), a);
        const ImuSample sb = imu_b.measure(circle.at(k / kRate_hz), b);
        EXPECT_EQ(sa.specific_force_mps2, sb.specific_force_mps2);
        EXPECT_EQ(sa.angular_rate_radps, sb.angular_rate_radps);
    }
}

TEST(Imu, BadConfigAndInputThrow) {
    Rng rng(8);
    ImuConfig c;
    c.rate_hz = 0.0;
    try {
        ImuSimulator imu(c, rng);
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("imu.rate_hz = 0"), std::string::npos) << e.what();
    }
    c = ImuConfig{};
    c.gyro_noise_density_radps_per_sqrt_hz = -1.0;
    EXPECT_THROW(ImuSimulator(c, rng), ConfigError);
    c = ImuConfig{};
    c.T_body_sensor.linear() *= 2.0;
    EXPECT_THROW(ImuSimulator(c, rng), ConfigError);
    ImuSimulator imu(ImuConfig{}, rng);
    imu.measure(at_rest(1.0, Eigen::Vector3d::Zero()), rng);
    EXPECT_THROW(imu.measure(at_rest(0.5, Eigen::Vector3d::Zero()), rng), InputError);
    MotionState bad = at_rest(2.0, Eigen::Vector3d::Zero());
    bad.a_world_mps2.x() = std::nan("");
    EXPECT_THROW(imu.measure(bad, rng), InputError);
}

}  // namespace
}  // namespace scantling::sim
