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

/// The 2 × 2 m mesh plate of 0.1 m cells (z = 0) without the cells whose centre lies inside
/// the square |x|, |y| < hole_half_m: a hole in the middle.
TriangleMesh plate_with_hole(double hole_half_m) {
    const TriangleMesh full = testing::grid_plate(1.0, 20);
    TriangleMesh holed;
    holed.vertices = full.vertices;
    for (const Eigen::Vector3i& t : full.triangles) {
        const Eigen::Vector3d c =
            (full.vertices[t[0]] + full.vertices[t[1]] + full.vertices[t[2]]) / 3.0;
        if (std::abs(c.x()) < hole_half_m && std::abs(c.y()) < hole_half_m) continue;
        holed.triangles.push_back(t);
    }
    return holed;
}

TEST(SurfaceRectangle, SnapsAStartOntoTheSurfaceOrNamesTheFieldAndTheDistance) {
    const MeshSurface plate(testing::grid_plate(0.5, 10));
    const SurfacePoint on = snap_to_surface(plate, {0.1, 0.2, 0.03}, 0.05, "start.xyz");
    EXPECT_LT((on.point - Eigen::Vector3d(0.1, 0.2, 0.0)).norm(), 1e-12);
    // 0.3 m above the plate, and 0.5 m beside its edge.
    SCANTLING_EXPECT_ERROR(snap_to_surface(plate, {0.1, 0.2, 0.3}, 0.05, "start.xyz"), InputError,
                           "start.xyz = (0.100, 0.200, 0.300) is 0.300 m from the surface");
    SCANTLING_EXPECT_ERROR(snap_to_surface(plate, {1.0, 0.0, 0.0}, 0.05, "start.xyz"), InputError,
                           "is 0.500 m from the surface, expected <= 0.05 m");
    SCANTLING_EXPECT_ERROR(snap_to_surface(plate, {NAN, 0.0, 0.0}, 0.05, "start.xyz"), InputError,
                           "start.xyz = (nan, 0.000, 0.000) is not finite");
}

TEST(SurfaceRectangle, ARectangleOverABoundedPlatesEdgeIsRefused) {
    // The 5 × 2 m plate (z = 0, up +y): 4.4 m across fits, 8 m runs over its x = 2.5 m edge
    // (on the unbounded plane it was planned, and flown into the air).
    const PlateSurface plate(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                             Eigen::Vector3d::UnitX(), 2.5, 1.0);
    SurfaceRectangleRequest request{.start_world_m = {-2.2, -0.6, 0.0},
                                    .width_m = 4.4,
                                    .height_m = 1.2,
                                    .max_step_m = 0.4,
                                    .up_world = Eigen::Vector3d::UnitY()};
    EXPECT_EQ(plan_surface_rectangle(request, plate).transects, 12u);
    request.width_m = 8.0;
    SCANTLING_EXPECT_ERROR(plan_surface_rectangle(request, plate), InputError,
                           "surface_rectangle.width_m: the bottom edge (4.800 m across to "
                           "transect 13 of 21) leaves the surface at (2.500, -0.600, 0.000)");
}

TEST(SurfaceRectangle, AWalkGrazingTheBorderIsRefusedNotSlidAlong) {
    // The 1 × 1 m mesh plate; a walk 11° off its x axis meets the y = -0.5 border after
    // 0.5 m. Each step still advances by 98 % of its length there, held on the border: the
    // walk used to slide along it and return a point on the border as if nothing happened.
    const MeshSurface plate(testing::grid_plate(0.5, 10));
    const Eigen::Vector3d start(-0.4, -0.4, 0.0);
    SCANTLING_EXPECT_ERROR(walk_on_surface(plate, start, {1.0, -0.2, 0.0}, 0.8), InputError,
                           "leaves the surface");
    // Walks that stay on the plate are unchanged: the straight line, to 1e-9.
    const Eigen::Vector3d end = walk_on_surface(plate, start, {1.0, -0.05, 0.0}, 0.6);
    EXPECT_LT((end - start - 0.6 * Eigen::Vector3d(1.0, -0.05, 0.0).normalized()).norm(), 1e-9);
}

TEST(SurfaceRectangle, ATransectAcrossAHoleIsRefusedAndARectangleAroundItIsPlanned) {
    // A 0.4 m hole in the middle of a 2 × 2 m mesh plate; up +y, transects along y.
    const MeshSurface plate(plate_with_hole(0.2));
    const SurfaceRectangleRequest across{.start_world_m = {-0.8, -0.8, 0.0},
                                         .width_m = 1.6,
                                         .height_m = 1.6,
                                         .max_step_m = 0.4,
                                         .up_world = Eigen::Vector3d::UnitY()};
    // Transects at x = -0.8, -0.4, 0, 0.4, 0.8: the third runs into the hole.
    SCANTLING_EXPECT_ERROR(plan_surface_rectangle(across, plate), InputError,
                           "surface_rectangle.height_m: transect 3 of 5");
    // Two transects at x = ±0.45 and the legs along y = ±0.8 go round the hole: planned, the
    // hole between the transects left out.
    SurfaceRectangleRequest around = across;
    around.start_world_m = {-0.45, -0.8, 0.0};
    around.width_m = 0.9;
    around.max_step_m = 0.9;
    const SurfaceRectanglePlan plan = plan_surface_rectangle(around, plate);
    ASSERT_EQ(plan.transects, 2u);
    EXPECT_LT((plan.waypoints_world_m[2] - Eigen::Vector3d(0.45, 0.8, 0.0)).norm(), 1e-9);
    // A line across the hole is refused as well.
    SCANTLING_EXPECT_ERROR(surface_line(plate, {-0.5, 0.0, 0.0}, {0.5, 0.0, 0.0}), InputError,
                           "the line leaves the surface");
}

TEST(SurfaceRectangle, NonManifoldMeshesAreWalkedWithoutNansOrHangs) {
    // The 1 × 1 m plate with a 0.1 m fin standing on x = 0 (each fin quad shares a plate edge:
    // edges of three triangles), one plate triangle repeated the other way round (a double-
    // sided patch) and a sliver on a plate edge.
    TriangleMesh mesh = testing::grid_plate(0.5, 10);
    const auto vertex = [&](const Eigen::Vector3d& p) {
        mesh.vertices.push_back(p);
        return static_cast<int>(mesh.vertices.size()) - 1;
    };
    for (int j = 3; j < 7; ++j) {
        const int a = j * 11 + 5, b = (j + 1) * 11 + 5;  // grid vertices on x = 0
        const int c = vertex(mesh.vertices[b] + Eigen::Vector3d(0, 0, 0.1));
        const int d = vertex(mesh.vertices[a] + Eigen::Vector3d(0, 0, 0.1));
        mesh.triangles.emplace_back(a, b, c);
        mesh.triangles.emplace_back(a, c, d);
    }
    const Eigen::Vector3i first = mesh.triangles[30];
    mesh.triangles.emplace_back(first[0], first[2], first[1]);
    mesh.triangles.emplace_back(0, 1, vertex(0.5 * (mesh.vertices[0] + mesh.vertices[1])));
    const MeshSurface surface(mesh);
    for (int i = 0; i <= 20; ++i) {
        for (int j = 0; j <= 20; ++j) {
            const SurfacePoint s = surface.project({-0.5 + 0.05 * i, -0.5 + 0.05 * j, 0.02});
            ASSERT_TRUE(s.point.allFinite() && s.normal.allFinite()) << i << " " << j;
            EXPECT_NEAR(s.normal.norm(), 1.0, 1e-9) << i << " " << j;
        }
    }
    // Walks, lines and a rectangle across the fin's foot: a result or an InputError, never a
    // NaN (the test ending says they do not hang).
    const auto finite_or_refused = [](auto&& plan_it) {
        try {
            plan_it();
        } catch (const InputError&) {
        }
    };
    finite_or_refused([&] {
        EXPECT_TRUE(walk_on_surface(surface, {-0.3, 0.0, 0.0}, {1, 0, 0}, 0.6).allFinite());
    });
    finite_or_refused([&] {
        for (const MeshPathSegment& s : surface_line(surface, {-0.3, 0.0, 0.0}, {0.3, 0.1, 0.0})) {
            EXPECT_TRUE(s.end_world_m.allFinite() && s.normal_world.allFinite());
        }
    });
    finite_or_refused([&] {
        const SurfaceRectanglePlan plan =
            plan_surface_rectangle({.start_world_m = {-0.3, -0.3, 0.0},
                                    .width_m = 0.6,
                                    .height_m = 0.6,
                                    .max_step_m = 0.2,
                                    .up_world = Eigen::Vector3d::UnitY()},
                                   surface);
        for (const Eigen::Vector3d& p : plan.waypoints_world_m) EXPECT_TRUE(p.allFinite());
    });
}

}  // namespace
}  // namespace scantling::planning
