// Circular inspection: rings at hand-computed angles, the yaw facing the centre, the turn
// direction, and the bad requests.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include <scantling/core/error.hpp>
#include <scantling/planning/circular_inspection.hpp>

#include "expect_error.hpp"

namespace scantling::planning {
namespace {

constexpr double kExact = 1e-12;  // m, rad: closed-form positions

CircleRequest circle() { return {Eigen::Vector2d(2.0, 3.0), 2.0, {1.0, 2.5}}; }

TEST(CircularInspection, OneClosedTurnPerHeightCounterClockwise) {
    CircularInspectionConfig config;
    config.points_per_turn = 4;
    const WaypointPath path = plan_circular_inspection(circle(), config);
    ASSERT_EQ(path.waypoints.size(), 10u);  // 2 rings × (4 + 1)
    const Eigen::Vector2d ring[] = {{4.0, 3.0}, {2.0, 5.0}, {0.0, 3.0}, {2.0, 1.0}, {4.0, 3.0}};
    for (std::size_t k = 0; k < 10; ++k) {
        const Eigen::Vector3d expected(ring[k % 5].x(), ring[k % 5].y(), k < 5 ? 1.0 : 2.5);
        EXPECT_TRUE(path.waypoints[k].p_world_m.isApprox(expected, kExact))
            << k << ": " << path.waypoints[k].p_world_m.transpose();
    }
}

TEST(CircularInspection, EveryWaypointFacesTheCentreAtTheRadius) {
    const WaypointPath path = plan_circular_inspection(circle());
    ASSERT_EQ(path.waypoints.size(), 34u);  // 2 × (16 + 1)
    for (const Waypoint& wp : path.waypoints) {
        const Eigen::Vector2d to_centre = Eigen::Vector2d(2.0, 3.0) - wp.p_world_m.head<2>();
        EXPECT_NEAR(to_centre.norm(), 2.0, kExact);
        ASSERT_TRUE(wp.yaw_rad.has_value());
        const Eigen::Vector2d heading(std::cos(*wp.yaw_rad), std::sin(*wp.yaw_rad));
        EXPECT_NEAR(heading.dot(to_centre.normalized()), 1.0, kExact);
        EXPECT_EQ(wp.tolerance_m, 0.20);
    }
}

TEST(CircularInspection, ClockwiseAndStartAngle) {
    CircularInspectionConfig config;
    config.points_per_turn = 4;
    config.clockwise = true;
    config.start_angle_rad = std::numbers::pi / 2.0;  // start north of the centre
    const WaypointPath path = plan_circular_inspection(circle(), config);
    EXPECT_TRUE(path.waypoints[0].p_world_m.isApprox(Eigen::Vector3d(2.0, 5.0, 1.0), kExact));
    EXPECT_TRUE(path.waypoints[1].p_world_m.isApprox(Eigen::Vector3d(4.0, 3.0, 1.0), kExact));
    EXPECT_NEAR(*path.waypoints[0].yaw_rad, -std::numbers::pi / 2.0, kExact);  // facing south
}

TEST(CircularInspection, BadRequestsAreRefusedNamingTheField) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CircleRequest request = circle();
    request.radius_m = 0.0;
    SCANTLING_EXPECT_ERROR(plan_circular_inspection(request), ConfigError,
                           "circular_inspection.request.radius_m = 0");
    request = circle();
    request.heights_m.clear();
    SCANTLING_EXPECT_ERROR(plan_circular_inspection(request), ConfigError,
                           "circular_inspection.request.heights_m is empty");
    request = circle();
    request.heights_m[1] = nan;
    SCANTLING_EXPECT_ERROR(plan_circular_inspection(request), ConfigError,
                           "circular_inspection.request.heights_m[1] = nan");
    request = circle();
    request.centre_xy_world_m.x() = nan;
    SCANTLING_EXPECT_ERROR(plan_circular_inspection(request), ConfigError,
                           "circular_inspection.request.centre_xy_world_m");
    CircularInspectionConfig config;
    config.points_per_turn = 2;
    SCANTLING_EXPECT_ERROR(plan_circular_inspection(circle(), config), ConfigError,
                           "circular_inspection.points_per_turn = 2, expected >= 3");
}

}  // namespace
}  // namespace scantling::planning
