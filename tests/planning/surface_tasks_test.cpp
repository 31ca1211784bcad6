// The crawler's mission tasks (planning/surface_tasks.hpp) on a wall, a tank shell and a mesh
// plate: where each leg goes, which legs are scored, and the refusals.
#include <gtest/gtest.h>

#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/core/surface_projector.hpp>
#include <scantling/planning/surface_tasks.hpp>

#include "../core/analytic_meshes.hpp"
#include "expect_error.hpp"

namespace scantling::planning {
namespace {

/// A wall in the x-z plane, normal -y (the robot's side): up +z, across = up × n = +x.
const PlaneSurface& wall() {
    static const PlaneSurface surface(Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitY());
    return surface;
}

SurfaceTask task_of(SurfaceTaskType type, double length_m = 1.0, bool reverse = false) {
    SurfaceTask t;
    t.type = type;
    t.length_m = length_m;
    t.reverse = reverse;
    return t;
}

Eigen::Vector3d end_of(const TaskPlan& plan) {
    return plan.legs.back().segments.back().end_world_m;
}

TEST(SurfaceTasks, TransectsGoUpDownRightAndLeftByTheirLength) {
    const Eigen::Vector3d p(1.0, 0.0, 0.5);
    const auto end = [&](SurfaceTaskType type, bool reverse) {
        const TaskPlan plan =
            lay_surface_task(task_of(type, 0.8, reverse), wall(), nullptr, p, {}, "tasks[0]");
        EXPECT_EQ(plan.legs.size(), 1u);
        EXPECT_TRUE(plan.legs.front().inspection);
        return end_of(plan);
    };
    EXPECT_LT(
        (end(SurfaceTaskType::kVerticalTransect, false) - Eigen::Vector3d(1.0, 0, 1.3)).norm(),
        1e-9);
    EXPECT_LT(
        (end(SurfaceTaskType::kVerticalTransect, true) - Eigen::Vector3d(1.0, 0, -0.3)).norm(),
        1e-9);
    EXPECT_LT(
        (end(SurfaceTaskType::kHorizontalTransect, false) - Eigen::Vector3d(1.8, 0, 0.5)).norm(),
        1e-9);
    EXPECT_LT(
        (end(SurfaceTaskType::kHorizontalTransect, true) - Eigen::Vector3d(0.2, 0, 0.5)).norm(),
        1e-9);
}

TEST(SurfaceTasks, AHorizontalTransectAroundATankKeepsItsHeight) {
    // The storage tank's shell, Ø 12 m, from outside: 3 m across is an arc of 0.5 rad.
    const double r = 6.0;
    const CylinderSurface shell(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), r);
    const TaskPlan plan = lay_surface_task(task_of(SurfaceTaskType::kHorizontalTransect, 3.0),
                                           shell, nullptr, {r, 0.0, 1.2}, {}, "tasks[0]");
    double length_m = 0.0;
    for (const MeshPathSegment& s : plan.legs.front().segments) {
        EXPECT_NEAR(s.end_world_m.z(), 1.2, 1e-6);
        EXPECT_NEAR(s.end_world_m.head<2>().norm(), r, 1e-6);
        length_m += (s.end_world_m - s.begin_world_m).norm();
    }
    EXPECT_NEAR(length_m, 3.0, 1e-3);
    // across = up × n = z × x = +y: the arc turns counter-clockwise seen from above.
    const Eigen::Vector3d e = end_of(plan);
    EXPECT_NEAR(std::atan2(e.y(), e.x()), 0.5, 1e-3);
}

TEST(SurfaceTasks, GoToTakesTheGeodesicOnAMeshAndIsAnApproach) {
    // A 2 × 2 m grid plate of 0.25 m cells (z = 0): the geodesic is the straight line, cut at
    // every facet it crosses; the walked line on the same mesh is one segment per 5 cm.
    const TriangleMesh mesh = testing::grid_plate(1.0, 8);
    const MeshSurface surface(mesh);
    SurfaceTask go;
    go.goal_world_m = {0.7, 0.4, 0.0};
    const TaskPlan geodesic =
        lay_surface_task(go, surface, &mesh, {-0.6, -0.5, 0.0}, {}, "tasks[0]");
    const TaskPlan walked =
        lay_surface_task(go, surface, nullptr, {-0.6, -0.5, 0.0}, {}, "tasks[0]");
    for (const TaskPlan* plan : {&geodesic, &walked}) {
        ASSERT_EQ(plan->legs.size(), 1u);
        EXPECT_FALSE(plan->legs.front().inspection);
        EXPECT_LT((end_of(*plan) - go.goal_world_m).norm(), 1e-9);
        for (const MeshPathSegment& s : plan->legs.front().segments) {
            // On the line from the start to the goal.
            const Eigen::Vector3d d =
                (go.goal_world_m - Eigen::Vector3d(-0.6, -0.5, 0)).normalized();
            const Eigen::Vector3d off = s.end_world_m - Eigen::Vector3d(-0.6, -0.5, 0);
            EXPECT_LT((off - d * d.dot(off)).norm(), 1e-6);
        }
    }
    // Facets, not walking steps: each geodesic piece names the facet it lies in, one after the
    // other; the walked line's 5 cm segments name none (0).
    const auto& pieces = geodesic.legs.front().segments;
    ASSERT_GT(pieces.size(), 5u);
    for (std::size_t i = 1; i < pieces.size(); ++i) EXPECT_NE(pieces[i].face, pieces[i - 1].face);
    for (const MeshPathSegment& s : walked.legs.front().segments) EXPECT_EQ(s.face, 0u);
}

TEST(SurfaceTasks, ARectangleIsItsApproachThenTheTransects) {
    SurfaceTask rectangle;
    rectangle.type = SurfaceTaskType::kRectangle;
    rectangle.rectangle = {.start_world_m = {1.0, 0.0, 0.5},
                           .width_m = 1.0,
                           .height_m = 2.0,
                           .max_step_m = 0.3,
                           .up_world = Eigen::Vector3d::UnitZ()};
    const TaskPlan plan =
        lay_surface_task(rectangle, wall(), nullptr, {0.5, 0.0, 0.2}, {}, "tasks[0]");
    EXPECT_EQ(plan.transects, 5u);
    EXPECT_DOUBLE_EQ(plan.step_m, 0.25);
    ASSERT_EQ(plan.legs.size(), 10u);  // to the corner, then 5 transects and 4 steps
    EXPECT_FALSE(plan.legs[0].inspection);
    for (std::size_t i = 1; i < plan.legs.size(); ++i) EXPECT_TRUE(plan.legs[i].inspection) << i;
    EXPECT_LT((plan.waypoints_world_m.back() - Eigen::Vector3d(2.0, 0, 2.5)).norm(), 1e-9);
}

TEST(SurfaceTasks, ACorridorTaskJoinsTheCentreLineThenDrivesAlongIt) {
    // A floor; the corridor's centre line y = 0.1 + 0.05 x, the crawler at (0, -0.05).
    const PlaneSurface floor(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
    const Eigen::Vector3d d = Eigen::Vector3d(1.0, 0.05, 0.0).normalized();
    const TaskPlan plan =
        lay_corridor_task(task_of(SurfaceTaskType::kDriveBetweenStiffeners, 2.0), floor,
                          {0.0, -0.05, 0.0}, {0.0, 0.1, 0.0}, d, 0.2, {}, "tasks[0]");
    ASSERT_EQ(plan.legs.size(), 2u);
    EXPECT_FALSE(plan.legs[0].inspection);
    EXPECT_TRUE(plan.legs[1].inspection);
    double length_m = 0.0;
    for (const MeshPathSegment& s : plan.legs[1].segments) {
        // On the centre line.
        EXPECT_NEAR(s.end_world_m.y(), 0.1 + 0.05 * s.end_world_m.x(), 1e-9);
        length_m += (s.end_world_m - s.begin_world_m).norm();
    }
    EXPECT_NEAR(length_m, 2.0, 1e-9);
    // Joined 0.2 m past the crawler's foot on the line.
    const Eigen::Vector3d foot =
        Eigen::Vector3d(0, 0.1, 0) + d * d.dot(Eigen::Vector3d(0, -0.15, 0));
    EXPECT_LT((plan.legs[0].segments.back().end_world_m - (foot + 0.2 * d)).norm(), 1e-9);
}

TEST(SurfaceTasks, BadRequestsAreRefusedNamingTheTaskAndField) {
    const Eigen::Vector3d p(1.0, 0.0, 0.5);
    SCANTLING_EXPECT_ERROR(lay_surface_task(task_of(SurfaceTaskType::kVerticalTransect, -1.0),
                                            wall(), nullptr, p, {}, "mission.tasks[2]"),
                           InputError, "mission.tasks[2].length_m: -1, expected finite > 0");
    SCANTLING_EXPECT_ERROR(lay_surface_task(task_of(SurfaceTaskType::kDriveOnStiffener), wall(),
                                            nullptr, p, {}, "tasks[0]"),
                           InputError, "drive_on_stiffener is laid on the LiDAR's corridor");
    // No vertical on a floor.
    const PlaneSurface floor(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
    SCANTLING_EXPECT_ERROR(lay_surface_task(task_of(SurfaceTaskType::kHorizontalTransect), floor,
                                            nullptr, Eigen::Vector3d::Zero(), {}, "tasks[1]"),
                           InputError, "tasks[1].up is along the surface normal");
    SurfaceTask go;
    go.goal_world_m = {0.0, 0.0, 1.0};  // 1 m off the floor
    SCANTLING_EXPECT_ERROR(
        lay_surface_task(go, floor, nullptr, Eigen::Vector3d::Zero(), {}, "tasks[3]"), InputError,
        "tasks[3].goal_m = (0.000, 0.000, 1.000) is 1.000 m from the surface");
    // A transect off a bounded plate.
    const PlateSurface plate(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                             Eigen::Vector3d::UnitX(), 1.0, 0.5);
    SurfaceTask along = task_of(SurfaceTaskType::kVerticalTransect, 1.0);
    along.up_world = Eigen::Vector3d::UnitY();
    SCANTLING_EXPECT_ERROR(
        lay_surface_task(along, plate, nullptr, Eigen::Vector3d::Zero(), {}, "tasks[4]"),
        InputError, "tasks[4].length_m: the transect leaves the surface");
    SCANTLING_EXPECT_ERROR(
        lay_corridor_task(task_of(SurfaceTaskType::kDriveOnStiffener), floor,
                          Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(std::nan("")),
                          Eigen::Vector3d::UnitX(), 0.1, {}, "tasks[5]"),
        InputError, "tasks[5]: the corridor's centre line is not finite");
}

TEST(SurfaceTasks, TypeNamesRoundTrip) {
    for (const SurfaceTaskType type :
         {SurfaceTaskType::kGoTo, SurfaceTaskType::kRectangle, SurfaceTaskType::kVerticalTransect,
          SurfaceTaskType::kHorizontalTransect, SurfaceTaskType::kDriveBetweenStiffeners,
          SurfaceTaskType::kDriveOnStiffener, SurfaceTaskType::kDriveOnStiffenerSide}) {
        EXPECT_EQ(surface_task_type_from(to_string(type)), type);
    }
    EXPECT_FALSE(surface_task_type_from("drive_on_stiffner"));
    EXPECT_NE(surface_task_type_names().find("drive_on_stiffener_side"), std::string::npos);
}

}  // namespace
}  // namespace scantling::planning
