// A bad request: a waypoint inside (or too close to) the known map is refused, naming the
// waypoint, its position and its distance; a clear path reports each waypoint's clearance.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <scantling/core/error.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/planning/obstacle_check.hpp>
#include <scantling/planning/sweep_mission.hpp>

#include "expect_error.hpp"

namespace scantling::planning {
namespace {

/// The wall x = 0, y ∈ [−1, 5], z ∈ [0, 4], sampled every 0.1 m.
PointCloud wall_map() {
    PointCloud map;
    for (int j = -10; j <= 50; ++j) {
        for (int k = 0; k <= 40; ++k) map.points.emplace_back(0.0, 0.1 * j, 0.1 * k);
    }
    return map;
}

WaypointPath sweep_in_front_of_the_wall() {
    return plan_sweep({Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d::UnitX(), 4.0, 2.0});
}

TEST(ObstacleCheck, AClearPathReportsEachWaypointsDistanceToTheMap) {
    const std::vector<double> distances =
        check_path_clear(sweep_in_front_of_the_wall(), wall_map(), 0.8);
    ASSERT_EQ(distances.size(), 6u);
    for (const double d : distances) EXPECT_NEAR(d, 1.5, 1e-9);  // the stand-off; on the grid
}

TEST(ObstacleCheck, AWaypointTooCloseToTheMapIsRefusedByIndexAndDistance) {
    WaypointPath path = sweep_in_front_of_the_wall();
    path.waypoints[3].p_world_m = Eigen::Vector3d(0.12, 2.0, 3.0);  // in front of a map point
    SCANTLING_EXPECT_ERROR(check_path_clear(path, wall_map(), 0.5), ConfigError,
                           "mission.waypoints[3] = (0.12, 2.00, 3.00) is 0.12 m from the map, "
                           "expected >= clearance 0.50 m");
    path.waypoints[3].p_world_m = Eigen::Vector3d(-0.5, 2.05, 3.05);  // behind the wall
    SCANTLING_EXPECT_ERROR(check_path_clear(path, wall_map(), 0.8, "sweep"), ConfigError,
                           "sweep.waypoints[3] = (-0.50, 2.05, 3.05) is 0.50 m from the map");
    // The clearance is inclusive: exactly at it passes.
    path.waypoints[3].p_world_m = Eigen::Vector3d(0.5, 2.0, 3.0);
    EXPECT_NEAR(check_path_clear(path, wall_map(), 0.5)[3], 0.5, 1e-12);
}

TEST(ObstacleCheck, AnEmptyMapBlocksNothingAndNonFinitePointsAreSkipped) {
    const std::vector<double> distances =
        check_path_clear(sweep_in_front_of_the_wall(), PointCloud{}, 0.8);
    ASSERT_EQ(distances.size(), 6u);
    EXPECT_EQ(distances[0], std::numeric_limits<double>::infinity());
    PointCloud map = wall_map();
    map.points.emplace_back(1.5, 0.0, 3.0);  // a NaN return would otherwise sit on waypoint 0
    map.points.back().x() = std::nan("");
    EXPECT_NEAR(check_path_clear(sweep_in_front_of_the_wall(), map, 0.8)[0], 1.5, 1e-9);
}

TEST(ObstacleCheck, BadClearanceOrPathIsRefused) {
    SCANTLING_EXPECT_ERROR(check_path_clear(sweep_in_front_of_the_wall(), wall_map(), -0.1),
                           ConfigError, "mission.clearance_m = -0.1, expected finite >= 0");
    WaypointPath path = sweep_in_front_of_the_wall();
    path.waypoints[1].tolerance_m = 0.0;
    SCANTLING_EXPECT_ERROR(check_path_clear(path, wall_map(), 0.5), ConfigError,
                           "mission.waypoints[1].tolerance_m");
}

}  // namespace
}  // namespace scantling::planning
