#include <scantling/core/error.hpp>
#include <scantling/sim/rov_dynamics.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

constexpr double kOneMinusInvE = 0.6321205588285577;
constexpr double kExactStep = 1e-9;  // closed-form per-step solution, round-off only

RovDynamicsConfig still_water(double thrust_tau_s) {
    RovDynamicsConfig c;
    c.dt_s = 0.01;
    c.damping_time_constant_s = Eigen::Vector4d(1.2, 0.9, 0.7, 0.5);
    c.thrust_time_constant_s = thrust_tau_s;
    return c;
}

void run(RovDynamics& rov, const RovCommand& cmd, double seconds) {
    const auto steps = static_cast<int>(std::lround(seconds / rov.config().dt_s));
    for (int i = 0; i < steps; ++i) rov.step(cmd);
}

TEST(RovDynamics, ImmediateThrustGivesAFirstOrderResponsePerAxis) {
    const RovDynamicsConfig c = still_water(0.0);
    for (int axis = 0; axis < 4; ++axis) {
        RovDynamics rov(c, Eigen::Isometry3d::Identity(), 1);
        Eigen::Vector4d cmd = Eigen::Vector4d::Zero();
        cmd[axis] = 0.4;
        run(rov, {cmd[0], cmd[1], cmd[2], cmd[3]}, c.damping_time_constant_s[axis]);
        EXPECT_NEAR(rov.water_velocity()[axis] / 0.4, kOneMinusInvE, kExactStep) << axis;
    }
}

TEST(RovDynamics, ThrusterLagGivesTheTwoPoleResponse) {
    const RovDynamicsConfig c = still_water(0.2);
    RovDynamics rov(c, Eigen::Isometry3d::Identity(), 1);
    const double tau = 1.2, tau_t = 0.2;
    for (int i = 1; i <= 300; ++i) {
        rov.step({0.8, 0.0, 0.0, 0.0});
        const double t = i * c.dt_s;
        const double expected =
            0.8 * (1.0 - (tau * std::exp(-t / tau) - tau_t * std::exp(-t / tau_t)) / (tau - tau_t));
        ASSERT_NEAR(rov.water_velocity()[0], expected, kExactStep) << t;
    }
}

TEST(RovDynamics, EqualPolesUseTheDoublePoleLimit) {
    RovDynamicsConfig c = still_water(0.5);
    c.damping_time_constant_s[0] = 0.5;
    RovDynamics rov(c, Eigen::Isometry3d::Identity(), 1);
    run(rov, {1.0, 0.0, 0.0, 0.0}, 1.0);
    const double t = 1.0, tau = 0.5;
    EXPECT_NEAR(rov.water_velocity()[0], 1.0 - (1.0 + t / tau) * std::exp(-t / tau), kExactStep);
}

TEST(RovDynamics, CurrentCarriesAVehicleWithoutCommand) {
    RovDynamicsConfig c = still_water(0.2);
    c.current.mean = Eigen::Vector3d(0.3, -0.1, 0.0);
    RovDynamics rov(c, Eigen::Isometry3d::Identity(), 1);
    run(rov, {}, 10.0);
    EXPECT_LT((rov.state().v_world_mps - c.current.mean).norm(), 1e-15);
    EXPECT_LT((rov.state().T_world_body.translation() - 10.0 * c.current.mean).norm(), 1e-12);
}

TEST(RovDynamics, SurgeFollowsTheHeadingAndHeaveIsUp) {
    RovDynamicsConfig c = still_water(0.0);
    const Eigen::Isometry3d start(
        Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
    RovDynamics rov(c, start, 1);
    run(rov, {0.5, 0.0, 0.2, 0.0}, 8.0);
    const Eigen::Vector3d v = rov.state().v_world_mps;
    EXPECT_NEAR(v.x(), 0.0, 1e-9);
    EXPECT_NEAR(v.y(), 0.5, 1e-3);  // e^(-8/1.2) of the step left
    EXPECT_NEAR(v.z(), 0.2, 1e-4);
    EXPECT_NEAR(rov.state().T_world_body.linear()(2, 2), 1.0, 1e-15);  // level
}

TEST(RovDynamics, YawRateTurnsTheVehicleAndCommandsAreClipped) {
    RovDynamicsConfig c = still_water(0.0);
    c.max_command[3] = 0.2;
    RovDynamics rov(c, Eigen::Isometry3d::Identity(), 1);
    run(rov, {0.0, 0.0, 0.0, 5.0}, 10.0);
    EXPECT_NEAR(rov.water_velocity()[3], 0.2, 1e-9);
    EXPECT_NEAR(rov.state().omega_body_radps.z(), 0.2, 1e-9);
    EXPECT_GT(rov.yaw_rad(), 1.5);  // ~ 0.2 (10 − 0.5)
}

TEST(RovDynamics, SlowlyVaryingCurrentIsSeededAndDeterministic) {
    RovDynamicsConfig c = still_water(0.2);
    c.current.sigma = Eigen::Vector3d(0.1, 0.1, 0.0);
    RovDynamics a(c, Eigen::Isometry3d::Identity(), 5), b(c, Eigen::Isometry3d::Identity(), 5);
    RovDynamics d(c, Eigen::Isometry3d::Identity(), 6);
    for (RovDynamics* rov : {&a, &b, &d}) run(*rov, {0.3, 0.0, 0.0, 0.1}, 5.0);
    EXPECT_EQ(a.state().T_world_body.matrix(), b.state().T_world_body.matrix());
    EXPECT_NE(a.state().T_world_body.translation(), d.state().T_world_body.translation());
}

// A contact: 6 m/s² along world y for 50 ms on a vehicle facing +y (yaw 90°) is a 0.3 m/s kick
// into its surge, which the damping then takes back; the acceleration shows in the state (the
// IMU's input) while the push lasts, and only then.
TEST(RovDynamics, APushKicksTheVehicleOverItsWindow) {
    RovDynamicsConfig c = still_water(0.0);
    c.pushes.push_back({.start_s = 1.0, .duration_s = 0.05, .acceleration_world_mps2 = {0, 6, 0}});
    const Eigen::Isometry3d facing_y(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitZ()));
    RovDynamics rov(c, facing_y, 1);
    run(rov, {}, 1.0);
    EXPECT_NEAR(rov.state().a_world_mps2.norm(), 0.0, 1e-12);
    run(rov, {}, 0.05);
    EXPECT_NEAR(rov.water_velocity()[0], 0.3 * std::exp(-0.005 / 1.2), 0.02);  // surge
    EXPECT_NEAR(rov.state().a_world_mps2.y(), 6.0, 1.0);
    run(rov, {}, 5.0);
    EXPECT_LT(rov.water_velocity().head<3>().norm(), 0.3 * std::exp(-4.0));
}

TEST(RovDynamics, BadConfigNamesTheField) {
    RovDynamicsConfig c;
    c.damping_time_constant_s[2] = 0.0;
    try {
        RovDynamics rov(c, Eigen::Isometry3d::Identity(), 1);
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("rov.damping_time_constant_s[2]"), std::string::npos)
            << e.what();
    }
    c = {};
    c.current.correlation_time_s = 0.0;
    EXPECT_THROW(RovDynamics(c, Eigen::Isometry3d::Identity(), 1), ConfigError);
    c = {};
    c.thrust_time_constant_s = -1.0;
    EXPECT_THROW(RovDynamics(c, Eigen::Isometry3d::Identity(), 1), ConfigError);
    c = {};
    c.pushes.push_back({.start_s = 1.0, .duration_s = 0.0});
    try {
        RovDynamics rov(c, Eigen::Isometry3d::Identity(), 1);
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("rov.pushes[0].duration_s"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace scantling::sim
