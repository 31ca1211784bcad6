// Vertical-structure inspection: up on the left, down on the right (SPEC §4), more legs with
// a leg spacing, and the bad requests.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <scantling/core/error.hpp>
#include <scantling/planning/vertical_inspection.hpp>

#include "expect_error.hpp"

namespace scantling::planning {
namespace {

constexpr double kExact = 1e-12;  // m, rad: closed-form positions

/// A 3 m wide, 9 m high face on the wall x = 0 facing +x, lower-left corner at (0, 1, 0.5).
WallRectangle face_3_by_9() {
    return {Eigen::Vector3d(0.0, 1.0, 0.5), Eigen::Vector3d::UnitX(), 3.0, 9.0};
}

TEST(VerticalInspection, DefaultIsUpOnTheLeftAndDownOnTheRight) {
    const WaypointPath path = plan_vertical_inspection(face_3_by_9());
    ASSERT_EQ(path.waypoints.size(), 4u);
    const Eigen::Vector3d expected[] = {
        {1.5, 1.0, 0.5}, {1.5, 1.0, 9.5}, {1.5, 4.0, 9.5}, {1.5, 4.0, 0.5}};
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_TRUE(path.waypoints[i].p_world_m.isApprox(expected[i], kExact))
            << i << ": " << path.waypoints[i].p_world_m.transpose();
        EXPECT_NEAR(std::abs(*path.waypoints[i].yaw_rad), std::numbers::pi, kExact);
        EXPECT_EQ(path.waypoints[i].tolerance_m, 0.20);
    }
}

TEST(VerticalInspection, LegSpacingAddsAlternatingLegsLeftToRight) {
    VerticalInspectionConfig config;
    config.leg_spacing_m = 1.0;  // legs at y = 1, 2, 3, 4: up, down, up, down
    const WaypointPath path = plan_vertical_inspection(face_3_by_9(), config);
    ASSERT_EQ(path.waypoints.size(), 8u);
    for (std::size_t leg = 0; leg < 4; ++leg) {
        const bool up = leg % 2 == 0;
        const Eigen::Vector3d& start = path.waypoints[2 * leg].p_world_m;
        const Eigen::Vector3d& end = path.waypoints[2 * leg + 1].p_world_m;
        EXPECT_NEAR(start.y(), 1.0 + static_cast<double>(leg), kExact);
        EXPECT_NEAR(end.y(), start.y(), kExact);
        EXPECT_NEAR(start.z(), up ? 0.5 : 9.5, kExact);
        EXPECT_NEAR(end.z(), up ? 9.5 : 0.5, kExact);
    }
}

TEST(VerticalInspection, BadRequestsAreRefusedNamingTheField) {
    WallRectangle face = face_3_by_9();
    face.height_m = 0.0;
    SCANTLING_EXPECT_ERROR(plan_vertical_inspection(face), ConfigError,
                           "vertical_inspection.rectangle.height_m = 0");
    face = face_3_by_9();
    face.width_m = std::numeric_limits<double>::infinity();
    SCANTLING_EXPECT_ERROR(plan_vertical_inspection(face), ConfigError,
                           "vertical_inspection.rectangle.width_m = inf");
    VerticalInspectionConfig config;
    config.leg_spacing_m = -1.0;
    SCANTLING_EXPECT_ERROR(plan_vertical_inspection(face_3_by_9(), config), ConfigError,
                           "vertical_inspection.leg_spacing_m = -1");
    config = {};
    config.standoff_m = -0.5;
    SCANTLING_EXPECT_ERROR(plan_vertical_inspection(face_3_by_9(), config), ConfigError,
                           "vertical_inspection.standoff_m = -0.5");
}

}  // namespace
}  // namespace scantling::planning
