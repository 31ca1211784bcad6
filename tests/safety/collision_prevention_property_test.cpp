// SPEC §3 collision prevention over seeded random clouds and velocities (the nearest frustum
// point against a brute force, never a command into a wall closer than d_min), a kinematic
// approach into a wall, and the behaviours SPEC §3 does not promise, pinned.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <scantling/core/random.hpp>
#include <scantling/safety/collision_prevention.hpp>

#include "test_clouds.hpp"

namespace scantling::safety {
namespace {

using namespace test;

constexpr double kExact = 1e-12;            // m or m/s: closed-form values, only rounding differs
const CollisionPreventionConfig kConfig{};  // d_att 2.0, d_min 0.8, d_r 0.35, K 1, v_max 1

TEST(CollisionPrevention, SeededPropertyNearestFrustumPointMatchesBruteForce) {
    Rng rng(13);
    const double tan_half = std::tan(deg(22.5));
    for (int trial = 0; trial < 300; ++trial) {
        std::vector<Vector3d> points(60);
        for (auto& p : points)
            p = Vector3d(rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5));
        const Vector3d v = rng.normal3(1.0);
        const auto result = prevent_collision(v, cloud_of(points), kConfig);
        // Brute force: the angles off the velocity by atan2 in the frustum's own axes.
        const auto frustum = make_frustum(v, kConfig);
        double d_o = std::numeric_limits<double>::infinity();
        for (const auto& p : points) {
            const double a = p.dot(frustum->axis_f);
            const bool in = a >= 0.35 && a <= 2.0 &&
                            std::abs(p.dot(frustum->horizontal_h)) / a <= tan_half &&
                            std::abs(p.dot(frustum->vertical_u)) / a <= tan_half;
            if (in) d_o = std::min(d_o, p.norm());
        }
        ASSERT_EQ(result.d_o_m.has_value(), std::isfinite(d_o)) << "trial " << trial;
        if (result.d_o_m) {
            EXPECT_NEAR(*result.d_o_m, d_o, kExact) << "trial " << trial;
        }
        if (d_o <= kConfig.d_min_m) {
            EXPECT_TRUE(result.v_att_body_mps.isZero());
        }
        EXPECT_LE(result.v_rep_body_mps.norm(), kConfig.max_speed_mps + kExact);
    }
}

TEST(CollisionPrevention, SeededPropertyNeverMovesIntoAWallCloserThanDmin) {
    // Random velocity, a wall whose nearest point is within 20° of it and closer than d_min:
    // the command never has a component towards the wall, whatever the desired speed.
    Rng rng(7);
    for (int trial = 0; trial < 200; ++trial) {
        const Vector3d f = rng.normal3(1.0).normalized();
        const Vector3d tilt_axis = f.unitOrthogonal();
        const Eigen::AngleAxisd tilt(deg(rng.uniform(0.0, 20.0)),
                                     Eigen::AngleAxisd(rng.uniform(0.0, 6.3), f) * tilt_axis);
        const Vector3d n = tilt * f;
        const double wall_m = rng.uniform(0.40, 0.79);
        const Vector3d v = f * rng.uniform(0.1, 5.0);
        const auto result = prevent_collision(v, plane_patch(n, wall_m, 1.5), kConfig);
        EXPECT_EQ(result.lambda, 0.0) << "trial " << trial;
        EXPECT_LT(result.v_cmd_body_mps.dot(n), 0.0) << "trial " << trial;
        EXPECT_LE(result.v_cmd_body_mps.norm(), kConfig.max_speed_mps + kExact);
    }
}

/// Closest approach to a wall ahead when the command drives a first-order velocity loop
/// (τ = 0.3 s, as sim/mav_dynamics.hpp) and is recomputed from a 10 Hz sweep of the wall.
double closest_approach_m(double desired_speed_mps, double start_m, double duration_s) {
    constexpr double kDt = 0.01, kTau = 0.3, kSweepPeriod = 0.1;
    double distance_m = start_m, speed_mps = 0.0, closest_m = start_m;
    Vector3d v_cmd = Vector3d::Zero();
    for (int step = 0; step * kDt < duration_s; ++step) {
        if (step % static_cast<int>(kSweepPeriod / kDt) == 0) {
            const auto wall = plane_patch(Vector3d::UnitX(), distance_m, 1.5);
            v_cmd = prevent_collision({desired_speed_mps, 0, 0}, wall, kConfig).v_cmd_body_mps;
        }
        speed_mps += (v_cmd.x() - speed_mps) * kDt / kTau;
        distance_m -= speed_mps * kDt;
        closest_m = std::min(closest_m, distance_m);
    }
    return closest_m;
}

TEST(CollisionPrevention, FlyingIntoAWallStopsAtDminOnlyUpToMaxSpeed) {
    // Not the simulator's closed loop (issue 13 item 3 asks for that as well), a kinematic one.
    // At v_max the braking (T = (d_att − d_min) / v = 1.2 s) is slow against τ: the approach
    // stops at d_min (measured 0.8001 m). Faster desired speeds overshoot: 0.66 m at 2 m/s,
    // 0.41 m at 3 m/s; at 4 m/s the lag carries the hull inside d_r, where SPEC's near plane
    // empties the frustum, λ returns to 1 and the vehicle hits the wall. So the defaults hold
    // for |v_ud| ≤ v_max; a faster vehicle needs d_att − d_min ≳ 1.2 s · |v_ud|.
    constexpr double kMarginAtVmax = 0.01, kMarginAtTwiceVmax = 0.15;  // m inside d_min
    const double at_vmax = closest_approach_m(kConfig.max_speed_mps, 6.0, 10.0);
    const double at_twice = closest_approach_m(2.0 * kConfig.max_speed_mps, 6.0, 10.0);
    const double at_four_times = closest_approach_m(4.0 * kConfig.max_speed_mps, 6.0, 10.0);
    EXPECT_GE(at_vmax, kConfig.d_min_m - kMarginAtVmax) << at_vmax;
    EXPECT_GE(at_twice, kConfig.d_min_m - kMarginAtTwiceVmax) << at_twice;
    EXPECT_LT(at_twice, kConfig.d_min_m - 0.1) << at_twice;
    EXPECT_LT(at_four_times, kConfig.robot_radius_m) << "pinned SPEC limit: " << at_four_times;
}

TEST(CollisionPrevention, SpecLimitObliqueApproachInsideDminKeepsATowardComponent) {
    // Pinned, not endorsed (file comment of collision_prevention.hpp): flying 10° towards a
    // wall already 0.75 m away, the wall's nearest points lie outside the 45° frustum, so λ
    // stays ~0.5 and the mean repulsion (~0.02 m/s) does not cancel the approach.
    const Vector3d v(std::cos(deg(10)), std::sin(deg(10)), 0.0);
    const auto result = prevent_collision(v, plane_patch(Vector3d::UnitY(), 0.75, 3.0), kConfig);
    EXPECT_GT(result.lambda, 0.3);
    EXPECT_LT(result.lambda, 0.7);
    EXPECT_GT(result.num_points_within_d_min, 0u);
    EXPECT_GT(result.v_cmd_body_mps.y(), 0.0);
}

TEST(CollisionPrevention, SpecLimitManyFartherPointsOutweighOneNearerPoint) {
    std::vector<Vector3d> points{{0.0, 0.4, 0.0}};  // pushes −y at 0.4 m/s
    for (int i = 0; i < 20; ++i) points.emplace_back(0.0, -0.7, 0.01 * (i - 10));  // +y ~0.1
    const auto result = prevent_collision(Vector3d::Zero(), cloud_of(points), kConfig);
    EXPECT_GT(result.v_rep_body_mps.y(), 0.0);  // towards the nearer point
}

}  // namespace
}  // namespace scantling::safety
