// Replanning around the obstacle that stopped the crawler (planning/detour.hpp) on a plate, near
// its edges, past a second obstacle, on a tank wall, and the refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/surface_projector.hpp>
#include <scantling/planning/detour.hpp>
#include <scantling/planning/surface_rectangle.hpp>

#include "../core/analytic_meshes.hpp"
#include "expect_error.hpp"

namespace scantling::planning {
namespace {

// The detour may round a clearance by a micrometre (detour.hpp); a test allows no more.
constexpr double kClearanceTolerance_m = 1e-6;
// Points of a straight line on a plate are exact to rounding.
constexpr double kPlateExact_m = 1e-9;
// Samples per segment when checking a clearance between its ends (segments are ≤ 5 cm).
constexpr int kSamplesPerSegment = 50;

using Path = std::vector<MeshPathSegment>;

/// A 5 × (2 · half_width) m plate in the x-y plane, normal +z, centred at the origin.
PlateSurface plate(double half_width_m = 1.0) {
    return PlateSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                        2.5, half_width_m);
}

/// The nearest the path comes to `centre`, sampled densely along every segment.
double min_distance_m(const Path& path, const Eigen::Vector3d& centre) {
    double nearest_m = std::numeric_limits<double>::infinity();
    for (const MeshPathSegment& s : path) {
        for (int i = 0; i <= kSamplesPerSegment; ++i) {
            const double t = static_cast<double>(i) / kSamplesPerSegment;
            const Eigen::Vector3d p = s.begin_world_m + t * (s.end_world_m - s.begin_world_m);
            nearest_m = std::min(nearest_m, (p - centre).norm());
        }
    }
    return nearest_m;
}

double length_m(const Path& path) {
    double sum_m = 0.0;
    for (const MeshPathSegment& s : path) sum_m += (s.end_world_m - s.begin_world_m).norm();
    return sum_m;
}

void expect_contiguous(const Path& path) {
    for (std::size_t i = 1; i < path.size(); ++i) {
        EXPECT_LT((path[i].begin_world_m - path[i - 1].end_world_m).norm(), 1e-12) << i;
    }
}

void expect_clear(const Detour& detour, const std::vector<ObstacleFootprint>& obstacles,
                  double clearance_m) {
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
        EXPECT_GE(min_distance_m(detour.path, obstacles[k].centre_world_m),
                  obstacles[k].radius_m + clearance_m - kClearanceTolerance_m)
            << "obstacles[" << k << "]";
    }
}

TEST(Detour, PassesAnObstacleOnAStraightPathAtTheClearanceAndRejoinsIt) {
    const PlateSurface surface = plate();
    const Eigen::Vector3d crawler(-1.5, 0, 0), goal(2, 0, 0);
    const Path remaining = surface_line(surface, crawler, goal);
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {0, 0, 0}, .radius_m = 0.1}};
    const Detour detour = plan_detour(surface, crawler, remaining, obstacles, 0);
    ASSERT_TRUE(detour.found) << detour.reason;
    EXPECT_TRUE(detour.reason.empty());
    EXPECT_EQ(detour.side, +1);  // a tie: left, y > 0 (normal z × forward x)
    EXPECT_DOUBLE_EQ(detour.offset_m, 0.3);
    expect_contiguous(detour.path);
    expect_clear(detour, obstacles, 0.2);
    EXPECT_LT((detour.path.front().begin_world_m - crawler).norm(), kPlateExact_m);
    EXPECT_LT((detour.path.back().end_world_m - goal).norm(), kPlateExact_m);
    // Leaves at x = −0.4 (0.1 + 0.3 before the centre), rejoins at x = +0.4, passes at y = 0.3.
    EXPECT_LT((detour.rejoin_world_m - Eigen::Vector3d(0.4, 0, 0)).norm(), kPlateExact_m);
    double widest_m = 0.0;
    for (const MeshPathSegment& s : detour.path) {
        widest_m = std::max(widest_m, s.end_world_m.y());
        EXPECT_GE(s.end_world_m.y(), -kPlateExact_m);
        if (s.begin_world_m.x() >= 0.4 - kPlateExact_m || s.end_world_m.x() <= -0.4) {
            EXPECT_LT(std::abs(s.begin_world_m.y()) + std::abs(s.end_world_m.y()), kPlateExact_m);
        }
    }
    EXPECT_NEAR(widest_m, 0.3, kPlateExact_m);
    // Two diagonals of 0.15 m along and 0.3 m across replace 0.3 m of the old line.
    const double expected_m = 3.5 + 2.0 * (std::hypot(0.15, 0.3) - 0.15);
    EXPECT_NEAR(detour.length_m, expected_m, 1e-9);
    EXPECT_NEAR(length_m(detour.path), detour.length_m, 1e-12);
    // Deterministic.
    const Detour again = plan_detour(surface, crawler, remaining, obstacles, 0);
    ASSERT_EQ(again.path.size(), detour.path.size());
    for (std::size_t i = 0; i < again.path.size(); ++i) {
        EXPECT_EQ(again.path[i].end_world_m, detour.path[i].end_world_m) << i;
    }
}

TEST(Detour, StepsSidewaysWhenStoppedAtTheClearance) {
    const PlateSurface surface = plate();
    const Eigen::Vector3d crawler(-0.3, 0, 0), goal(2, 0, 0);
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {0, 0, 0}, .radius_m = 0.1}};
    const Detour detour =
        plan_detour(surface, crawler, surface_line(surface, crawler, goal), obstacles, 0);
    ASSERT_TRUE(detour.found) << detour.reason;
    // A diagonal from here would cut 4 mm into the clearance: the first leg is across.
    const MeshPathSegment& first = detour.path.front();
    EXPECT_NEAR(first.begin_world_m.x(), -0.3, kPlateExact_m);
    EXPECT_NEAR(first.end_world_m.x(), -0.3, kPlateExact_m);
    EXPECT_GT(first.end_world_m.y(), first.begin_world_m.y());
    expect_clear(detour, obstacles, 0.2);
    EXPECT_LT((detour.path.back().end_world_m - goal).norm(), kPlateExact_m);
}

TEST(Detour, GoesRightNearThePlatesLeftEdge) {
    const PlateSurface surface = plate();  // |y| <= 1
    const Eigen::Vector3d crawler(-1.5, 0.8, 0), goal(2, 0.8, 0);
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {0, 0.8, 0}, .radius_m = 0.1}};
    const Detour detour =
        plan_detour(surface, crawler, surface_line(surface, crawler, goal), obstacles, 0);
    ASSERT_TRUE(detour.found) << detour.reason;
    EXPECT_EQ(detour.side, -1);
    EXPECT_DOUBLE_EQ(detour.offset_m, 0.3);
    expect_clear(detour, obstacles, 0.2);
    for (const MeshPathSegment& s : detour.path) {
        EXPECT_LE(s.end_world_m.y(), 0.8 + kPlateExact_m);
        EXPECT_GE(s.end_world_m.y(), 0.5 - kPlateExact_m);
    }
}

TEST(Detour, NotFoundWhenBothSidesLeaveANarrowPlate) {
    const PlateSurface surface = plate(0.25);  // 0.1 + 0.2 m needed, 0.25 m on each side
    const Eigen::Vector3d crawler(-1.5, 0, 0), goal(2, 0, 0);
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {0, 0, 0}, .radius_m = 0.1}};
    const Detour detour =
        plan_detour(surface, crawler, surface_line(surface, crawler, goal), obstacles, 0);
    EXPECT_FALSE(detour.found);
    EXPECT_TRUE(detour.path.empty());
    EXPECT_NE(detour.reason.find("left"), std::string::npos) << detour.reason;
    EXPECT_NE(detour.reason.find("right"), std::string::npos) << detour.reason;
    EXPECT_NE(detour.reason.find("leaves the surface"), std::string::npos) << detour.reason;
}

TEST(Detour, GoesRightOfASecondObstacleOnTheLeft) {
    const PlateSurface surface = plate();
    const Eigen::Vector3d crawler(-1.5, 0, 0), goal(2, 0, 0);
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {0, 0, 0}, .radius_m = 0.1},
        {.centre_world_m = {0, 0.45, 0}, .radius_m = 0.1}};
    const Detour detour =
        plan_detour(surface, crawler, surface_line(surface, crawler, goal), obstacles, 0);
    ASSERT_TRUE(detour.found) << detour.reason;
    EXPECT_EQ(detour.side, -1);
    EXPECT_DOUBLE_EQ(detour.offset_m, 0.3);
    expect_clear(detour, obstacles, 0.2);
}

TEST(Detour, WidensTheOffsetPastASecondObstacleWhenTheOtherSideIsTheEdge) {
    const PlateSurface surface = plate();  // the right side, y < -1, is off the plate
    const Eigen::Vector3d crawler(-1.5, -0.8, 0), goal(2, -0.8, 0);
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {0, -0.8, 0}, .radius_m = 0.1},
        {.centre_world_m = {0, -0.35, 0}, .radius_m = 0.1}};
    const Detour detour =
        plan_detour(surface, crawler, surface_line(surface, crawler, goal), obstacles, 0);
    ASSERT_TRUE(detour.found) << detour.reason;
    EXPECT_EQ(detour.side, +1);
    // Past the second one's far side: 0.45 + 0.1 + 0.2 m at least, in steps of 5 cm.
    EXPECT_GE(detour.offset_m, 0.75 - kPlateExact_m);
    EXPECT_LE(detour.offset_m, 0.9);
    expect_clear(detour, obstacles, 0.2);
    // With the widening capped below that, neither side works; the reason says why.
    const Detour capped = plan_detour(
        surface, crawler, surface_line(surface, crawler, goal), obstacles, 0, {},
        {.clearance_m = 0.2, .rejoin_m = 0.3, .max_offset_m = 0.6, .offset_step_m = 0.05});
    EXPECT_FALSE(capped.found);
    EXPECT_NE(capped.reason.find("obstacles[1]"), std::string::npos) << capped.reason;
    EXPECT_NE(capped.reason.find("leaves the surface"), std::string::npos) << capped.reason;
}

/// Every segment end on the unit cylinder around z.
void expect_on_unit_cylinder(const Path& path) {
    constexpr double kOnSurface_m = 1e-3;
    for (const MeshPathSegment& s : path) {
        EXPECT_NEAR(s.begin_world_m.head<2>().norm(), 1.0, kOnSurface_m);
        EXPECT_NEAR(s.end_world_m.head<2>().norm(), 1.0, kOnSurface_m);
    }
}

TEST(Detour, StaysOnATankWallAlongItsAxis) {
    const CylinderSurface wall(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 1.0);
    const Eigen::Vector3d crawler(1, 0, -1.5), goal(1, 0, 1.5);
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {1, 0, 0}, .radius_m = 0.1}};
    const Detour detour =
        plan_detour(wall, crawler, surface_line(wall, crawler, goal), obstacles, 0);
    ASSERT_TRUE(detour.found) << detour.reason;
    expect_on_unit_cylinder(detour.path);
    expect_clear(detour, obstacles, 0.2);
    // 0.3 m around the wall is a 0.299 m chord: the offset grows one step.
    EXPECT_DOUBLE_EQ(detour.offset_m, 0.35);
    EXPECT_LT((detour.path.back().end_world_m - goal).norm(), 1e-9);
}

TEST(Detour, StaysOnATankWallAroundIt) {
    const CylinderSurface wall(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 1.0);
    const Eigen::Vector3d crawler(std::cos(-1.5), std::sin(-1.5), 0);
    const Eigen::Vector3d goal(std::cos(1.5), std::sin(1.5), 0);
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {1, 0, 0}, .radius_m = 0.1}};
    const Detour detour =
        plan_detour(wall, crawler, surface_line(wall, crawler, goal), obstacles, 0);
    ASSERT_TRUE(detour.found) << detour.reason;
    EXPECT_EQ(detour.side, +1);  // left of travel around +z is up the wall
    expect_on_unit_cylinder(detour.path);
    expect_clear(detour, obstacles, 0.2);
    EXPECT_LT((detour.path.back().end_world_m - goal).norm(), 1e-3);
}

TEST(Detour, KeepsToAMeshPlateAwayFromItsEdge) {
    // A 2 × 2 m mesh plate; the path 0.25 m from its y = 1 edge: 0.3 m to the left is off it.
    const MeshSurface surface(testing::grid_plate(1.0, 20));
    const Eigen::Vector3d crawler(-0.9, 0.75, 0), goal(0.9, 0.75, 0);
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {0, 0.75, 0}, .radius_m = 0.1}};
    const Detour detour =
        plan_detour(surface, crawler, surface_line(surface, crawler, goal), obstacles, 0);
    ASSERT_TRUE(detour.found) << detour.reason;
    EXPECT_EQ(detour.side, -1);
    expect_clear(detour, obstacles, 0.2);
    for (const MeshPathSegment& s : detour.path) EXPECT_NEAR(s.end_world_m.z(), 0.0, 1e-9);
    EXPECT_LT((detour.path.back().end_world_m - goal).norm(), 1e-9);
}

TEST(Detour, RejoinsLaterWhenAnObstacleStandsBesideTheFirstRejoinPoint) {
    // The blocking obstacle on the path at x = 0, a second one 0.2 m to the left of the path
    // just past the first rejoin point (x = 0.4 + 0.1): rejoining at x = 0.4 from the right
    // passes it at 0.2 m, inside its 0.05 + 0.2 m; rejoining at x = 0.7 passes it clear.
    const PlateSurface surface = plate();
    const Eigen::Vector3d crawler(-1.0, 0, 0), goal(2, 0, 0);
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {0, 0, 0}, .radius_m = 0.1},
        {.centre_world_m = {0.5, 0.2, 0}, .radius_m = 0.05}};
    DetourConfig config;
    config.max_offset_m = 0.3;  // no wider way round on the left
    const Detour detour = plan_detour(surface, crawler, surface_line(surface, crawler, goal),
                                      obstacles, 0, {}, config);
    ASSERT_TRUE(detour.found) << detour.reason;
    EXPECT_EQ(detour.side, -1);
    EXPECT_GT(detour.rejoin_world_m.x(), 0.45);  // later than s_o + r + R = 0.4
    // The new pieces (before the rejoin) clear both; the old path after it is the plan the
    // second obstacle did not block.
    Path fresh;
    for (const MeshPathSegment& seg : detour.path) {
        if (seg.begin_world_m.x() < detour.rejoin_world_m.x() - 1e-9) fresh.push_back(seg);
    }
    EXPECT_GE(min_distance_m(fresh, obstacles[0].centre_world_m), 0.3 - kClearanceTolerance_m);
    EXPECT_GE(min_distance_m(fresh, obstacles[1].centre_world_m), 0.25 - kClearanceTolerance_m);
    EXPECT_LT((detour.path.back().end_world_m - goal).norm(), 1e-9);
}

TEST(Detour, NotFoundWhenTheObstacleCoversTheGoal) {
    const PlateSurface surface = plate();
    const Eigen::Vector3d crawler(-1.5, 0, 0), goal(2, 0, 0);
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {2.1, 0, 0}, .radius_m = 0.1}};
    const Detour detour =
        plan_detour(surface, crawler, surface_line(surface, crawler, goal), obstacles, 0);
    EXPECT_FALSE(detour.found);
    EXPECT_NE(detour.reason.find("goal"), std::string::npos) << detour.reason;
}

TEST(Detour, RefusesBadInputNamingTheArgument) {
    const PlateSurface surface = plate();
    const Eigen::Vector3d crawler(-1.5, 0, 0);
    const Path remaining = surface_line(surface, crawler, {2, 0, 0});
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {0, 0, 0}, .radius_m = 0.1}};
    EXPECT_NO_THROW(plan_detour(surface, crawler, remaining, obstacles, 0));
    SCANTLING_EXPECT_ERROR(
        plan_detour(surface, Eigen::Vector3d(std::nan(""), 0, 0), remaining, obstacles, 0),
        InputError, "p_world_m");
    SCANTLING_EXPECT_ERROR(
        plan_detour(surface, Eigen::Vector3d(-1.5, 0, 1), remaining, obstacles, 0), InputError,
        "p_world_m");
    SCANTLING_EXPECT_ERROR(plan_detour(surface, crawler, {}, obstacles, 0), InputError,
                           "remaining");
    SCANTLING_EXPECT_ERROR(plan_detour(surface, crawler, remaining, obstacles, 1), InputError,
                           "blocking = 1");
    std::vector<ObstacleFootprint> bad = obstacles;
    bad.push_back({.centre_world_m = {1, 0, 0}, .radius_m = -0.1});
    SCANTLING_EXPECT_ERROR(plan_detour(surface, crawler, remaining, bad, 0), InputError,
                           "obstacles[1]");
}

TEST(Detour, RefusesABadConfigNamingTheField) {
    const PlateSurface surface = plate();
    const Eigen::Vector3d crawler(-1.5, 0, 0);
    const Path remaining = surface_line(surface, crawler, {2, 0, 0});
    const std::vector<ObstacleFootprint> obstacles = {
        {.centre_world_m = {0, 0, 0}, .radius_m = 0.1}};
    const auto with = [&](DetourConfig config) {
        return plan_detour(surface, crawler, remaining, obstacles, 0, {}, config);
    };
    DetourConfig c;
    c.clearance_m = 0.0;
    SCANTLING_EXPECT_ERROR(with(c), ConfigError, "detour.clearance_m = 0");
    c = {};
    c.rejoin_m = -1.0;
    SCANTLING_EXPECT_ERROR(with(c), ConfigError, "detour.rejoin_m");
    c = {};
    c.max_offset_m = std::nan("");
    SCANTLING_EXPECT_ERROR(with(c), ConfigError, "detour.max_offset_m");
    c = {};
    c.offset_step_m = 0.0;
    SCANTLING_EXPECT_ERROR(with(c), ConfigError, "detour.offset_step_m");
    SurfaceWalkConfig walk;
    walk.march_step_m = 0.0;
    SCANTLING_EXPECT_ERROR(plan_detour(surface, crawler, remaining, obstacles, 0, walk),
                           ConfigError, "surface_walk.march_step_m");
}

}  // namespace
}  // namespace scantling::planning
