// The crawler's rectangle mission and surface lines (planning/surface_rectangle.hpp) on a
// plate, a storage-tank wall and a small mesh plate.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <scantling/core/error.hpp>
#include <scantling/core/surface_projector.hpp>
#include <scantling/planning/surface_rectangle.hpp>

#include "../core/analytic_meshes.hpp"
#include "expect_error.hpp"

namespace scantling::planning {
namespace {

TEST(SurfaceRectangle, AdjustsTheStepSoTheWholeWidthIsCovered) {
    // A wall standing in the x-z plane, normal -y (the robot's side), up +z.
    const PlaneSurface wall(Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitY());
    const SurfaceRectanglePlan plan = plan_surface_rectangle(
        {.start_world_m = {1.0, 0.0, 0.5}, .width_m = 1.0, .height_m = 2.0, .max_step_m = 0.3},
        wall);
    // ⌈1.0 / 0.3⌉ + 1 = 5 transects, 0.25 m apart: the last one exactly at W.
    ASSERT_EQ(plan.transects, 5u);
    EXPECT_DOUBLE_EQ(plan.step_m, 0.25);
    ASSERT_EQ(plan.waypoints_world_m.size(), 10u);
    // across = up × n = z × (−y) = +x.
    EXPECT_LT((plan.across_world - Eigen::Vector3d::UnitX()).norm(), 1e-12);
    const std::vector<Eigen::Vector3d> expected = {
        {1.0, 0, 0.5}, {1.0, 0, 2.5},  {1.25, 0, 2.5}, {1.25, 0, 0.5}, {1.5, 0, 0.5},
        {1.5, 0, 2.5}, {1.75, 0, 2.5}, {1.75, 0, 0.5}, {2.0, 0, 0.5},  {2.0, 0, 2.5}};
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_LT((plan.waypoints_world_m[i] - expected[i]).norm(), 1e-9) << i;
    }
}

TEST(SurfaceRectangle, WalksAroundATankWall) {
    // The storage tank's shell, Ø 12 m, crawled from outside; start at +x.
    const double r = 6.0;
    const CylinderSurface shell(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), r);
    const SurfaceRectanglePlan plan = plan_surface_rectangle(
        {.start_world_m = {r, 0.0, 0.5}, .width_m = 6.0, .height_m = 2.0, .max_step_m = 0.5},
        shell);
    ASSERT_EQ(plan.transects, 13u);
    for (std::size_t i = 0; i < plan.transects; ++i) {
        // Transect i stands at arc length i · 0.5 m (chords of 1 cm: 1e-7 relative).
        const double angle = 0.5 * static_cast<double>(i) / r;
        const Eigen::Vector3d bottom(r * std::cos(angle), r * std::sin(angle), 0.5);
        const Eigen::Vector3d& first = plan.waypoints_world_m[2 * i];
        const Eigen::Vector3d& second = plan.waypoints_world_m[2 * i + 1];
        const Eigen::Vector3d& b = i % 2 == 0 ? first : second;
        const Eigen::Vector3d& t = i % 2 == 0 ? second : first;
        EXPECT_LT((b - bottom).norm(), 1e-4) << i;
        EXPECT_LT((t - bottom - Eigen::Vector3d(0, 0, 2.0)).norm(), 1e-4) << i;
    }
    // A line along the width is the arc, in segments of 5 cm on the shell.
    const auto line = surface_line(shell, plan.waypoints_world_m[1], plan.waypoints_world_m[2]);
    double length_m = 0.0;
    for (const MeshPathSegment& s : line) {
        length_m += (s.end_world_m - s.begin_world_m).norm();
        EXPECT_NEAR(s.end_world_m.head<2>().norm(), r, 1e-9);
        const Eigen::Vector3d middle = 0.5 * (s.begin_world_m + s.end_world_m);
        EXPECT_GT(s.normal_world.dot(Eigen::Vector3d(middle.x(), middle.y(), 0).normalized()),
                  1.0 - 1e-9);
    }
    EXPECT_NEAR(length_m, 0.5, 1e-3);
    EXPECT_NEAR(static_cast<double>(line.size()), 10.0, 1.0);  // 5 cm each, the last shorter
}

TEST(SurfaceRectangle, RefusesImpossibleRequests) {
    const PlaneSurface wall(Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitY());
    const SurfaceRectangleRequest good{.start_world_m = {0, 0, 0}, .width_m = 1, .height_m = 1};
    EXPECT_NO_THROW(plan_surface_rectangle(good, wall));
    SurfaceRectangleRequest r = good;
    r.width_m = 0.0;
    SCANTLING_EXPECT_ERROR(plan_surface_rectangle(r, wall), InputError, "width_m = 0");
    r = good;
    r.height_m = std::nan("");
    SCANTLING_EXPECT_ERROR(plan_surface_rectangle(r, wall), InputError, "height_m");
    r = good;
    r.start_world_m = {0.0, -0.4, 0.0};  // 0.4 m in front of the wall
    SCANTLING_EXPECT_ERROR(plan_surface_rectangle(r, wall), InputError, "from the surface");
    // A floor: up is the normal.
    const PlaneSurface floor(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
    SCANTLING_EXPECT_ERROR(plan_surface_rectangle(good, floor), InputError, "no vertical");
    // A 1 × 1 m mesh plate (z = 0, up +y here): a 2 m high rectangle leaves it.
    const MeshSurface plate(testing::grid_plate(0.5, 10));
    SurfaceRectangleRequest on_plate{.start_world_m = {-0.4, -0.4, 0.0},
                                     .width_m = 0.5,
                                     .height_m = 2.0,
                                     .up_world = Eigen::Vector3d::UnitY()};
    SCANTLING_EXPECT_ERROR(plan_surface_rectangle(on_plate, plate), InputError,
                           "leaves the surface");
    on_plate.height_m = 0.7;
    EXPECT_NO_THROW(plan_surface_rectangle(on_plate, plate));
}

}  // namespace
}  // namespace scantling::planning
