#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/surface_projector.hpp>

#include "analytic_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace scantling {
namespace {

using testing::grid_plate;
using testing::open_cylinder;

constexpr double kExactM = 1e-12;

TEST(PlaneSurface, ProjectsAlongTheNormal) {
    const PlaneSurface plane(Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0, 0, 3));
    const SurfacePoint s = plane.project(Eigen::Vector3d(1, -4, 5));
    EXPECT_LT((s.point - Eigen::Vector3d(1, -4, 2)).norm(), kExactM);
    EXPECT_EQ(s.normal, Eigen::Vector3d::UnitZ());
    EXPECT_THROW(PlaneSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), InputError);
}

TEST(PlateSurface, ProjectsOntoItsRectangleAndClampsAtTheEdges) {
    // The 5 × 2 m plate of the `plate` world, x_axis given a little off the plane.
    const PlateSurface plate(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 2),
                             Eigen::Vector3d(1, 0, 0.3), 2.5, 1.0);
    const SurfacePoint inside = plate.project(Eigen::Vector3d(1.0, -0.5, 0.4));
    EXPECT_LT((inside.point - Eigen::Vector3d(1.0, -0.5, 0.0)).norm(), 1e-12);
    EXPECT_LT((inside.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
    // Beyond a corner: the corner, same normal.
    const SurfacePoint corner = plate.project(Eigen::Vector3d(4.0, 3.0, -1.0));
    EXPECT_LT((corner.point - Eigen::Vector3d(2.5, 1.0, 0.0)).norm(), 1e-12);
    EXPECT_LT((corner.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
    EXPECT_THROW(PlateSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                              Eigen::Vector3d::UnitZ(), 1.0, 1.0),
                 InputError);
    EXPECT_THROW(PlateSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                              Eigen::Vector3d::UnitX(), 1.0, 0.0),
                 InputError);
}

TEST(CylinderSurface, NormalPointsAwayFromTheAxisOutsideAndTowardsItInside) {
    const CylinderSurface outside(Eigen::Vector3d(1, 1, 0), Eigen::Vector3d::UnitZ(), 2.0);
    const SurfacePoint s = outside.project(Eigen::Vector3d(4, 1, 7));
    EXPECT_LT((s.point - Eigen::Vector3d(3, 1, 7)).norm(), kExactM);
    EXPECT_LT((s.normal - Eigen::Vector3d::UnitX()).norm(), kExactM);
    const CylinderSurface inside(Eigen::Vector3d(1, 1, 0), Eigen::Vector3d::UnitZ(), 2.0,
                                 CylinderSide::kInside);
    EXPECT_LT((inside.project(Eigen::Vector3d(1, 0, 0)).normal - Eigen::Vector3d::UnitY()).norm(),
              kExactM);
    // A point on the axis still lands on the shell.
    EXPECT_NEAR((outside.project(Eigen::Vector3d(1, 1, 3)).point - Eigen::Vector3d(1, 1, 3)).norm(),
                2.0, kExactM);
    EXPECT_THROW(CylinderSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 0.0),
                 InputError);
}

TEST(MeshSurface, GridSearchFindsTheSameClosestPointAsBruteForce) {
    TriangleMesh mesh = open_cylinder(1.5, 3.0, 48, 12);
    append(mesh, grid_plate(4.0, 10));
    const MeshSurface surface(mesh, false);
    Rng rng(3);
    for (int i = 0; i < 300; ++i) {
        // Mostly near the surfaces, some far outside the grid.
        const double spread = i % 10 == 0 ? 30.0 : 4.0;
        const Eigen::Vector3d p(rng.uniform(-spread, spread), rng.uniform(-spread, spread),
                                rng.uniform(-1.0, 4.0));
        const MeshClosestPoint brute = closest_point_on_mesh(mesh, p);
        const SurfacePoint s = surface.project(p);
        EXPECT_NEAR((s.point - p).norm(), brute.distance_m, kExactM) << p.transpose();
    }
}

TEST(MeshSurface, SmoothNormalsBlendAcrossFacetsAndFaceNormalsDoNot) {
    const TriangleMesh mesh = open_cylinder(2.0, 2.0, 16, 2);
    const MeshSurface smooth(mesh, true), faceted(mesh, false);
    // Half-way between two vertex columns the smooth normal is radial; at a vertex column too.
    for (const double angle : {0.0, 3.14159265358979 / 16}) {
        const Eigen::Vector3d radial(std::cos(angle), std::sin(angle), 0.0);
        const SurfacePoint s = smooth.project(2.5 * radial + Eigen::Vector3d(0, 0, 1.0));
        EXPECT_LT((s.normal - radial).norm(), 1e-9) << angle;
    }
    const SurfacePoint f = faceted.project(Eigen::Vector3d(2.5, 0.1, 1.0));
    EXPECT_NEAR(f.normal.norm(), 1.0, 1e-12);
    EXPECT_NEAR(f.normal.z(), 0.0, 1e-12);
    EXPECT_GT(f.normal.x(), 0.9);
}

TEST(MeshSurface, RejectsEmptyMeshAndNonFinitePoints) {
    EXPECT_THROW(MeshSurface(TriangleMesh{}), InputError);
    const MeshSurface plate(grid_plate(1.0, 2));
    EXPECT_THROW(plate.project(Eigen::Vector3d(NAN, 0, 0)), InputError);
}

TEST(MeshSurface, ATriangleWithoutAreaNeverGivesAZeroNormal) {
    // A unit square of two triangles, and first a sliver lying on their shared diagonal, as
    // STL exports leave them. Right above the diagonal all three are equally near; the sliver
    // has the lowest index but no normal.
    TriangleMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
    mesh.triangles = {{0, 2, 4}, {0, 1, 2}, {0, 2, 3}};
    for (const bool smooth : {false, true}) {
        const MeshSurface surface(mesh, smooth);
        const SurfacePoint s = surface.project(Eigen::Vector3d(0.5, 0.5, 1.0));
        EXPECT_LT((s.point - Eigen::Vector3d(0.5, 0.5, 0.0)).norm(), 1e-12);
        EXPECT_LT((s.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-9) << smooth;
    }
    // Only slivers: no surface at all.
    TriangleMesh slivers;
    slivers.vertices = {{0, 0, 0}, {1, 1, 0}, {0.5, 0.5, 0}};
    slivers.triangles = {{0, 1, 2}};
    EXPECT_THROW(MeshSurface{slivers}, InputError);
}

}  // namespace
}  // namespace scantling
