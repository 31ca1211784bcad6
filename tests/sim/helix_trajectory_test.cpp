#include <scantling/core/error.hpp>
#include <scantling/sim/helix_trajectory.hpp>

#include "vehicle_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

using testing::expect_consistent_derivatives_along;

constexpr double kPi = std::numbers::pi;
constexpr double kFormulaM = 1e-12;  // same formula up to cos(π − x) = −cos x round-off

double yaw_of(const MotionState& m) {
    return std::atan2(m.T_world_body(1, 0), m.T_world_body(0, 0));
}

TEST(HelixTrajectory, FollowsTheSpecFormulaExactly) {
    HelixTrajectoryConfig c;
    c.x0_m = 1.5;
    c.y0_m = -2.0;
    c.z0_m = 0.3;
    c.radius_m = 2.0;
    c.omega_radps = 0.25;
    c.v_z_mps = 0.1;
    c.yaw0_rad = 0.4;
    c.rotations = 5.0;
    const HelixTrajectory helix(c);
    EXPECT_NEAR(helix.duration_s(), 2.0 * kPi * 5.0 / 0.25, 1e-9);
    for (int i = 0; i <= 50; ++i) {
        const double t = helix.duration_s() * i / 50.0;
        const MotionState m = helix.at(t);
        const double w = c.omega_radps;
        const Eigen::Vector3d expected(-c.radius_m * std::cos(w * t) + c.x0_m,
                                       c.radius_m * std::sin(w * t) + c.y0_m,
                                       c.v_z_mps * t + c.z0_m);
        EXPECT_LT((m.T_world_body.translation() - expected).norm(), kFormulaM) << t;
        EXPECT_NEAR(wrap_angle(yaw_of(m) - (-w * t + c.yaw0_rad)), 0.0, 1e-12) << t;
        EXPECT_EQ(m.stamp_s, t);
    }
}

TEST(HelixTrajectory, ZeroYawOffsetLooksAtTheAxis) {
    const HelixTrajectory helix(HelixTrajectoryConfig{});
    for (const double t : {0.0, 3.0, 40.0}) {
        const MotionState m = helix.at(t);
        Eigen::Vector3d to_axis = -m.T_world_body.translation();
        to_axis.z() = 0.0;
        EXPECT_GT(m.T_world_body.linear().col(0).dot(to_axis.normalized()), 1.0 - 1e-12);
    }
}

TEST(HelixTrajectory, DerivativesMatchThePose) {
    HelixTrajectoryConfig c;
    c.rotations = 1.0;
    c.v_z_mps = 0.2;
    expect_consistent_derivatives_along(HelixTrajectory(c), 37);
}

TEST(OrbitTrajectory, StartsAtTheStartAngleAndCirclesAtTheRadius) {
    OrbitTrajectoryConfig c;
    c.centre_m = Eigen::Vector3d(3, 4, 2);
    c.radius_m = 2.5;
    c.start_angle_rad = kPi / 2;
    c.angular_rate_radps = 0.4;
    c.turns = 2.0;
    const OrbitTrajectory orbit(c);
    EXPECT_LT((orbit.at(0.0).T_world_body.translation() - Eigen::Vector3d(3, 6.5, 2)).norm(),
              1e-12);
    for (int i = 0; i <= 40; ++i) {
        const MotionState m = orbit.at(orbit.duration_s() * i / 40.0);
        const Eigen::Vector3d r = m.T_world_body.translation() - c.centre_m;
        EXPECT_NEAR(r.norm(), 2.5, 1e-12);
        EXPECT_NEAR(r.z(), 0.0, 1e-12);
        EXPECT_NEAR(m.v_world_mps.norm(), 2.5 * 0.4, 1e-12);
    }
    // Two turns bring it back to the start.
    EXPECT_LT((orbit.at(orbit.duration_s()).T_world_body.translation() -
               orbit.at(0.0).T_world_body.translation())
                  .norm(),
              1e-9);
}

TEST(OrbitTrajectory, FaceTravelHeadingFollowsTheVelocityBothWaysRound) {
    for (const double rate : {0.3, -0.3}) {
        OrbitTrajectoryConfig c;
        c.angular_rate_radps = rate;
        c.heading = OrbitHeading::kFaceTravel;
        const OrbitTrajectory orbit(c);
        for (const double t : {0.5, 7.0, 15.0}) {
            const MotionState m = orbit.at(t);
            EXPECT_GT(m.T_world_body.linear().col(0).dot(m.v_world_mps.normalized()), 1 - 1e-12);
        }
        expect_consistent_derivatives_along(orbit, 19);
    }
}

TEST(OrbitTrajectory, RestsOutsideItsTimeSpan) {
    const OrbitTrajectory orbit(OrbitTrajectoryConfig{});
    EXPECT_EQ(orbit.at(-1.0).v_world_mps.norm(), 0.0);
    EXPECT_EQ(orbit.at(orbit.duration_s() + 1.0).omega_body_radps.norm(), 0.0);
}

TEST(OrbitTrajectory, BadConfigNamesTheField) {
    OrbitTrajectoryConfig c;
    c.radius_m = 0.0;
    try {
        OrbitTrajectory orbit(c);
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("orbit_trajectory.radius_m"), std::string::npos);
    }
    c = {};
    c.angular_rate_radps = 0.0;
    EXPECT_THROW(OrbitTrajectory{c}, ConfigError);
    HelixTrajectoryConfig h;
    h.rotations = -1.0;
    try {
        HelixTrajectory helix(h);
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("helix_trajectory.rotations"), std::string::npos);
    }
}

}  // namespace
}  // namespace scantling::sim
