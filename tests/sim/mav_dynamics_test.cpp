#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/sim/mav_dynamics.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace scantling::sim {
namespace {

constexpr double kOneMinusInvE = 0.6321205588285577;  // first-order response at t = τ
constexpr double kExactStep = 1e-9;  // the unsaturated update is the exact ODE solution

MavDynamicsConfig calm(double drag_per_s = 0.0) {
    MavDynamicsConfig c;
    c.dt_s = 0.001;
    c.velocity_time_constant_s = 0.4;
    c.drag_coefficient_per_s = drag_per_s;
    c.max_accel_mps2 = 100.0;  // unsaturated loop for the step-response tests
    return c;
}

MavDynamics run(const MavDynamicsConfig& c, const MavCommand& cmd, double seconds,
                std::uint64_t seed = 7) {
    MavDynamics mav(c, Eigen::Isometry3d::Identity(), seed);
    const auto steps = static_cast<int>(std::lround(seconds / c.dt_s));
    for (int i = 0; i < steps; ++i) mav.step(cmd);
    return mav;
}

TEST(MavDynamics, VelocityStepReaches63PercentAtTheTimeConstant) {
    const MavDynamicsConfig c = calm();
    const MavDynamics mav = run(c, {Eigen::Vector3d(2.0, 0.0, 0.0), 0.0}, 0.4);
    EXPECT_NEAR(mav.state().v_world_mps.x() / 2.0, kOneMinusInvE, kExactStep);
    EXPECT_NEAR(mav.state().stamp_s, 0.4, 1e-15);
}

TEST(MavDynamics, WithDragTheResponseDecaysAtOneOverTauPlusC) {
    MavDynamicsConfig c = calm(0.5);
    const MavDynamics mav = run(c, {Eigen::Vector3d(0.0, 1.0, 0.0), 0.0}, 1.0);
    const double rate = 1.0 / 0.4 + 0.5;
    const double v_ss = 1.0 / (1.0 + 0.5 * 0.4);
    EXPECT_NEAR(mav.state().v_world_mps.y(), v_ss * (1.0 - std::exp(-rate * 1.0)), kExactStep);
}

TEST(MavDynamics, AccelerationLimitCapsTheInitialResponse) {
    MavDynamicsConfig c = calm();
    c.max_accel_mps2 = 2.0;
    MavDynamics mav(c, Eigen::Isometry3d::Identity(), 1);
    mav.step({Eigen::Vector3d(3.0, 0.0, 0.0), 0.0});  // demand 7.5 m/s² > 2
    EXPECT_NEAR(mav.state().a_world_mps2.x(), 2.0, 1e-12);
    EXPECT_NEAR(mav.state().v_world_mps.x(), 2.0 * c.dt_s, 1e-15);
}

TEST(MavDynamics, SpeedCommandIsClippedToTheLimit) {
    MavDynamicsConfig c = calm();
    c.max_speed_mps = 1.0;
    const MavDynamics mav = run(c, {Eigen::Vector3d(3.0, 4.0, 0.0), 0.0}, 6.0);
    EXPECT_NEAR(mav.state().v_world_mps.norm(), 1.0, 1e-6);  // e^(-15) of the step left
}

TEST(MavDynamics, SteadyWindPushesAHoveringMavDownwindAtTheDragModelSpeed) {
    MavDynamicsConfig c = calm(0.4);
    c.velocity_time_constant_s = 0.3;
    c.wind.mean = Eigen::Vector3d(0.0, 5.0, 0.0);  // SPEC §4: 5 m/s lateral wind
    const MavDynamics mav = run(c, {}, 5.0);
    const Eigen::Vector3d expected =
        mav_steady_velocity_mps(c, Eigen::Vector3d::Zero(), c.wind.mean);
    EXPECT_NEAR(expected.y(), 5.0 * 0.12 / 1.12, 1e-12);
    EXPECT_LT((mav.state().v_world_mps - expected).norm(), 1e-6);
    EXPECT_GT(mav.state().T_world_body.translation().y(), 2.0);  // drifted downwind
    // It leans into the wind: drag pushes +y, so the thrust (body z) leans towards −y.
    EXPECT_LT(mav.state().T_world_body.linear()(1, 2), -0.01);
}

TEST(MavDynamics, TiltsTowardsItsAccelerationAndKeepsTheCommandedYaw) {
    MavDynamicsConfig c = calm();
    c.attitude_time_constant_s = 0.0;  // tilt = thrust direction, exactly
    MavDynamics mav(c, Eigen::Isometry3d(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ())), 3);
    for (int i = 0; i < 100; ++i) mav.step({Eigen::Vector3d(1.0, 0.0, 0.0), 0.0});
    const Eigen::Matrix3d R = mav.state().T_world_body.linear();
    const Eigen::Vector3d expected_z =
        (mav.state().a_world_mps2 + Eigen::Vector3d(0, 0, c.gravity_mps2)).normalized();
    EXPECT_LT((R.col(2) - expected_z).norm(), 1e-12);  // no drag: thrust = a + g
    EXPECT_GT(R(0, 2), 0.01);
    EXPECT_NEAR(std::atan2(R.col(0).y(), R.col(0).x()), 0.7, 0.05);  // heading kept (tilt aside)
    EXPECT_NEAR(mav.yaw_rad(), 0.7, 1e-15);
}

TEST(MavDynamics, AttitudeLagKeepsBodyRatesBoundedOnAVelocityStep) {
    // A 1 m/s step asks for 3.3 m/s², a 0.33 rad tilt: in one 5 ms step that is 65 rad/s.
    MavDynamicsConfig c;
    double max_rate_lagged = 0.0, max_rate_instant = 0.0;
    for (const double tau_att : {0.05, 0.0}) {
        c.attitude_time_constant_s = tau_att;
        MavDynamics mav(c, Eigen::Isometry3d::Identity(), 1);
        double& max_rate = tau_att > 0.0 ? max_rate_lagged : max_rate_instant;
        for (int i = 0; i < 400; ++i) {
            max_rate = std::max(
                max_rate, mav.step({Eigen::Vector3d(1.0, 0, 0), 0.0}).omega_body_radps.norm());
        }
    }
    EXPECT_GT(max_rate_instant, 40.0);
    EXPECT_LT(max_rate_lagged, 7.0);  // at most the initial tilt error / τ_att = 0.33 / 0.05
}

TEST(MavDynamics, IntegratingTheReportedRatesReproducesThePose) {
    MavDynamicsConfig c = calm(0.3);
    c.wind.mean = Eigen::Vector3d(1.0, -2.0, 0.0);
    c.wind.sigma = Eigen::Vector3d(1.0, 1.0, 0.3);
    c.max_accel_mps2 = 3.0;
    MavDynamics mav(c, Eigen::Isometry3d::Identity(), 11);
    for (int i = 0; i < 3000; ++i) {
        const MotionState prev = mav.state();
        const double t = i * c.dt_s;
        const MotionState& next =
            mav.step({Eigen::Vector3d(std::sin(t), std::cos(2 * t), 0.3), 0.5 * std::sin(t)});
        const double dt = c.dt_s;
        const Eigen::Vector3d p = prev.T_world_body.translation() + prev.v_world_mps * dt +
                                  0.5 * next.a_world_mps2 * dt * dt;
        ASSERT_LT((p - next.T_world_body.translation()).norm(), 1e-12) << i;
        const Eigen::Matrix3d R = prev.T_world_body.linear() * so3_exp(next.omega_body_radps * dt);
        ASSERT_LT((R - next.T_world_body.linear()).norm(), 1e-9) << i;
    }
}

TEST(MavDynamics, YawRateFollowsItsCommandWithTheLag) {
    MavDynamicsConfig c = calm();
    c.yaw_rate_time_constant_s = 0.1;
    const MavDynamics mav = run(c, {Eigen::Vector3d::Zero(), 0.5}, 0.1);
    EXPECT_NEAR(mav.yaw_rate_radps(), 0.5 * kOneMinusInvE, 1e-12);
}

TEST(MavDynamics, SameSeedSameFlightDifferentSeedDifferentGusts) {
    MavDynamicsConfig c = calm(0.4);
    c.wind.sigma = Eigen::Vector3d(2.0, 2.0, 0.5);
    const MavCommand cmd{Eigen::Vector3d(1.0, 0.0, 0.0), 0.1};
    const MavDynamics a = run(c, cmd, 2.0, 42), b = run(c, cmd, 2.0, 42), d = run(c, cmd, 2.0, 43);
    EXPECT_EQ(a.state().T_world_body.matrix(), b.state().T_world_body.matrix());
    EXPECT_EQ(a.state().v_world_mps, b.state().v_world_mps);
    EXPECT_GT((a.state().T_world_body.translation() - d.state().T_world_body.translation()).norm(),
              1e-3);
}

TEST(MavDynamics, BadConfigNamesTheField) {
    MavDynamicsConfig c;
    c.velocity_time_constant_s = 0.0;
    try {
        MavDynamics mav(c, Eigen::Isometry3d::Identity(), 1);
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("mav.velocity_time_constant_s"), std::string::npos);
    }
    c = {};
    c.wind.sigma.x() = -1.0;
    try {
        MavDynamics mav(c, Eigen::Isometry3d::Identity(), 1);
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("mav.wind.sigma"), std::string::npos);
    }
    c = {};
    c.dt_s = -0.01;
    EXPECT_THROW(MavDynamics(c, Eigen::Isometry3d::Identity(), 1), ConfigError);
    MavDynamics mav(MavDynamicsConfig{}, Eigen::Isometry3d::Identity(), 1);
    EXPECT_THROW(mav.step({Eigen::Vector3d(NAN, 0, 0), 0.0}), InputError);
}

}  // namespace
}  // namespace scantling::sim
