// SPEC §3 collision prevention, in the style of PX4's collision-prevention suite: no data, no
// bias, frustum edges and planes, monotone attenuation, repulsion (mean, clamp), the log line
// and every input and config contract. Properties and limits: collision_prevention_property_test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/safety/collision_prevention.hpp>

#include "test_clouds.hpp"

namespace scantling::safety {
namespace {

using namespace test;

constexpr double kExact = 1e-12;            // m or m/s: closed-form values, only rounding differs
const CollisionPreventionConfig kConfig{};  // d_att 2.0, d_min 0.8, d_r 0.35, K 1, v_max 1

TEST(CollisionPrevention, EmptyCloudLeavesTheCommandUnchanged) {
    const Vector3d v(0.7, -0.2, 0.1);
    const auto result = prevent_collision(v, PointCloud{}, kConfig);
    EXPECT_EQ(result.v_cmd_body_mps, v);
    EXPECT_EQ(result.lambda, 1.0);
    EXPECT_FALSE(result.d_o_m.has_value());
    EXPECT_EQ(result.status, AttenuationStatus::kNoData);
    EXPECT_EQ(result.num_valid_points, 0u);
}

TEST(CollisionPrevention, NanAndInfiniteOnlyCloudLeavesTheCommandUnchanged) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const auto cloud = cloud_of(
        {{nan, nan, nan}, {0.5, nan, 0.0}, {inf, 0.0, 0.0}, {0.3, 0.0, -inf}, Vector3d::Zero()});
    const Vector3d v(1.0, 0.0, 0.0);
    const auto result = prevent_collision(v, cloud, kConfig);
    EXPECT_EQ(result.v_cmd_body_mps, v);
    EXPECT_EQ(result.status, AttenuationStatus::kNoData);
    EXPECT_EQ(result.num_points_within_d_min, 0u);
}

TEST(CollisionPrevention, NanPointsAmongRealOnesAreSkipped) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const auto clean = prevent_collision({1, 0, 0}, cloud_of({{1.4, 0, 0}}), kConfig);
    const auto noisy = prevent_collision({1, 0, 0}, cloud_of({{nan, 0, 0}, {1.4, 0, 0}}), kConfig);
    EXPECT_EQ(noisy.v_cmd_body_mps, clean.v_cmd_body_mps);
    EXPECT_EQ(noisy.num_valid_points, 1u);
    EXPECT_NEAR(noisy.lambda, 0.5, kExact);  // (1.4 − 0.8) / (2.0 − 0.8)
}

TEST(CollisionPrevention, UniformObstaclesAllAroundGiveNoBias) {
    const auto walls = box_walls(0.45, 20);  // every point inside d_min = 0.8 (corner 0.78)
    const auto hovering = prevent_collision(Vector3d::Zero(), walls, kConfig);
    EXPECT_EQ(hovering.num_points_within_d_min, walls.size());
    EXPECT_LT(hovering.v_rep_body_mps.norm(), kExact);
    EXPECT_LT(hovering.v_cmd_body_mps.norm(), kExact);
    // Pushing into any wall is stopped, and the balanced repulsion adds nothing.
    const auto pushing = prevent_collision({0.3, -0.8, 0.2}, walls, kConfig);
    EXPECT_EQ(pushing.status, AttenuationStatus::kStopped);
    EXPECT_LT(pushing.v_cmd_body_mps.norm(), kExact);
}

TEST(CollisionPrevention, ObstacleAheadAttenuatesMonotonicallyFromDminToDatt) {
    const Vector3d v(0.8, 0.0, 0.0);
    double previous = -1.0;
    for (double d = kConfig.robot_radius_m; d <= 2.6; d += 0.01) {
        const auto result = prevent_collision(v, cloud_of({{d, 0, 0}}), kConfig);
        const double expected =
            std::clamp((d - kConfig.d_min_m) / (kConfig.d_att_m - kConfig.d_min_m), 0.0, 1.0);
        EXPECT_NEAR(result.lambda, expected, kExact) << "d = " << d;
        EXPECT_GE(result.lambda, previous) << "d = " << d;
        if (d <= kConfig.d_min_m) {
            EXPECT_EQ(result.lambda, 0.0) << "d = " << d;
        }
        if (d >= kConfig.d_att_m) {
            EXPECT_EQ(result.lambda, 1.0) << "d = " << d;
        }
        EXPECT_TRUE((result.v_att_body_mps - result.lambda * v).norm() < kExact);
        previous = result.lambda;
    }
}

TEST(CollisionPrevention, ObstacleInsideDminIsStoppedAndPushedBack) {
    const auto result = prevent_collision({1, 0, 0}, cloud_of({{0.5, 0, 0}}), kConfig);
    EXPECT_EQ(result.status, AttenuationStatus::kStopped);
    EXPECT_NEAR(*result.d_o_m, 0.5, kExact);
    EXPECT_TRUE(result.v_att_body_mps.isZero());
    // K (d_min − d) = 1 · 0.3, straight away from the point.
    EXPECT_TRUE((result.v_cmd_body_mps - Vector3d(-0.3, 0, 0)).norm() < kExact);
}

TEST(CollisionPrevention, FrustumEdgesAtTwentyTwoAndTwentyThreeDegrees) {
    const Vector3d v(1.0, 0.0, 0.0);
    for (const double sign : {-1.0, 1.0}) {
        const double in = 22.0 * sign, out = 23.0 * sign;
        EXPECT_TRUE(prevent_collision(v, cloud_of({off_axis(1.2, in, 0)}), kConfig).d_o_m);
        EXPECT_TRUE(prevent_collision(v, cloud_of({off_axis(1.2, 0, in)}), kConfig).d_o_m);
        EXPECT_TRUE(prevent_collision(v, cloud_of({off_axis(1.2, in, in)}), kConfig).d_o_m);
        EXPECT_FALSE(prevent_collision(v, cloud_of({off_axis(1.2, out, 0)}), kConfig).d_o_m);
        EXPECT_FALSE(prevent_collision(v, cloud_of({off_axis(1.2, 0, out)}), kConfig).d_o_m);
        EXPECT_FALSE(prevent_collision(v, cloud_of({off_axis(1.2, in, out)}), kConfig).d_o_m);
    }
    const auto counted = prevent_collision(v, cloud_of({off_axis(1.2, 22.0, 0)}), kConfig);
    EXPECT_NEAR(*counted.d_o_m, 1.2, kExact);
    EXPECT_NEAR(counted.lambda, 1.0 / 3.0, kExact);
    const auto ignored = prevent_collision(v, cloud_of({off_axis(1.2, 23.0, 0)}), kConfig);
    EXPECT_EQ(ignored.v_cmd_body_mps, v);
}

TEST(CollisionPrevention, NearAndFarPlanesBoundTheFrustum) {
    const Vector3d v(0.0, 1.0, 0.0);
    EXPECT_FALSE(prevent_collision(v, cloud_of({{0, 0.34, 0}}), kConfig).d_o_m);  // < d_r
    EXPECT_TRUE(prevent_collision(v, cloud_of({{0, 0.35, 0}}), kConfig).d_o_m);
    EXPECT_TRUE(prevent_collision(v, cloud_of({{0, 2.0, 0}}), kConfig).d_o_m);
    EXPECT_FALSE(prevent_collision(v, cloud_of({{0, 2.01, 0}}), kConfig).d_o_m);  // > d_att
}

TEST(CollisionPrevention, PointsBehindAndBesideDoNotAttenuateForwardMotion) {
    const Vector3d v(1.0, 0.0, 0.0);
    const auto around = cloud_of({{-1, 0, 0},
                                  {0, 1, 0},
                                  {0, -1, 0},
                                  {0, 0, 1},
                                  {0, 0, -1},
                                  {0.5, 1.0, 0},
                                  {-0.3, -0.3, 0.9}});
    const auto result = prevent_collision(v, around, kConfig);
    EXPECT_EQ(result.lambda, 1.0);
    EXPECT_EQ(result.v_cmd_body_mps, v);
    // A close point behind pushes forward and still does not slow the forward command.
    const auto behind = prevent_collision(v, cloud_of({{-0.6, 0, 0}}), kConfig);
    EXPECT_EQ(behind.lambda, 1.0);
    EXPECT_TRUE((behind.v_cmd_body_mps - Vector3d(1.2, 0, 0)).norm() < kExact);
}

TEST(CollisionPrevention, VerticalVelocityLooksUpOrDown) {
    const auto down = prevent_collision({0, 0, -1}, cloud_of({{0, 0, -1.4}}), kConfig);
    EXPECT_NEAR(down.lambda, 0.5, kExact);
    EXPECT_FALSE(prevent_collision({0, 0, 1}, cloud_of({{0, 0, -1.4}}), kConfig).d_o_m);
    for (const Vector3d& v : {Vector3d(0, 0, 2), Vector3d(0.3, -0.4, 0.5), Vector3d(-1, 2, 0)}) {
        const auto frustum = make_frustum(v, kConfig);
        ASSERT_TRUE(frustum);
        EXPECT_NEAR(frustum->horizontal_h.z(), 0.0, kExact);  // horizontal ⟂ body z
        EXPECT_NEAR(frustum->axis_f.dot(frustum->horizontal_h), 0.0, kExact);
        EXPECT_NEAR(frustum->vertical_u.norm(), 1.0, kExact);
    }
    EXPECT_FALSE(make_frustum(Vector3d::Zero(), kConfig));
}

TEST(CollisionPrevention, ZeroDesiredVelocityHasNoFrustumButStillRepels) {
    const auto result = prevent_collision(Vector3d::Zero(), cloud_of({{0, 0.6, 0}}), kConfig);
    EXPECT_FALSE(result.d_o_m);
    EXPECT_EQ(result.status, AttenuationStatus::kClear);
    EXPECT_TRUE((result.v_cmd_body_mps - Vector3d(0, -0.2, 0)).norm() < kExact);
}

TEST(CollisionPrevention, RepulsionIsTheMeanNotTheSum) {
    // SPEC §3 "mean" (the seeds' overviews say "added together"): doubling a point changes
    // nothing; two points give the average of their pushes.
    const Vector3d p(0.0, 0.5, 0.0);
    const auto once = prevent_collision(Vector3d::Zero(), cloud_of({p}), kConfig);
    const auto twice = prevent_collision(Vector3d::Zero(), cloud_of({p, p}), kConfig);
    EXPECT_TRUE((twice.v_rep_body_mps - once.v_rep_body_mps).norm() < kExact);
    const auto pair = prevent_collision(Vector3d::Zero(), cloud_of({{0.6, 0, 0}, p}), kConfig);
    EXPECT_TRUE((pair.v_rep_body_mps - Vector3d(-0.1, -0.15, 0)).norm() < kExact);
}

TEST(CollisionPrevention, RepulsionIsClampedToMaxSpeed) {
    CollisionPreventionConfig strong = kConfig;
    strong.repulsion_gain_per_s = 10.0;  // 10 · (0.8 − 0.05) = 7.5 m/s before the clamp
    const auto result = prevent_collision(Vector3d::Zero(), cloud_of({{0, 0, 0.05}}), strong);
    EXPECT_TRUE(result.repulsion_clamped);
    EXPECT_NEAR(result.v_rep_body_mps.norm(), strong.max_speed_mps, kExact);
    EXPECT_NEAR(result.v_rep_body_mps.z(), -strong.max_speed_mps, kExact);
    const auto gentle = prevent_collision(Vector3d::Zero(), cloud_of({{0, 0, 0.05}}), kConfig);
    EXPECT_FALSE(gentle.repulsion_clamped);  // 0.75 m/s < 1 m/s
}
TEST(CollisionPrevention, DescribeSaysWhy) {
    const auto attenuated = prevent_collision({1, 0, 0}, cloud_of({{1.4, 0, 0}}), kConfig);
    EXPECT_EQ(describe(attenuated, kConfig), "attenuated: d_o = 1.40 m, lambda = 0.50");
    const auto stopped = prevent_collision({1, 0, 0}, cloud_of({{0.5, 0, 0}}), kConfig);
    EXPECT_EQ(describe(stopped, kConfig),
              "stopped: d_o = 0.50 m, lambda = 0.00; repelled by 1 points closer than d_min = "
              "0.80 m (|v_rep| = 0.30 m/s)");
    EXPECT_EQ(describe(prevent_collision({1, 0, 0}, PointCloud{}, kConfig), kConfig),
              "no data: no usable point, command unchanged");
}

TEST(CollisionPrevention, NonFiniteDesiredVelocityThrows) {
    const Vector3d v(std::numeric_limits<double>::quiet_NaN(), 0, 0);
    EXPECT_THROW(prevent_collision(v, PointCloud{}, kConfig), InputError);
}

void expect_config_error(const std::function<void(CollisionPreventionConfig&)>& spoil,
                         const std::string& field) {
    CollisionPreventionConfig config;
    spoil(config);
    try {
        prevent_collision(Vector3d::UnitX(), PointCloud{}, config);
        ADD_FAILURE() << "no ConfigError for " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("collision_prevention." + field + " = "),
                  std::string::npos)
            << e.what();
    }
}

TEST(CollisionPrevention, BadConfigsThrowNamingTheField) {
    EXPECT_NO_THROW(CollisionPreventionConfig{}.validate());
    expect_config_error([](auto& c) { c.d_att_m = 0.8; }, "d_att_m");  // not > d_min
    expect_config_error([](auto& c) { c.d_min_m = 0.3; }, "d_min_m");  // not > d_r
    expect_config_error([](auto& c) { c.d_min_m = 2.5; }, "d_att_m");
    expect_config_error([](auto& c) { c.robot_radius_m = -0.1; }, "robot_radius_m");
    expect_config_error([](auto& c) { c.repulsion_gain_per_s = 0.0; }, "repulsion_gain_per_s");
    expect_config_error([](auto& c) { c.max_speed_mps = std::nan(""); }, "max_speed_mps");
    expect_config_error([](auto& c) { c.half_fov_horizontal_deg = 90.0; },
                        "half_fov_horizontal_deg");
    expect_config_error([](auto& c) { c.half_fov_vertical_deg = 0.0; }, "half_fov_vertical_deg");
}

}  // namespace
}  // namespace scantling::safety
