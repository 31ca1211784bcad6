// Re-inspection of the sonar map's coverage holes (SPEC §5, issue 14 item 4): each hole visited
// once at the stand-off facing the hull, nearest-first with a deterministic tie-break, a pass
// across holes wider than the footprint, and every bad request refused with the field named.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/planning/hole_reinspection.hpp>

#include "expect_error.hpp"

namespace scantling::planning {
namespace {

constexpr double kExact = 1e-12;  // m, rad: closed-form positions
const double kNaN = std::numeric_limits<double>::quiet_NaN();
// Hull side in the plane y = 0, the water (and the vehicle) on the −y side.
const Eigen::Vector3d kNormal(0.0, -1.0, 0.0);

/// A hole of w × h m (along x, z) centred on its centroid (x, 0, z).
ReinspectionHole hole_at(double x, double z, double w = 0.4, double h = 0.4) {
    ReinspectionHole hole;
    hole.centroid_world_m = {x, 0.0, z};
    hole.box_min_u_m = -w / 2.0;
    hole.box_max_u_m = w / 2.0;
    hole.box_min_v_m = -h / 2.0;
    hole.box_max_v_m = h / 2.0;
    return hole;
}

TEST(HoleReinspection, VisitsEachNarrowHoleOnceAtTheStandOffFacingTheHull) {
    const std::vector<ReinspectionHole> holes{hole_at(0.0, -1.0), hole_at(5.0, -2.0),
                                              hole_at(10.0, -1.5)};
    HoleReinspectionConfig config;
    config.stand_off_m = 1.3;
    const WaypointPath path =
        plan_hole_reinspection(holes, 2.0 * kNormal, {12.0, -1.3, -1.0}, config);
    ASSERT_EQ(path.waypoints.size(), 3U);
    // Nearest-first from x = 12: the holes at x = 10, 5, 0.
    const std::vector<Eigen::Vector3d> expected{
        {10.0, -1.3, -1.5}, {5.0, -1.3, -2.0}, {0.0, -1.3, -1.0}};
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_LT((path.waypoints[i].p_world_m - expected[i]).norm(), kExact) << i;
        ASSERT_TRUE(path.waypoints[i].yaw_rad.has_value());
        EXPECT_NEAR(*path.waypoints[i].yaw_rad, std::numbers::pi / 2.0, kExact);  // faces +y
        EXPECT_EQ(path.waypoints[i].tolerance_m, kDefaultWaypointToleranceM);
    }
}

TEST(HoleReinspection, GreedyOrderFollowsTheVehicleNotTheStart) {
    // From x = 0: the hole at 1 first, then 3 (2 m away) before −2.5 (3.5 m away from 1),
    // although −2.5 is nearer the start than 3.
    const std::vector<ReinspectionHole> holes{hole_at(-2.5, 0.0), hole_at(3.0, 0.0),
                                              hole_at(1.0, 0.0)};
    const WaypointPath path = plan_hole_reinspection(holes, kNormal, {0.0, -1.0, 0.0});
    ASSERT_EQ(path.waypoints.size(), 3U);
    EXPECT_NEAR(path.waypoints[0].p_world_m.x(), 1.0, kExact);
    EXPECT_NEAR(path.waypoints[1].p_world_m.x(), 3.0, kExact);
    EXPECT_NEAR(path.waypoints[2].p_world_m.x(), -2.5, kExact);
}

TEST(HoleReinspection, EqualDistancesGoToTheLowerIndex) {
    const std::vector<ReinspectionHole> holes{hole_at(2.0, 0.0), hole_at(-2.0, 0.0)};
    const WaypointPath path = plan_hole_reinspection(holes, kNormal, {0.0, -1.0, 0.0});
    ASSERT_EQ(path.waypoints.size(), 2U);
    EXPECT_NEAR(path.waypoints[0].p_world_m.x(), 2.0, kExact);
    const std::vector<ReinspectionHole> swapped{holes[1], holes[0]};
    const WaypointPath other = plan_hole_reinspection(swapped, kNormal, {0.0, -1.0, 0.0});
    EXPECT_NEAR(other.waypoints[0].p_world_m.x(), -2.0, kExact);
}

TEST(HoleReinspection, WideHoleGetsAPassFromItsNearerEndThroughTheCentroid) {
    // 3 m wide, footprint 1.59 m: the ends at ±(1.5 − 0.795) = ±0.705 m from the centroid.
    const std::vector<ReinspectionHole> holes{hole_at(5.0, -2.0, 3.0, 0.6)};
    const WaypointPath path = plan_hole_reinspection(holes, kNormal, {10.0, -1.0, -2.0});
    ASSERT_EQ(path.waypoints.size(), 3U);
    EXPECT_LT((path.waypoints[0].p_world_m - Eigen::Vector3d(5.705, -1.0, -2.0)).norm(), kExact);
    EXPECT_LT((path.waypoints[1].p_world_m - Eigen::Vector3d(5.0, -1.0, -2.0)).norm(), kExact);
    EXPECT_LT((path.waypoints[2].p_world_m - Eigen::Vector3d(4.295, -1.0, -2.0)).norm(), kExact);
    // A tall hole passes along its v axis (z here); from below it starts at the bottom end.
    const std::vector<ReinspectionHole> tall{hole_at(0.0, -2.0, 0.4, 2.0)};
    const WaypointPath up = plan_hole_reinspection(tall, kNormal, {0.0, -1.0, -5.0});
    ASSERT_EQ(up.waypoints.size(), 3U);
    EXPECT_NEAR(up.waypoints[0].p_world_m.z(), -2.0 - (1.0 - 0.795), kExact);
    EXPECT_NEAR(up.waypoints[2].p_world_m.z(), -2.0 + (1.0 - 0.795), kExact);
    for (const Waypoint& wp : up.waypoints) EXPECT_NEAR(wp.p_world_m.y(), -1.0, kExact);
}

TEST(HoleReinspection, TiltedHullKeepsTheStandOffAlongItsNormal) {
    const Eigen::Vector3d normal = Eigen::Vector3d(-1.0, -1.0, 0.0).normalized();
    ReinspectionHole hole = hole_at(0.0, 0.0);
    hole.axis_u_world = Eigen::Vector3d(1.0, -1.0, 0.0).normalized();
    const std::vector<ReinspectionHole> holes{hole};
    const WaypointPath path = plan_hole_reinspection(holes, normal, {-5.0, -5.0, 0.0});
    ASSERT_EQ(path.waypoints.size(), 1U);
    EXPECT_LT((path.waypoints[0].p_world_m - normal).norm(), kExact);
    EXPECT_NEAR(*path.waypoints[0].yaw_rad, std::atan2(1.0, 1.0), kExact);
}

TEST(HoleReinspection, NoHolesGiveAnEmptyPath) {
    EXPECT_TRUE(plan_hole_reinspection({}, kNormal, Eigen::Vector3d::Zero()).waypoints.empty());
}

TEST(HoleReinspection, BadRequestsThrowNamingTheField) {
    const std::vector<ReinspectionHole> ok{hole_at(0.0, 0.0)};
    const Eigen::Vector3d start(0.0, -1.0, 0.0);
    SCANTLING_EXPECT_ERROR(plan_hole_reinspection(ok, Eigen::Vector3d::UnitZ(), start), InputError,
                           "normal_world");
    SCANTLING_EXPECT_ERROR(plan_hole_reinspection(ok, Eigen::Vector3d::Zero(), start), InputError,
                           "normal_world");
    SCANTLING_EXPECT_ERROR(plan_hole_reinspection(ok, kNormal, {kNaN, 0.0, 0.0}), InputError,
                           "p_start_world_m");
    std::vector<ReinspectionHole> bad{hole_at(0.0, 0.0), hole_at(1.0, 0.0)};
    bad[1].axis_u_world = {2.0, 0.0, 0.0};
    SCANTLING_EXPECT_ERROR(plan_hole_reinspection(bad, kNormal, start), InputError,
                           "holes[1].axis_u_world");
    bad[1] = hole_at(1.0, 0.0);
    bad[1].axis_v_world = Eigen::Vector3d(1.0, 0.0, 1.0).normalized();
    SCANTLING_EXPECT_ERROR(plan_hole_reinspection(bad, kNormal, start), InputError,
                           "holes[1].axis_v_world");
    bad[1] = hole_at(1.0, 0.0);
    bad[1].box_min_u_m = 0.1;  // the box misses its centroid
    SCANTLING_EXPECT_ERROR(plan_hole_reinspection(bad, kNormal, start), InputError,
                           "holes[1].box_min_u_m = 0.1");
    bad[1] = hole_at(1.0, 0.0);
    bad[1].centroid_world_m.z() = kNaN;
    SCANTLING_EXPECT_ERROR(plan_hole_reinspection(bad, kNormal, start), InputError,
                           "holes[1].centroid_world_m");
    HoleReinspectionConfig config;
    config.stand_off_m = 0.0;
    SCANTLING_EXPECT_ERROR(plan_hole_reinspection(ok, kNormal, start, config), ConfigError,
                           "hole_reinspection.stand_off_m = 0");
    config = {};
    config.footprint_width_m = kNaN;
    SCANTLING_EXPECT_ERROR(plan_hole_reinspection(ok, kNormal, start, config), ConfigError,
                           "hole_reinspection.footprint_width_m");
    config = {};
    config.waypoint_tolerance_m = -0.2;
    SCANTLING_EXPECT_ERROR(plan_hole_reinspection(ok, kNormal, start, config), ConfigError,
                           "hole_reinspection.waypoint_tolerance_m");
}

}  // namespace
}  // namespace scantling::planning
