// The ROV's survey guidance (SPEC §5, issue 14 item 3): the constant-bearing law's speeds and
// directions, the pause on heading or depth error with its hysteresis, the depth loop, a
// simulated approach to a moving target, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <scantling/control/rov_guidance.hpp>
#include <scantling/core/error.hpp>

#include "../planning/expect_error.hpp"

namespace scantling::control {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kDt = 0.05;

GuidanceTarget target_at(const Eigen::Vector3d& p, double yaw_rad = 0.0,
                         const Eigen::Vector2d& v = Eigen::Vector2d::Zero()) {
    return {.p_world_m = p, .v_horizontal_mps = v, .yaw_rad = yaw_rad};
}

TEST(RovGuidance, ConstantBearingApproachesAlongTheLineOfSightBelowKappa) {
    RovGuidance guidance;  // κ 0.4 m/s, Δ 0.5 m
    const GuidanceCommand far = guidance.update({10, 0, -2}, 0.0, target_at({0, 0, -2}), kDt);
    EXPECT_NEAR(far.v_world_mps.x(), -0.4 * 10.0 / std::sqrt(100.0 + 0.25), 1e-12);
    EXPECT_NEAR(far.v_world_mps.y(), 0.0, 1e-12);
    const GuidanceCommand near = guidance.update({0.1, 0.1, -2}, 0.0, target_at({0, 0, -2}), kDt);
    const double e = std::sqrt(0.02);
    EXPECT_NEAR(near.v_world_mps.head<2>().norm(), 0.4 * e / std::sqrt(e * e + 0.25), 1e-12);
    const GuidanceCommand at = guidance.update({0, 0, -2}, 0.0, target_at({0, 0, -2}), kDt);
    EXPECT_EQ(at.v_world_mps.head<2>().norm(), 0.0);
}

TEST(RovGuidance, TheTargetsVelocityIsAddedThenTheSpeedIsClamped) {
    RovGuidance guidance;
    const auto on = guidance.update({0, 0, -2}, 0.0, target_at({0, 0, -2}, 0.0, {0.25, 0}), kDt);
    EXPECT_NEAR(on.v_world_mps.x(), 0.25, 1e-12);
    const auto both = guidance.update({0, 5, -2}, 0.0, target_at({0, 0, -2}, 0.0, {0.45, 0}), kDt);
    EXPECT_NEAR(both.v_world_mps.head<2>().norm(), 0.5, 1e-12);  // max_speed_mps
    EXPECT_LT(both.v_world_mps.y(), -0.3);                       // still closing in
}

TEST(RovGuidance, HeadingErrorPausesTheInspectionMotionWithHysteresis) {
    RovGuidance guidance;  // pause above 15°, resume below 7.5°
    const Eigen::Vector3d p(0, 0, -2);
    const Eigen::Vector2d v_t(0.25, 0.0);
    const auto off = guidance.update(p, 0.0, target_at(p, 30 * kDeg, v_t), kDt);
    EXPECT_TRUE(off.paused);
    EXPECT_NEAR(off.v_world_mps.x(), 0.0, 1e-12);  // the target's motion is held
    EXPECT_NEAR(off.yaw_rate_radps, 0.5, 1e-12);   // k_ψ · 30° clamped to 0.5 rad/s
    EXPECT_TRUE(guidance.update(p, 20 * kDeg, target_at(p, 30 * kDeg, v_t), kDt).paused);  // 10°
    const auto back = guidance.update(p, 25 * kDeg, target_at(p, 30 * kDeg, v_t), kDt);    // 5°
    EXPECT_FALSE(back.paused);
    EXPECT_NEAR(back.v_world_mps.x(), 0.25, 1e-12);
    EXPECT_FALSE(guidance.update(p, 18 * kDeg, target_at(p, 30 * kDeg, v_t), kDt).paused);  // 12°
}

TEST(RovGuidance, DepthErrorPausesAndTheHeaveLoopCorrectsIt) {
    RovGuidance guidance;
    const auto deep = guidance.update({0, 0, -2}, 0.0, target_at({0, 0, -3}), kDt);
    EXPECT_TRUE(deep.paused);
    EXPECT_NEAR(deep.depth_error_m, -1.0, 1e-12);
    EXPECT_NEAR(deep.v_world_mps.z(), -0.3, 1e-12);  // kp · 1 m clamped to the heave limit
}

// A vertical slice: the target descends at 0.25 m/s. The PI alone lags it by v / kp ≈ 0.31 m,
// beyond the 0.3 m pause bound; fed forward, the lag is the integral's transient only.
TEST(RovGuidance, TheTargetsVerticalVelocityIsFedForwardToTheHeave) {
    RovGuidance guidance;
    Eigen::Vector3d p(0.0, 0.0, -1.0);
    Eigen::Vector3d p_target = p;
    double worst_lag_m = 0.0;
    for (int k = 0; k < 400; ++k) {  // 20 s, 5 m down
        GuidanceTarget target = target_at(p_target);
        target.v_vertical_mps = -0.25;
        const GuidanceCommand c = guidance.update(p, 0.0, target, kDt);
        p += c.v_world_mps * kDt;
        p_target.z() -= 0.25 * kDt;
        worst_lag_m = std::max(worst_lag_m, std::abs(p.z() - p_target.z()));
        EXPECT_FALSE(c.paused);
    }
    EXPECT_LT(worst_lag_m, 0.02);
}

// Kinematics (the ROV's velocity loop is fast against these speeds): from 3 m aside, 0.6 m too
// shallow and 40° off, the vehicle catches a target moving at 0.25 m/s along x.
TEST(RovGuidance, CatchesAMovingTargetAndResumes) {
    RovGuidance guidance;
    Eigen::Vector3d p(0.0, -3.0, -1.4);
    double yaw = 40 * kDeg;
    Eigen::Vector3d p_target(0.0, 0.0, -2.0);
    bool paused_at_start = false;
    for (int k = 0; k < 1200; ++k) {  // 60 s
        const GuidanceCommand c =
            guidance.update(p, yaw, target_at(p_target, 0.0, {0.25, 0.0}), kDt);
        if (k == 0) paused_at_start = c.paused;
        p += c.v_world_mps * kDt;
        yaw += c.yaw_rate_radps * kDt;
        if (!c.paused) p_target.x() += 0.25 * kDt;  // the caller holds the target while paused
    }
    EXPECT_TRUE(paused_at_start);
    EXPECT_FALSE(guidance.paused());
    EXPECT_LT((p - p_target).norm(), 0.05);
    EXPECT_LT(std::abs(yaw), 0.5 * kDeg);
}

TEST(RovGuidance, BadInputIsRefusedNamingIt) {
    RovGuidanceConfig config;
    config.resume_fraction = 1.5;
    SCANTLING_EXPECT_ERROR(RovGuidance{config}, ConfigError, "rov_guidance.resume_fraction");
    config = {};
    config.depth.kp = -1.0;
    SCANTLING_EXPECT_ERROR(RovGuidance{config}, ConfigError, "rov_guidance.depth.kp");
    RovGuidance guidance;
    SCANTLING_EXPECT_ERROR(guidance.update({std::nan(""), 0, 0}, 0.0, target_at({0, 0, 0}), kDt),
                           InputError, "rov_guidance.update");
    SCANTLING_EXPECT_ERROR(guidance.update({0, 0, 0}, 0.0, target_at({0, 0, 0}), 0.0), InputError,
                           "dt");
}

}  // namespace
}  // namespace scantling::control
