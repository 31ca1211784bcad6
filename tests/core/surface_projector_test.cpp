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

}  // namespace
}  // namespace scantling
