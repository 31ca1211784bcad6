#include <scantling/core/error.hpp>
#include <scantling/sim/waypoint_trajectory.hpp>

#include "vehicle_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

using testing::expect_consistent_derivatives;
using testing::expect_consistent_derivatives_along;

constexpr double kExactM = 1e-12;     // the profile ends exactly on s = D
constexpr double kLimitSlack = 1e-9;  // limits hold up to round-off
constexpr double kPi = std::numbers::pi;

WaypointTrajectoryConfig square_mission() {
    WaypointTrajectoryConfig c;
    c.waypoints = {{{0, 0, 1}, 0.0, 1.0},
                   {{4, 0, 1}, kPi / 2, 0.5},
                   {{4, 3, 2}, kPi, 0.0},
                   {{0, 3, 2}, -kPi / 2, 2.0}};
    c.max_speed_mps = 1.5;
    c.max_accel_mps2 = 0.8;
    return c;
}

TEST(WaypointTrajectory, ArrivesAtRestOnEveryWaypointWithItsYaw) {
    const WaypointTrajectory traj(square_mission());
    const auto& wps = traj.config().waypoints;
    for (std::size_t i = 0; i < wps.size(); ++i) {
        const MotionState m = traj.at(traj.arrival_time_s(i));
        EXPECT_LT((m.T_world_body.translation() - wps[i].position_m).norm(), kExactM) << i;
        EXPECT_LT(m.v_world_mps.norm(), kExactM);
        const double yaw = std::atan2(m.T_world_body(1, 0), m.T_world_body(0, 0));
        EXPECT_NEAR(wrap_angle(yaw - wps[i].yaw_rad), 0.0, 1e-9) << i;
    }
    EXPECT_NEAR(traj.duration_s(), traj.arrival_time_s(3) + 2.0, 1e-12);  // last dwell
}

TEST(WaypointTrajectory, DwellHoldsStillAtTheWaypoint) {
    const WaypointTrajectory traj(square_mission());
    const double arrive = traj.arrival_time_s(1);
    for (const double dt : {0.1, 0.25, 0.49}) {
        const MotionState m = traj.at(arrive + dt);
        EXPECT_LT((m.T_world_body.translation() - Eigen::Vector3d(4, 0, 1)).norm(), kExactM);
        EXPECT_EQ(m.v_world_mps.norm(), 0.0);
    }
    EXPECT_GT(traj.at(arrive + 0.6).v_world_mps.norm(), 0.0);  // leaves after 0.5 s
}

TEST(WaypointTrajectory, VelocityAccelerationAndRateAreTheDerivativesOfThePose) {
    const WaypointTrajectory traj(square_mission());
    expect_consistent_derivatives_along(traj, 97);
}

TEST(WaypointTrajectory, TrapezoidalProfileIsDifferentiableInsideItsPhases) {
    WaypointTrajectoryConfig c;
    c.waypoints = {{{0, 0, 0}, 0.0, 0.0}, {{10, 0, 0}, 0.0, 0.0}};
    c.max_speed_mps = 2.0;
    c.max_accel_mps2 = 1.0;
    c.shape = ProfileShape::kTrapezoidal;
    const WaypointTrajectory traj(c);  // phases: [0, 2] accelerate, [2, 5] cruise, [5, 7] brake
    for (const double t : {1.0, 3.5, 6.0}) expect_consistent_derivatives(traj, t);
    EXPECT_NEAR(traj.duration_s(), 7.0, 1e-12);
}

TEST(WaypointTrajectory, RespectsSpeedAccelerationAndYawRateLimits) {
    WaypointTrajectoryConfig c = square_mission();
    c.max_yaw_rate_radps = 0.3;
    const WaypointTrajectory traj(c);
    for (int i = 0; i <= 2000; ++i) {
        const MotionState m = traj.at(traj.duration_s() * i / 2000.0);
        EXPECT_LE(m.v_world_mps.norm(), c.max_speed_mps + kLimitSlack);
        EXPECT_LE(m.a_world_mps2.norm(), c.max_accel_mps2 + kLimitSlack);
        EXPECT_LE(std::abs(m.omega_body_radps.z()), c.max_yaw_rate_radps + kLimitSlack);
    }
}

TEST(WaypointTrajectory, FaceTravelTurnsOnTheSpotThenFliesNoseFirst) {
    WaypointTrajectoryConfig c;
    c.waypoints = {{{0, 0, 0}, 0.0, 0.0}, {{0, 5, 0}, 0.0, 0.0}, {{0, 5, 3}, 0.0, 0.0}};
    c.yaw_mode = YawMode::kFaceTravel;
    const WaypointTrajectory traj(c);
    int moving = 0;
    for (double t = 0.0; t < traj.arrival_time_s(1); t += 0.1) {
        const MotionState m = traj.at(t);
        if (m.v_world_mps.norm() < 1e-3) continue;
        ++moving;
        const Eigen::Vector3d x_body = m.T_world_body.linear().col(0);
        EXPECT_GT(x_body.dot(m.v_world_mps.normalized()), 1.0 - 1e-9) << t;
    }
    // The vertical leg keeps the heading (+y).
    const MotionState climbing = traj.at(0.5 * (traj.arrival_time_s(1) + traj.arrival_time_s(2)));
    EXPECT_GT(climbing.v_world_mps.z(), 0.0);
    EXPECT_NEAR(climbing.T_world_body(1, 0), 1.0, 1e-12);
    EXPECT_GT(moving, 20);
}

TEST(WaypointTrajectory, YawTakesTheShorterWayRound) {
    WaypointTrajectoryConfig c;
    c.waypoints = {{{0, 0, 0}, 3.0, 0.0}, {{1, 0, 0}, -3.0, 0.0}};  // 0.28 rad apart via ±π
    const WaypointTrajectory traj(c);
    double turned = 0.0;
    for (int i = 0; i < 1000; ++i) {
        turned += traj.at(traj.duration_s() * (i + 0.5) / 1000).omega_body_radps.z() *
                  traj.duration_s() / 1000;
    }
    EXPECT_NEAR(turned, 2.0 * kPi - 6.0, 1e-5);  // midpoint rule on a smooth profile
}

TEST(WaypointTrajectory, SingleWaypointIsAtRestForever) {
    WaypointTrajectoryConfig c;
    c.waypoints = {{{1, 2, 3}, 0.5, 0.0}};
    const WaypointTrajectory traj(c);
    EXPECT_EQ(traj.duration_s(), 0.0);
    EXPECT_EQ(traj.at(10.0).T_world_body.translation(), Eigen::Vector3d(1, 2, 3));
    EXPECT_EQ(traj.at(10.0).stamp_s, 10.0);
}

TEST(WaypointTrajectory, BadConfigNamesTheField) {
    WaypointTrajectoryConfig c = square_mission();
    c.waypoints[2].dwell_s = -1.0;
    try {
        WaypointTrajectory traj(c);
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("waypoint_trajectory.waypoints[2].dwell_s"),
                  std::string::npos)
            << e.what();
    }
    c = square_mission();
    c.max_accel_mps2 = 0.0;
    EXPECT_THROW(WaypointTrajectory{c}, ConfigError);
    c = square_mission();
    c.waypoints[0].position_m.x() = std::nan("");
    EXPECT_THROW(WaypointTrajectory{c}, ConfigError);
    EXPECT_THROW(WaypointTrajectory{WaypointTrajectoryConfig{}}, ConfigError);  // no waypoints
    EXPECT_THROW(WaypointTrajectory(square_mission()).arrival_time_s(4), InputError);
}

}  // namespace
}  // namespace scantling::sim
