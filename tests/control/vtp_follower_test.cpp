// The VTP follower's five cases of SPEC §4 with hand-computed geometry, their boundaries, the
// zero-length segment and the input contracts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <scantling/control/vtp_follower.hpp>
#include <scantling/core/error.hpp>

#include "../planning/expect_error.hpp"

namespace scantling::control {
namespace {

constexpr double kExact = 1e-12;  // m: closed-form points, only rounding differs
constexpr double kTol = 0.2;      // WP_tol (SPEC §4)
const VtpConfig kSpec{};          // δ = 2.0 m, λ = 0.2 m

// The segment WP_prev = (0, 0, 0) → WP = (8, 0, 0) (a power of two keeps t exact).
const Eigen::Vector3d kPrev(0.0, 0.0, 0.0);
const Eigen::Vector3d kWp(8.0, 0.0, 0.0);

VtpResult vtp_at(double x, double y, double tolerance_m = kTol) {
    return virtual_target_point(Eigen::Vector3d(x, y, 0.0), kPrev, kWp, tolerance_m, kSpec);
}

void expect_vtp(const VtpResult& result, VtpCase expected_case, const Eigen::Vector3d& vtp) {
    EXPECT_EQ(result.vtp_case, expected_case) << to_string(result.vtp_case);
    EXPECT_TRUE(result.vtp_world_m.isApprox(vtp, kExact) ||
                (result.vtp_world_m - vtp).norm() < kExact)
        << "VTP " << result.vtp_world_m.transpose() << ", expected " << vtp.transpose();
}

TEST(VtpFollower, Case1LeadsAlongThePathByDeltaTimesOneMinusDOverLambda) {
    expect_vtp(vtp_at(3.0, 0.0), VtpCase::kOnPath, {5.0, 0.0, 0.0});    // d = 0: L = δ
    expect_vtp(vtp_at(3.0, 0.1), VtpCase::kOnPath, {4.0, 0.0, 0.0});    // d = λ/2: L = δ/2
    expect_vtp(vtp_at(3.0, -0.15), VtpCase::kOnPath, {3.5, 0.0, 0.0});  // L = δ/4
    const VtpResult result = vtp_at(3.0, 0.1);
    EXPECT_NEAR(result.distance_to_path_m, 0.1, kExact);
    EXPECT_TRUE(result.closest_world_m.isApprox(Eigen::Vector3d(3.0, 0.0, 0.0), kExact));
}

TEST(VtpFollower, Case1IsClippedToTheWaypointWhenLExceedsTheRemainder) {
    expect_vtp(vtp_at(7.5, 0.05), VtpCase::kOnPath, kWp);  // L = 1.5 > |C − WP| = 0.5
    expect_vtp(vtp_at(8.0, 0.1), VtpCase::kOnPath, kWp);   // C exactly at WP: still "between"
}

TEST(VtpFollower, Case2ReturnsToTheClosestPointFromDEqualToLambdaOn) {
    expect_vtp(vtp_at(3.0, 0.2), VtpCase::kOffPath, {3.0, 0.0, 0.0});  // boundary d = λ
    expect_vtp(vtp_at(3.0, 1.0), VtpCase::kOffPath, {3.0, 0.0, 0.0});
    expect_vtp(vtp_at(0.0, -0.5), VtpCase::kOffPath, kPrev);  // C exactly at WP_prev
}

TEST(VtpFollower, CExactlyAtThePreviousWaypointIsBetween) {
    expect_vtp(vtp_at(0.0, 0.1), VtpCase::kOnPath, {1.0, 0.0, 0.0});
}

TEST(VtpFollower, Case3GoesToThePreviousWaypointFromOutsideItsTolerance) {
    expect_vtp(vtp_at(-1.0, 0.05), VtpCase::kBeforeStart, kPrev);
    expect_vtp(vtp_at(-0.25, 0.0, 0.125), VtpCase::kBeforeStart, kPrev);
}

TEST(VtpFollower, Case4InsideTheToleranceActsAsCase1Or2) {
    // |C − WP_prev| = 0.25 = WP_tol exactly: inside. d = λ/2: L = 1 from C = (−0.25, 0, 0).
    expect_vtp(vtp_at(-0.25, 0.1, 0.25), VtpCase::kNearStart, {0.75, 0.0, 0.0});
    expect_vtp(vtp_at(-0.125, 0.5), VtpCase::kNearStart, {-0.125, 0.0, 0.0});  // d ≥ λ: C
}

TEST(VtpFollower, Case5BeyondTheWaypointGoesToIt) {
    expect_vtp(vtp_at(9.0, 0.05), VtpCase::kBeyondWaypoint, kWp);
    expect_vtp(vtp_at(20.0, -3.0), VtpCase::kBeyondWaypoint, kWp);
}

TEST(VtpFollower, ZeroLengthSegmentTargetsTheWaypoint) {
    const Eigen::Vector3d wp(1.0, 2.0, 3.0);
    const VtpResult result =
        virtual_target_point(Eigen::Vector3d(4.0, 6.0, 3.0), wp, wp, kTol, kSpec);
    expect_vtp(result, VtpCase::kBeyondWaypoint, wp);
    EXPECT_NEAR(result.distance_to_path_m, 5.0, kExact);
}

TEST(VtpFollower, ObliqueSegmentInThreeDimensions) {
    // WP_prev → WP along (2, 3, 6)/7, 7 m long; P 1 m along it and 0.05 m off it.
    const Eigen::Vector3d prev(1.0, 2.0, 3.0);
    const Eigen::Vector3d direction = Eigen::Vector3d(2.0, 3.0, 6.0) / 7.0;
    const Eigen::Vector3d normal = Eigen::Vector3d(3.0, -2.0, 0.0).normalized();
    const Eigen::Vector3d wp = prev + 7.0 * direction;
    const Eigen::Vector3d p = prev + 1.0 * direction + 0.05 * normal;
    const VtpResult result = virtual_target_point(p, prev, wp, kTol, kSpec);
    EXPECT_EQ(result.vtp_case, VtpCase::kOnPath);
    EXPECT_NEAR(result.distance_to_path_m, 0.05, kExact);
    EXPECT_NEAR(result.along_segment, 1.0 / 7.0, kExact);
    EXPECT_TRUE(result.vtp_world_m.isApprox(prev + 2.5 * direction, kExact));  // L = 1.5
}

TEST(VtpFollower, VtpStaysOnTheSegmentWithinDeltaOfCAndIsContinuousAcrossLambda) {
    for (double x = -3.0; x <= 11.0; x += 0.05) {
        for (double y = -1.0; y <= 1.0; y += 0.01) {
            const VtpResult result = vtp_at(x, y);
            const Eigen::Vector3d& vtp = result.vtp_world_m;
            EXPECT_NEAR(vtp.y(), 0.0, kExact);  // always on the segment ...
            EXPECT_GE(vtp.x(), std::min(result.closest_world_m.x(), 0.0) - kExact);
            EXPECT_LE(vtp.x(), 8.0 + kExact);  // ... never past WP
            if (result.vtp_case != VtpCase::kBeforeStart &&
                result.vtp_case != VtpCase::kBeyondWaypoint) {
                EXPECT_LE((vtp - result.closest_world_m).norm(), 2.0 + kExact);  // ≤ δ from C
            }
        }
    }
    // Across d = λ the lead L = δ(1 − d/λ) has shrunk to 0: no jump between cases 1 and 2.
    const double below = vtp_at(3.0, 0.2 - 1e-9).vtp_world_m.x();
    const double at = vtp_at(3.0, 0.2).vtp_world_m.x();
    EXPECT_NEAR(below, at, 1e-7);
}

TEST(VtpFollower, BadInputsAreRefused) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    SCANTLING_EXPECT_ERROR(
        virtual_target_point(Eigen::Vector3d(nan, 0.0, 0.0), kPrev, kWp, kTol, kSpec), InputError,
        "p_world_m = (nan, 0, 0)");
    SCANTLING_EXPECT_ERROR(virtual_target_point(Eigen::Vector3d::Zero(), kPrev, kWp, 0.0, kSpec),
                           ConfigError, "virtual_target_point.waypoint_tolerance_m = 0");
    VtpConfig config;
    config.max_path_separation_m = 0.0;
    SCANTLING_EXPECT_ERROR(virtual_target_point(Eigen::Vector3d::Zero(), kPrev, kWp, kTol, config),
                           ConfigError, "vtp.max_path_separation_m = 0");
}

}  // namespace
}  // namespace scantling::control
