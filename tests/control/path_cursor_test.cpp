// The ROV's moving target along its path (control/path_cursor.hpp).
#include <gtest/gtest.h>

#include <scantling/control/path_cursor.hpp>

namespace scantling::control {
namespace {

planning::WaypointPath two_legs() {
    planning::WaypointPath path;
    path.waypoints.push_back({.p_world_m = {2.0, 0.0, 0.0}, .yaw_rad = 1.0, .tolerance_m = 0.2});
    path.waypoints.push_back({.p_world_m = {2.0, 0.0, -1.0}, .yaw_rad = 1.5, .tolerance_m = 0.2});
    return path;
}

TEST(PathCursor, TheTargetMovesAtTheSpeedAlongTheFirstLegFromTheStart) {
    const planning::WaypointPath path = two_legs();
    PathCursor cursor(Eigen::Vector3d::Zero(), 0.3, 0.25);
    for (int i = 0; i < 40; ++i) cursor.advance(path, Eigen::Vector3d::Zero(), 0.1, false);
    const GuidanceTarget target = cursor.target(path);
    EXPECT_NEAR(target.p_world_m.x(), 1.0, 1e-12);  // 4 s at 0.25 m/s
    EXPECT_NEAR(target.v_horizontal_mps.x(), 0.25, 1e-12);
    EXPECT_DOUBLE_EQ(target.yaw_rad, 1.0);  // the goal's heading
    EXPECT_EQ(cursor.next_index(), 0u);
}

TEST(PathCursor, HoldingFreezesTheTargetAndZeroesItsVelocity) {
    const planning::WaypointPath path = two_legs();
    PathCursor cursor(Eigen::Vector3d::Zero(), 0.0, 0.25);
    cursor.advance(path, Eigen::Vector3d::Zero(), 1.0, false);
    cursor.advance(path, Eigen::Vector3d::Zero(), 1.0, true);
    const GuidanceTarget target = cursor.target(path);
    EXPECT_NEAR(target.p_world_m.x(), 0.25, 1e-12);
    EXPECT_EQ(target.v_horizontal_mps.norm(), 0.0);
}

TEST(PathCursor, AWaypointIsPassedOnlyOnceTheVehicleIsWithinItsTolerance) {
    const planning::WaypointPath path = two_legs();
    PathCursor cursor(Eigen::Vector3d::Zero(), 0.0, 1.0);
    EXPECT_FALSE(cursor.advance(path, {1.0, 0.0, 0.0}, 3.0, false));  // target at the end
    EXPECT_EQ(cursor.target(path).v_horizontal_mps.norm(), 0.0);      // waiting there
    EXPECT_EQ(cursor.next_index(), 0u);
    EXPECT_TRUE(cursor.advance(path, {1.9, 0.0, 0.0}, 0.1, false));
    EXPECT_EQ(cursor.next_index(), 1u);
    cursor.advance(path, {1.9, 0.0, 0.0}, 0.5, false);
    const GuidanceTarget down = cursor.target(path);
    EXPECT_NEAR(down.p_world_m.z(), -0.5, 1e-12);
    EXPECT_NEAR(down.v_vertical_mps, -1.0, 1e-12);  // fed forward to the heave loop
    EXPECT_DOUBLE_EQ(down.yaw_rad, 1.5);
}

TEST(PathCursor, AMovedWaypointMovesTheTargetAtOnce) {
    planning::WaypointPath path = two_legs();
    PathCursor cursor(Eigen::Vector3d::Zero(), 0.0, 1.0);
    cursor.advance(path, Eigen::Vector3d::Zero(), 1.0, false);
    path.waypoints[0].p_world_m.y() = 2.0;  // the hull-relative adaptation shifted it
    const GuidanceTarget target = cursor.target(path);
    EXPECT_NEAR(target.p_world_m.y(), 1.0 / std::sqrt(2.0), 1e-12);
}

TEST(PathCursor, DoneHoldsTheLastWaypointAndRestartBeginsANewPath) {
    const planning::WaypointPath path = two_legs();
    PathCursor cursor(Eigen::Vector3d::Zero(), 0.0, 10.0);
    cursor.advance(path, {2.0, 0.0, 0.0}, 1.0, false);
    cursor.advance(path, {2.0, 0.0, -1.0}, 1.0, false);
    EXPECT_TRUE(cursor.done(path));
    EXPECT_TRUE(cursor.target(path).p_world_m.isApprox(Eigen::Vector3d(2.0, 0.0, -1.0)));
    cursor.restart({2.0, 0.0, -1.0}, 1.5);
    EXPECT_FALSE(cursor.done(path));
    EXPECT_EQ(cursor.next_index(), 0u);
}

}  // namespace
}  // namespace scantling::control
