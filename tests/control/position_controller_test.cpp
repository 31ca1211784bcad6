// The position controller on a simulated first-order velocity plant (τ = 0.3 s): reaching a
// waypoint within WP_tol, the speed and yaw-rate limits, the yaw's shortest way round, and the
// input and config contracts.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include <scantling/control/position_controller.hpp>
#include <scantling/core/error.hpp>

#include "../planning/expect_error.hpp"
#include "velocity_plant.hpp"

namespace scantling::control {
namespace {

constexpr double kDt = 0.05;            // s: 20 Hz set-points
constexpr double kWaypointTolM = 0.20;  // SPEC §4's WP_tol
constexpr double kSpeedSlack = 1e-12;   // m/s: the clamp's rounding

TEST(PositionController, DrivesTheVelocityPlantToAWaypointAndHoldsIt) {
    PositionController controller;
    test::Plant3d plant{Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d::Zero()};
    const Eigen::Vector3d target(3.0, -2.0, 2.0);  // 3.7 m away
    double reached_s = -1.0;
    for (int k = 1; k <= 400; ++k) {  // 20 s
        const VelocityCommand command = controller.update(plant.p, 0.0, target, 0.0, kDt);
        EXPECT_LE(command.v_cmd_world_mps.norm(), 1.0 + kSpeedSlack);
        plant.step(command.v_cmd_world_mps, kDt, Eigen::Vector3d::Zero());
        const double error_m = (plant.p - target).norm();
        if (reached_s < 0.0 && error_m <= kWaypointTolM) reached_s = k * kDt;
        if (reached_s >= 0.0) {
            EXPECT_LE(error_m, kWaypointTolM) << "left the waypoint";
        }
    }
    // 3.7 m at 1 m/s is 3.7 s plus the braking: reached within 6 s.
    EXPECT_GT(reached_s, 0.0);
    EXPECT_LE(reached_s, 6.0);
    EXPECT_LE((plant.p - target).norm(), 0.01);
}

TEST(PositionController, DoesNotIntegrateWhileTheSpeedClampActs) {
    // Chasing a target that stays 2 m ahead (a VTP δ ahead) along a diagonal: the clamp acts
    // on every update, and an integral of the 2 m along-track error would wind up, each axis
    // its own share, and push the vehicle off its line through the clamp's cross-track part.
    PositionController controller;
    test::Plant3d plant{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    const Eigen::Vector3d along = Eigen::Vector3d(3.0, -1.0, 0.5).normalized();
    double largest_offset_m = 0.0;
    for (int k = 1; k <= 200; ++k) {  // 10 s
        const Eigen::Vector3d target = along * (along.dot(plant.p) + 2.0);
        const VelocityCommand command = controller.update(plant.p, 0.0, target, 0.0, kDt);
        EXPECT_TRUE(command.speed_clamped);
        plant.step(command.v_cmd_world_mps, kDt, Eigen::Vector3d::Zero());
        largest_offset_m =
            std::max(largest_offset_m, (plant.p - along * along.dot(plant.p)).norm());
    }
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(controller.axis(i).integral(), 0.0) << i;
    EXPECT_LT(largest_offset_m, 1e-9);
    // Within reach the integral works again.
    controller.update(plant.p, 0.0, plant.p + Eigen::Vector3d(0.1, 0.0, 0.0), 0.0, kDt);
    EXPECT_GT(controller.axis(0).integral(), 0.0);
}

TEST(PositionController, YawTurnsTheShortWayRoundAndIsRateLimited) {
    PositionController controller;
    const Eigen::Vector3d p = Eigen::Vector3d::Zero();
    // From −π + 0.1 to π − 0.1 is −0.2 rad the short way: k_ψ = 1/s gives −0.2 rad/s.
    const double pi = std::numbers::pi;
    EXPECT_NEAR(controller.update(p, -pi + 0.1, p, pi - 0.1, kDt).yaw_rate_cmd_radps, -0.2, 1e-12);
    EXPECT_EQ(controller.update(p, 0.0, p, 1.5, kDt).yaw_rate_cmd_radps, 0.5);  // clamped
    EXPECT_EQ(controller.update(p, 0.3, p, std::nullopt, kDt).yaw_rate_cmd_radps, 0.0);
    EXPECT_NEAR(wrap_angle_rad(2.5 * pi), 0.5 * pi, 1e-12);
    EXPECT_NEAR(wrap_angle_rad(-pi), pi, 1e-12);
    EXPECT_NEAR(wrap_angle_rad(-0.5), -0.5, 1e-15);
}

TEST(PositionController, TheSpeedClampKeepsTheDirection) {
    PositionController controller;
    const VelocityCommand command = controller.update(
        Eigen::Vector3d::Zero(), 0.0, Eigen::Vector3d(30.0, 40.0, 0.0), std::nullopt, kDt);
    EXPECT_TRUE(command.speed_clamped);
    EXPECT_NEAR(command.v_cmd_world_mps.norm(), 1.0, kSpeedSlack);
    // Clamped as a vector, not per axis (which would give the diagonal (1, 1)/√2).
    EXPECT_NEAR(command.v_cmd_world_mps.x(), 0.6, kSpeedSlack);
    EXPECT_NEAR(command.v_cmd_world_mps.y(), 0.8, kSpeedSlack);
}

TEST(PositionController, NonFiniteInputsThrowAndNeverGiveANanCommand) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    PositionController controller;
    const Eigen::Vector3d p = Eigen::Vector3d::Zero();
    SCANTLING_EXPECT_ERROR(controller.update(Eigen::Vector3d(0.0, nan, 0.0), 0.0, p, 0.0, kDt),
                           InputError, "p_world_m = (0, nan, 0)");
    SCANTLING_EXPECT_ERROR(controller.update(p, 0.0, Eigen::Vector3d::Constant(nan), 0.0, kDt),
                           InputError, "p_target_world_m");
    SCANTLING_EXPECT_ERROR(controller.update(p, nan, p, 0.0, kDt), InputError, "yaw_rad = nan");
    SCANTLING_EXPECT_ERROR(controller.update(p, 0.0, p, nan, kDt), InputError,
                           "target_yaw_rad = nan");
    SCANTLING_EXPECT_ERROR(controller.update(p, 0.0, p, 0.0, 0.0), InputError, "dt_s = 0");
    const VelocityCommand command =
        controller.update(p, 0.0, Eigen::Vector3d(1.0, 0.0, 0.0), 0.0, kDt);
    EXPECT_TRUE(command.v_cmd_world_mps.allFinite());
}

TEST(PositionController, BadConfigsAreRefusedNamingTheField) {
    PositionControllerConfig config;
    config.max_speed_mps = 0.0;
    SCANTLING_EXPECT_ERROR(PositionController{config}, ConfigError,
                           "position_controller.max_speed_mps = 0");
    config = {};
    config.kd_s = -0.3;
    SCANTLING_EXPECT_ERROR(PositionController{config}, ConfigError,
                           "position_controller.kd_s = -0.3");
}

TEST(ClampAlongError, KeepsTheCrossTrackPartAndCutsTheApproach) {
    // Chasing a target 2 m ahead along x at kp = 2 (4 m/s) while the integral holds 0.5 m/s
    // against a crosswind along y: the limit takes speed off x only.
    const Eigen::Vector3d v = clamp_along_error({4.0, 0.5, 0.0}, {2.0, 0.0, 0.0}, 1.0);
    EXPECT_NEAR(v.y(), 0.5, 1e-12);
    EXPECT_NEAR(v.x(), std::sqrt(1.0 - 0.25), 1e-12);
    EXPECT_NEAR(v.norm(), 1.0, 1e-12);
    // A cross-track part above the limit is all that is left, at the limit.
    const Eigen::Vector3d across = clamp_along_error({3.0, 2.0, 0.0}, {1.0, 0.0, 0.0}, 1.0);
    EXPECT_NEAR(across.x(), 0.0, 1e-12);
    EXPECT_NEAR(across.y(), 1.0, 1e-12);
    // No error direction: the whole vector scales.
    const Eigen::Vector3d uniform =
        clamp_along_error({3.0, 4.0, 0.0}, Eigen::Vector3d::Zero(), 1.0);
    EXPECT_NEAR(uniform.x(), 0.6, 1e-12);
    EXPECT_NEAR(uniform.y(), 0.8, 1e-12);
}

}  // namespace
}  // namespace scantling::control
