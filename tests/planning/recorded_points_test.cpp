// Go-to-point and go-home: recorded points by name, the unknown name refused with the known
// ones listed, and the take-off point.
#include <gtest/gtest.h>

#include <limits>

#include <scantling/core/error.hpp>
#include <scantling/planning/recorded_points.hpp>

#include "expect_error.hpp"

namespace scantling::planning {
namespace {

TEST(RecordedPoints, GoToARecordedPointGivesOneWaypointWithItsYaw) {
    RecordedPoints points;
    points.record("A", {Eigen::Vector3d(1.0, 2.0, 3.0), 0.5});
    points.record("manhole", {Eigen::Vector3d(11.0, 3.0, 2.0), std::nullopt});
    const WaypointPath path = plan_go_to_point(points, "A");
    ASSERT_EQ(path.waypoints.size(), 1u);
    EXPECT_EQ(path.waypoints[0].p_world_m, Eigen::Vector3d(1.0, 2.0, 3.0));
    EXPECT_EQ(path.waypoints[0].yaw_rad, 0.5);
    EXPECT_EQ(path.waypoints[0].tolerance_m, 0.20);
    EXPECT_FALSE(plan_go_to_point(points, "manhole").waypoints[0].yaw_rad.has_value());
}

TEST(RecordedPoints, RecordingANameAgainReplacesIt) {
    RecordedPoints points;
    points.record("B", {Eigen::Vector3d(1.0, 0.0, 0.0), std::nullopt});
    points.record("B", {Eigen::Vector3d(2.0, 0.0, 0.0), std::nullopt});
    EXPECT_EQ(points.size(), 1u);
    EXPECT_EQ(points.at("B").p_world_m.x(), 2.0);
}

TEST(RecordedPoints, UnknownNameIsRefusedListingTheKnownOnes) {
    RecordedPoints points;
    SCANTLING_EXPECT_ERROR(plan_go_to_point(points, "A"), InputError,
                           "recorded point 'A' is unknown (recorded: none)");
    points.record("manhole", {Eigen::Vector3d::Zero(), std::nullopt});
    points.record("A", {Eigen::Vector3d::Zero(), std::nullopt});
    SCANTLING_EXPECT_ERROR(plan_go_to_point(points, "B"), InputError,
                           "recorded point 'B' is unknown (recorded: A, manhole)");
    EXPECT_FALSE(points.contains("B"));
}

TEST(RecordedPoints, BadPointsAreRefused) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    RecordedPoints points;
    SCANTLING_EXPECT_ERROR(points.record("", {}), InputError, "name is empty");
    SCANTLING_EXPECT_ERROR(points.record("A", {Eigen::Vector3d(nan, 0.0, 0.0), std::nullopt}),
                           InputError, "recorded point 'A' p_world_m = (nan, 0, 0)");
    SCANTLING_EXPECT_ERROR(points.record("A", {Eigen::Vector3d::Zero(), nan}), InputError,
                           "recorded point 'A' yaw_rad = nan");
    EXPECT_EQ(points.size(), 0u);
}

TEST(GoHome, ReturnsToTheTakeOffPoint) {
    const WaypointPath path = plan_go_home(Eigen::Vector3d(-1.0, 0.5, 0.2));
    ASSERT_EQ(path.waypoints.size(), 1u);
    EXPECT_EQ(path.waypoints[0].p_world_m, Eigen::Vector3d(-1.0, 0.5, 0.2));
    EXPECT_FALSE(path.waypoints[0].yaw_rad.has_value());
    const double inf = std::numeric_limits<double>::infinity();
    SCANTLING_EXPECT_ERROR(plan_go_home(Eigen::Vector3d(0.0, inf, 0.0)), InputError,
                           "take-off point");
    GoToConfig config;
    config.waypoint_tolerance_m = -0.2;
    SCANTLING_EXPECT_ERROR(plan_go_home(Eigen::Vector3d::Zero(), config), ConfigError,
                           "go_home.waypoint_tolerance_m = -0.2");
}

TEST(WaypointPathValidation, NamesTheWaypointAndField) {
    WaypointPath path{{Waypoint{}, Waypoint{}}};
    path.waypoints[1].tolerance_m = 0.0;
    SCANTLING_EXPECT_ERROR(validate(path), ConfigError, "path.waypoints[1].tolerance_m = 0");
    path.waypoints[1].tolerance_m = 0.2;
    path.waypoints[0].yaw_rad = std::numeric_limits<double>::quiet_NaN();
    SCANTLING_EXPECT_ERROR(validate(path), ConfigError, "path.waypoints[0].yaw_rad = nan");
}

}  // namespace
}  // namespace scantling::planning
