#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/triangle_mesh.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace scantling {
namespace {

// Geometry built from exact small numbers: results are exact up to a few ulps.
constexpr double kExactTol = 1e-12;

// Axis-aligned unit cube [0,1]³, 8 shared vertices, 12 counter-clockwise-outside triangles.
TriangleMesh unit_cube() {
    TriangleMesh mesh;
    for (int i = 0; i < 8; ++i) mesh.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    const std::array<Eigen::Vector4i, 6> quads{{
        {0, 2, 3, 1},  // z = 0, normal -z
        {4, 5, 7, 6},  // z = 1, normal +z
        {0, 1, 5, 4},  // y = 0, normal -y
        {2, 6, 7, 3},  // y = 1, normal +y
        {0, 4, 6, 2},  // x = 0, normal -x
        {1, 3, 7, 5},  // x = 1, normal +x
    }};
    for (const auto& q : quads) {
        mesh.triangles.emplace_back(q[0], q[1], q[2]);
        mesh.triangles.emplace_back(q[0], q[2], q[3]);
    }
    return mesh;
}

// STL-style soup: each triangle stores its own three corners.
TriangleMesh soup_of(const TriangleMesh& mesh) {
    TriangleMesh soup;
    for (const auto& tri : mesh.triangles) {
        const int base = static_cast<int>(soup.vertices.size());
        for (int c = 0; c < 3; ++c) soup.vertices.push_back(mesh.vertices[tri[c]]);
        soup.triangles.emplace_back(base, base + 1, base + 2);
    }
    return soup;
}

double distance_to_unit_cube_surface(const Eigen::Vector3d& p) {
    const Eigen::Vector3d to_faces = p.cwiseMin(Eigen::Vector3d::Ones() - p);
    return to_faces.minCoeff();  // valid for points inside or on the cube
}

TEST(TriangleMesh, UnitCubeHasAreaSixAndUnitBounds) {
    const TriangleMesh cube = unit_cube();
    check_valid(cube, "cube");
    EXPECT_NEAR(surface_area(cube), 6.0, kExactTol);
    EXPECT_NEAR(triangle_area(cube, 0), 0.5, kExactTol);
    const Aabb box = compute_bounds(cube);
    EXPECT_EQ(box.min, Eigen::Vector3d::Zero());
    EXPECT_EQ(box.max, Eigen::Vector3d::Ones());
}

TEST(TriangleMesh, UnitCubeNormalsPointOutwards) {
    const TriangleMesh cube = unit_cube();
    const Eigen::Vector3d center(0.5, 0.5, 0.5);
    for (std::size_t i = 0; i < cube.num_triangles(); ++i) {
        const Eigen::Vector3d n = triangle_normal(cube, i);
        EXPECT_NEAR(n.norm(), 1.0, kExactTol);
        const Eigen::Vector3d on_face = cube.vertices[cube.triangles[i][0]];
        // Outward: the normal points from the centre towards the face, along one axis.
        EXPECT_NEAR(n.dot(on_face - center), 0.5, kExactTol) << "triangle " << i;
    }
}

TEST(TriangleMesh, DegenerateTriangleHasZeroNormalAndArea) {
    TriangleMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    mesh.triangles = {{0, 1, 2}};
    EXPECT_EQ(triangle_normal(mesh, 0), Eigen::Vector3d::Zero());
    EXPECT_EQ(triangle_area(mesh, 0), 0.0);
}

TEST(TriangleMesh, VertexNormalsOfCubeCornersPointDiagonallyOut) {
    TriangleMesh cube = unit_cube();
    compute_vertex_normals(cube);
    ASSERT_EQ(cube.vertex_normals.size(), 8U);
    for (std::size_t i = 0; i < 8; ++i) {
        const Eigen::Vector3d outward = (cube.vertices[i] - Eigen::Vector3d::Constant(0.5));
        EXPECT_NEAR(cube.vertex_normals[i].norm(), 1.0, kExactTol);
        // Each corner touches 3 faces; area weights differ (1 or 2 triangles per face), so
        // only the octant is fixed: every component has the outward sign.
        for (int k = 0; k < 3; ++k) EXPECT_GT(cube.vertex_normals[i][k] * outward[k], 0.0);
    }
}

TEST(TriangleMesh, WeldingAnStlSoupRecoversTheCube) {
    TriangleMesh soup = soup_of(unit_cube());
    ASSERT_EQ(soup.num_vertices(), 36U);
    // Sub-tolerance jitter as left by float STL export.
    for (std::size_t i = 0; i < soup.vertices.size(); ++i) soup.vertices[i].x() += (i % 3) * 1e-7;
    weld_vertices(soup, 1e-5);
    EXPECT_EQ(soup.num_vertices(), 8U);
    EXPECT_EQ(soup.num_triangles(), 12U);
    check_valid(soup, "welded");
    EXPECT_NEAR(surface_area(soup), 6.0, 1e-6);
    // First-occurrence order: the soup starts with triangle (0, 2, 3) of the cube.
    EXPECT_LT((soup.vertices[0] - Eigen::Vector3d(0, 0, 0)).norm(), 1e-6);
    EXPECT_LT((soup.vertices[1] - Eigen::Vector3d(0, 1, 0)).norm(), 1e-6);
}

TEST(TriangleMesh, WeldingIsDeterministicAndDropsCollapsedTriangles) {
    TriangleMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1e-4, 0, 0}};
    mesh.triangles = {{0, 1, 2}, {0, 3, 2}};
    TriangleMesh copy = mesh;
    weld_vertices(mesh, 1e-3);
    weld_vertices(copy, 1e-3);
    EXPECT_EQ(mesh.vertices, copy.vertices);
    EXPECT_EQ(mesh.num_vertices(), 3U);
    ASSERT_EQ(mesh.num_triangles(), 1U);
    EXPECT_EQ(mesh.triangles[0], Eigen::Vector3i(0, 1, 2));
}

TEST(TriangleMesh, WeldWithZeroToleranceMergesExactDuplicatesOnly) {
    TriangleMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {1e-12, 0, 0}};
    mesh.triangles = {{0, 1, 2}};
    weld_vertices(mesh, 0.0);
    EXPECT_EQ(mesh.num_vertices(), 4U);
    EXPECT_THROW(weld_vertices(mesh, -1.0), InputError);
}

TEST(TriangleMesh, InvalidIndexOrVertexThrows) {
    TriangleMesh mesh = unit_cube();
    mesh.triangles[3] = {0, 1, 8};
    EXPECT_THROW(check_valid(mesh, "cube"), InputError);
    try {
        check_valid(mesh, "cube");
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("triangle 3"), std::string::npos) << e.what();
    }
    mesh.triangles[3] = {0, -1, 2};
    EXPECT_THROW(check_valid(mesh, "cube"), InputError);
    TriangleMesh nan_mesh = unit_cube();
    nan_mesh.vertices[2].y() = std::nan("");
    EXPECT_THROW(check_valid(nan_mesh, "cube"), InputError);
    TriangleMesh normals_mesh = unit_cube();
    normals_mesh.vertex_normals.resize(3);
    EXPECT_THROW(check_valid(normals_mesh, "cube"), InputError);
}

TEST(TriangleMesh, TransformMovesVerticesAndRotatesNormals) {
    TriangleMesh cube = unit_cube();
    compute_vertex_normals(cube);
    Eigen::Isometry3d T_world_cube = Eigen::Isometry3d::Identity();
    T_world_cube.linear() =
        Eigen::AngleAxisd(std::numbers::pi / 2.0, Eigen::Vector3d::UnitZ()).matrix();
    T_world_cube.translation() = Eigen::Vector3d(10.0, 0.0, 0.0);
    const Eigen::Vector3d n7 = cube.vertex_normals[7];
    transform_in_place(cube, T_world_cube);
    EXPECT_LT((cube.vertices[1] - Eigen::Vector3d(10.0, 1.0, 0.0)).norm(), kExactTol);
    EXPECT_LT((cube.vertex_normals[7] - T_world_cube.linear() * n7).norm(), kExactTol);
    EXPECT_NEAR(surface_area(cube), 6.0, kExactTol);
}

TEST(TriangleMesh, AppendReindexesTriangles) {
    TriangleMesh a = unit_cube();
    TriangleMesh b = unit_cube();
    Eigen::Isometry3d T_shift = Eigen::Isometry3d::Identity();
    T_shift.translation() = Eigen::Vector3d(5.0, 0.0, 0.0);
    transform_in_place(b, T_shift);
    append(a, b);
    EXPECT_EQ(a.num_vertices(), 16U);
    EXPECT_EQ(a.num_triangles(), 24U);
    check_valid(a, "appended");
    EXPECT_EQ(a.triangles[12], Eigen::Vector3i(unit_cube().triangles[0].array() + 8));
    EXPECT_NEAR(surface_area(a), 12.0, kExactTol);
    TriangleMesh with_normals = unit_cube();
    compute_vertex_normals(with_normals);
    EXPECT_THROW(append(a, with_normals), InputError);
}

TEST(TriangleMesh, ClosestPointOnTriangleCoversEveryRegion) {
    const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
    const auto closest = [&](double x, double y, double z) {
        return closest_point_on_triangle({x, y, z}, a, b, c);
    };
    EXPECT_LT((closest(0.5, 0.5, 3.0) - Eigen::Vector3d(0.5, 0.5, 0)).norm(), kExactTol);
    EXPECT_LT((closest(-1, -1, 1) - a).norm(), kExactTol);
    EXPECT_LT((closest(3, -1, 0) - b).norm(), kExactTol);
    EXPECT_LT((closest(-1, 3, 0) - c).norm(), kExactTol);
    EXPECT_LT((closest(1, -1, 0) - Eigen::Vector3d(1, 0, 0)).norm(), kExactTol);
    EXPECT_LT((closest(-1, 1, 0) - Eigen::Vector3d(0, 1, 0)).norm(), kExactTol);
    EXPECT_LT((closest(2, 2, 0) - Eigen::Vector3d(1, 1, 0)).norm(), kExactTol);
    // Degenerate (collinear) triangle falls back to its segments.
    const Eigen::Vector3d on_line = closest_point_on_triangle({1, 1, 0}, a, b, {1, 0, 0});
    EXPECT_LT((on_line - Eigen::Vector3d(1, 0, 0)).norm(), kExactTol);
}

TEST(TriangleMesh, ClosestPointOnMeshFindsTheNearestFace) {
    const TriangleMesh cube = unit_cube();
    const MeshClosestPoint hit = closest_point_on_mesh(cube, {0.5, 0.4, 3.0});
    EXPECT_NEAR(hit.distance_m, 2.0, kExactTol);
    EXPECT_LT((hit.point - Eigen::Vector3d(0.5, 0.4, 1.0)).norm(), kExactTol);
    EXPECT_NEAR(triangle_normal(cube, hit.triangle).z(), 1.0, kExactTol);
    EXPECT_THROW(closest_point_on_mesh(TriangleMesh{}, Eigen::Vector3d::Zero()), InputError);
}

TEST(TriangleMesh, SampledPointsLieOnTheSurfaceWithFaceNormals) {
    const TriangleMesh cube = unit_cube();
    Rng rng(17);
    const PointCloud cloud = sample_surface_count(cube, 5000, rng);
    ASSERT_EQ(cloud.size(), 5000U);
    ASSERT_TRUE(cloud.has_normals());
    constexpr double kOnSurfaceTol = 1e-9;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        ASSERT_LT(distance_to_unit_cube_surface(cloud.points[i]), kOnSurfaceTol) << i;
        ASSERT_LT(closest_point_on_mesh(cube, cloud.points[i]).distance_m, kOnSurfaceTol);
        // The normal is the axis of the face the point lies on, pointing outwards.
        const Eigen::Vector3d& n = cloud.normals[i];
        const Eigen::Vector3d p = cloud.points[i] - Eigen::Vector3d::Constant(0.5);
        EXPECT_NEAR(n.dot(p), 0.5, kOnSurfaceTol);
    }
}

TEST(TriangleMesh, SamplingIsAreaWeightedAcrossFaces) {
    TriangleMesh mesh = unit_cube();
    // Stretch x by 3: the two x-faces keep area 1, the other four become area 3.
    for (auto& v : mesh.vertices) v.x() *= 3.0;
    Rng rng(4);
    constexpr int kSamples = 60000;
    const PointCloud cloud = sample_surface_count(mesh, kSamples, rng);
    int on_x_faces = 0;
    for (const auto& n : cloud.normals) on_x_faces += std::abs(n.x()) > 0.5;
    // Expected fraction 2/14; binomial standard deviation √(n p (1-p)) ≈ 86, allow 5σ.
    EXPECT_NEAR(on_x_faces, kSamples * 2.0 / 14.0, 430.0);
}

TEST(TriangleMesh, SamplingAtSpacingGivesAreaOverSpacingSquaredPoints) {
    const TriangleMesh cube = unit_cube();
    Rng rng(1);
    const PointCloud cloud = sample_surface_spacing(cube, 0.05, rng);
    // round(6 / 0.0025) = 2400; rounding allows at most one point of slack.
    EXPECT_NEAR(static_cast<double>(cloud.size()), 6.0 / (0.05 * 0.05), 1.0);
}

TEST(TriangleMesh, SamplingIsDeterministicForASeed) {
    const TriangleMesh cube = unit_cube();
    Rng a(99);
    Rng b(99);
    EXPECT_EQ(sample_surface_count(cube, 100, a).points, sample_surface_count(cube, 100, b).points);
}

TEST(TriangleMesh, SamplingRejectsBadInput) {
    Rng rng(1);
    const TriangleMesh cube = unit_cube();
    EXPECT_THROW(sample_surface_spacing(cube, 0.0, rng), InputError);
    EXPECT_THROW(sample_surface_spacing(cube, -1.0, rng), InputError);
    EXPECT_THROW(sample_surface_spacing(cube, 1e-9, rng), InputError);
    EXPECT_THROW(sample_surface_count(TriangleMesh{}, 10, rng), InputError);
    EXPECT_EQ(sample_surface_count(TriangleMesh{}, 0, rng).size(), 0U);
    TriangleMesh flat;
    flat.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    flat.triangles = {{0, 1, 2}};
    EXPECT_THROW(sample_surface_count(flat, 10, rng), InputError);
}

}  // namespace
}  // namespace scantling
