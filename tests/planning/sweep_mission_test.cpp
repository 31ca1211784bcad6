// Sweeping mission: waypoints against hand-computed positions, the stand-off, the alternation,
// the yaw facing the wall, and every bad request refused with its field named.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include <scantling/core/error.hpp>
#include <scantling/planning/sweep_mission.hpp>

#include "expect_error.hpp"

namespace scantling::planning {
namespace {

constexpr double kExact = 1e-12;  // m, rad: closed-form positions, only rounding differs

/// An 8 × 5 m rectangle on the wall x = 0 facing +x, lower-left corner at (0, 0, 1): seen from
/// the vehicle at x > 0, "right" is +y and "up" is +z.
WallRectangle wall_8_by_5() {
    return {Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d::UnitX(), 8.0, 5.0};
}

TEST(SweepMission, EightByFiveWithOneMetreSpacingGivesSixLinesTopToBottomAlternating) {
    const WaypointPath path = plan_sweep(wall_8_by_5(), {});
    ASSERT_EQ(path.waypoints.size(), 12u);  // lines at z = 6, 5, 4, 3, 2, 1; two ends each
    for (std::size_t line = 0; line < 6; ++line) {
        const double z = 6.0 - static_cast<double>(line);
        const double y_start = line % 2 == 0 ? 0.0 : 8.0;  // left to right first, then back
        const Waypoint& first = path.waypoints[2 * line];
        const Waypoint& second = path.waypoints[2 * line + 1];
        EXPECT_TRUE(first.p_world_m.isApprox(Eigen::Vector3d(1.5, y_start, z), kExact))
            << "line " << line << ": " << first.p_world_m.transpose();
        EXPECT_TRUE(second.p_world_m.isApprox(Eigen::Vector3d(1.5, 8.0 - y_start, z), kExact))
            << "line " << line << ": " << second.p_world_m.transpose();
    }
}

TEST(SweepMission, EveryWaypointFacesTheWallAtTheStandOffWithTheSpecTolerance) {
    for (const Waypoint& wp : plan_sweep(wall_8_by_5(), {}).waypoints) {
        EXPECT_NEAR(wp.p_world_m.x(), 1.5, kExact);
        ASSERT_TRUE(wp.yaw_rad.has_value());
        EXPECT_NEAR(std::abs(*wp.yaw_rad), std::numbers::pi, kExact);  // looking along −x
        EXPECT_EQ(wp.tolerance_m, 0.20);
    }
    SweepConfig no_yaw;
    no_yaw.face_wall = false;
    EXPECT_FALSE(plan_sweep(wall_8_by_5(), no_yaw).waypoints.front().yaw_rad.has_value());
}

TEST(SweepMission, WallFacingMinusYSweepsAlongPlusX) {
    // Vehicle on the −y side looking along +y: its right is +x, its heading π/2.
    const WallRectangle wall{Eigen::Vector3d(2.0, 0.0, 0.0), -Eigen::Vector3d::UnitY(), 9.0, 5.0};
    const WaypointPath path = plan_sweep(wall, {});
    ASSERT_EQ(path.waypoints.size(), 12u);
    EXPECT_TRUE(path.waypoints[0].p_world_m.isApprox(Eigen::Vector3d(2.0, -1.5, 5.0), kExact));
    EXPECT_TRUE(path.waypoints[1].p_world_m.isApprox(Eigen::Vector3d(11.0, -1.5, 5.0), kExact));
    EXPECT_TRUE(path.waypoints[10].p_world_m.isApprox(Eigen::Vector3d(11.0, -1.5, 0.0), kExact));
    EXPECT_TRUE(path.waypoints[11].p_world_m.isApprox(Eigen::Vector3d(2.0, -1.5, 0.0), kExact));
    EXPECT_NEAR(*path.waypoints[0].yaw_rad, std::numbers::pi / 2.0, kExact);
}

TEST(SweepMission, SpacingIsAMaximumAndTheBottomEdgeIsAlwaysFlown) {
    SweepConfig config;
    config.line_spacing_m = 2.0;  // 5 / 2 → 3 gaps of 5/3 m, 4 lines
    const WaypointPath path = plan_sweep(wall_8_by_5(), config);
    ASSERT_EQ(path.waypoints.size(), 8u);
    for (std::size_t line = 0; line < 4; ++line) {
        EXPECT_NEAR(path.waypoints[2 * line].p_world_m.z(), 6.0 - 5.0 * line / 3.0, kExact);
    }
    config.line_spacing_m = 10.0;  // one gap: top and bottom lines only
    EXPECT_EQ(plan_sweep(wall_8_by_5(), config).waypoints.size(), 4u);
}

TEST(SweepMission, ObliqueWallKeepsTheStandOffAndLinesLevel) {
    const Eigen::Vector3d n = Eigen::Vector3d(1.0, 1.0, 0.2).normalized();  // slightly tilted
    const WallRectangle wall{Eigen::Vector3d(1.0, -2.0, 0.5), n, 6.0, 3.0};
    const WaypointPath path = plan_sweep(wall, {});
    ASSERT_EQ(path.waypoints.size(), 8u);
    for (const Waypoint& wp : path.waypoints) {
        EXPECT_NEAR((wp.p_world_m - wall.corner_world_m).dot(n), 1.5, kExact);
    }
    for (std::size_t i = 0; i < path.waypoints.size(); i += 2) {  // each line is horizontal
        EXPECT_NEAR(path.waypoints[i].p_world_m.z(), path.waypoints[i + 1].p_world_m.z(), kExact);
        EXPECT_NEAR((path.waypoints[i + 1].p_world_m - path.waypoints[i].p_world_m).norm(), 6.0,
                    kExact);
    }
}

TEST(SweepMission, BadRequestsAreRefusedNamingTheField) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    WallRectangle wall = wall_8_by_5();
    wall.width_m = 0.0;
    SCANTLING_EXPECT_ERROR(plan_sweep(wall), ConfigError, "sweep.rectangle.width_m = 0");
    wall = wall_8_by_5();
    wall.height_m = -5.0;
    SCANTLING_EXPECT_ERROR(plan_sweep(wall), ConfigError, "sweep.rectangle.height_m = -5");
    wall = wall_8_by_5();
    wall.corner_world_m.y() = nan;
    SCANTLING_EXPECT_ERROR(plan_sweep(wall), ConfigError, "sweep.rectangle.corner_world_m");
    wall = wall_8_by_5();
    wall.normal_world = Eigen::Vector3d::Zero();
    SCANTLING_EXPECT_ERROR(plan_sweep(wall), ConfigError, "sweep.rectangle.normal_world");
    wall.normal_world = Eigen::Vector3d::UnitZ();  // a ceiling
    SCANTLING_EXPECT_ERROR(plan_sweep(wall), ConfigError, "not a floor or ceiling");
    SweepConfig config;
    config.line_spacing_m = 0.0;
    SCANTLING_EXPECT_ERROR(plan_sweep(wall_8_by_5(), config), ConfigError,
                           "sweep.line_spacing_m = 0");
    config.line_spacing_m = 1e-9;  // a unit mistake: 5e9 lines
    SCANTLING_EXPECT_ERROR(plan_sweep(wall_8_by_5(), config), ConfigError,
                           "sweep.line_spacing_m = 1e-09, expected at most 10000 lines");
    config = {};
    config.standoff_m = nan;
    SCANTLING_EXPECT_ERROR(plan_sweep(wall_8_by_5(), config), ConfigError,
                           "sweep.standoff_m = nan");
    config = {};
    config.waypoint_tolerance_m = 0.0;
    SCANTLING_EXPECT_ERROR(plan_sweep(wall_8_by_5(), config), ConfigError,
                           "sweep.waypoint_tolerance_m = 0");
}

}  // namespace
}  // namespace scantling::planning
