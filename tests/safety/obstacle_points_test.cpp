// Collision prevention on the points gathered once per sweep gives the sweep's own answer, bit
// for bit, for any velocity (seeded clouds that reach well past the frustum's far corner, wide
// and narrow frustums), and refuses points gathered for a smaller frustum.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/safety/obstacle_points.hpp>

#include "test_clouds.hpp"

namespace scantling::safety {
namespace {

using namespace test;

void expect_identical(const CollisionPreventionResult& a, const CollisionPreventionResult& b) {
    EXPECT_EQ(a.v_cmd_body_mps, b.v_cmd_body_mps);
    EXPECT_EQ(a.v_rep_body_mps, b.v_rep_body_mps);
    EXPECT_EQ(a.lambda, b.lambda);
    EXPECT_EQ(a.d_o_m, b.d_o_m);
    EXPECT_EQ(a.num_valid_points, b.num_valid_points);
    EXPECT_EQ(a.num_frustum_points, b.num_frustum_points);
    EXPECT_EQ(a.num_points_within_d_min, b.num_points_within_d_min);
    EXPECT_EQ(a.repulsion_clamped, b.repulsion_clamped);
    EXPECT_EQ(a.status, b.status);
}

PointCloud random_sweep(Rng& rng, double extent_m) {
    std::vector<Vector3d> points(400);
    for (auto& p : points) {
        p = Vector3d(rng.uniform(-extent_m, extent_m), rng.uniform(-extent_m, extent_m),
                     rng.uniform(-extent_m, extent_m));
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    points[7] = Vector3d(nan, 0.0, 0.0);  // a no-return
    points[8] = Vector3d::Zero();         // the origin has no direction
    return cloud_of(points);
}

TEST(ObstaclePoints, GiveTheSweepsResultForEveryVelocity) {
    Rng rng(29);
    CollisionPreventionConfig wide;
    wide.half_fov_horizontal_deg = 60.0;
    wide.half_fov_vertical_deg = 40.0;
    for (const CollisionPreventionConfig& config : {CollisionPreventionConfig{}, wide}) {
        std::size_t kept = 0, total = 0, in_frustum = 0;
        for (int trial = 0; trial < 200; ++trial) {
            const PointCloud sweep = random_sweep(rng, 6.0);
            const ObstaclePoints obstacles = gather_obstacle_points(sweep, config);
            kept += obstacles.points_body.size();
            total += sweep.size();
            for (int k = 0; k < 5; ++k) {
                const Vector3d v = k == 0 ? Vector3d::Zero() : rng.normal3(1.0);
                const auto direct = prevent_collision(v, sweep, config);
                in_frustum += direct.num_frustum_points;
                expect_identical(prevent_collision(v, obstacles, config), direct);
            }
        }
        // The test means something only if points were dropped and frustums were not empty.
        EXPECT_LT(kept, total / 2);
        EXPECT_GT(in_frustum, 100u);
    }
}

TEST(ObstaclePoints, PointsOnTheFrustumsFarCornerAreKept) {
    const CollisionPreventionConfig config;
    // On the x-axis frustum's corner: a = d_att, both angles at the half field of view.
    const Vector3d corner = Vector3d(1.0, std::tan(deg(22.5)), std::tan(deg(22.5))) * 2.0;
    const ObstaclePoints obstacles = gather_obstacle_points(cloud_of({corner}), config);
    ASSERT_EQ(obstacles.points_body.size(), 1u);
    expect_identical(prevent_collision({1, 0, 0}, obstacles, config),
                     prevent_collision({1, 0, 0}, cloud_of({corner}), config));
}

TEST(ObstaclePoints, GatheredForASmallerFrustumAreRefused) {
    CollisionPreventionConfig narrow;
    narrow.d_att_m = 1.5;
    const ObstaclePoints obstacles = gather_obstacle_points(box_walls(1.0, 4), narrow);
    EXPECT_THROW(prevent_collision({1, 0, 0}, obstacles, CollisionPreventionConfig{}), InputError);
    EXPECT_NO_THROW(prevent_collision({1, 0, 0}, obstacles, narrow));
}

TEST(ObstaclePoints, AnEmptySweepHasNoData) {
    const ObstaclePoints obstacles = gather_obstacle_points(PointCloud{});
    EXPECT_EQ(prevent_collision({1, 0, 0}, obstacles).status, AttenuationStatus::kNoData);
}

}  // namespace
}  // namespace scantling::safety
