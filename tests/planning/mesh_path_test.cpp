// Shortest surface paths on triangle meshes (planning/mesh_path.hpp, SPEC §6): exact geodesics
// on a plate, a faceted cylinder and a fold, cut into one segment per facet.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <utility>

#include <scantling/core/error.hpp>
#include <scantling/core/triangle_mesh.hpp>
#include <scantling/planning/mesh_path.hpp>

#include "expect_error.hpp"

namespace scantling::planning {
namespace {

constexpr double kRoundingM = 1e-9;  // the brief's bound: exact geodesics, only rounding differs
constexpr double kDeg = std::numbers::pi / 180.0;
// |faceted geodesic − helix| / helix: 64 facets around, 8 rings; 0.022 % measured, ~2× that.
constexpr double kCylinderRelative = 5e-4;

// A rectangle origin + a u + b w, a ∈ [0, size_u], b ∈ [0, size_w], in square cells of `cell_m`,
// two triangles per cell, wound counter-clockwise about u × w.
TriangleMesh grid(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& w,
                  int cells_u, int cells_w, double cell_m) {
    TriangleMesh mesh;
    for (int j = 0; j <= cells_w; ++j) {
        for (int i = 0; i <= cells_u; ++i)
            mesh.vertices.push_back(origin + cell_m * (i * u + j * w));
    }
    const auto at = [&](int i, int j) { return j * (cells_u + 1) + i; };
    for (int j = 0; j < cells_w; ++j) {
        for (int i = 0; i < cells_u; ++i) {
            mesh.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            mesh.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
    return mesh;
}

// 4 × 2 m in the z = 0 plane, 0.25 m cells (256 triangles).
TriangleMesh plate() {
    return grid(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 16, 8,
                0.25);
}

// The side of a cylinder about z: radius_m, z ∈ [0, height_m], `around` facets per ring.
TriangleMesh cylinder(double radius_m, double height_m, int around, int rings) {
    TriangleMesh mesh;
    for (int j = 0; j <= rings; ++j) {
        for (int i = 0; i < around; ++i) {
            const double theta = 2.0 * std::numbers::pi * i / around;
            mesh.vertices.emplace_back(radius_m * std::cos(theta), radius_m * std::sin(theta),
                                       height_m * j / rings);
        }
    }
    const auto at = [&](int i, int j) { return j * around + (i % around); };
    for (int j = 0; j < rings; ++j) {
        for (int i = 0; i < around; ++i) {  // outward: tangent × up
            mesh.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            mesh.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
    return mesh;
}

double distance_to_facet_m(const TriangleMesh& mesh, std::size_t face, const Eigen::Vector3d& p) {
    const Eigen::Vector3i& t = mesh.triangles[face];
    return (closest_point_on_triangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]],
                                      mesh.vertices[t[2]]) -
            p)
        .norm();
}

// Every segment in its facet (both ends), with the facet's normal, joined end to begin, and the
// length the sum of the pieces.
void expect_well_formed(const TriangleMesh& mesh, const MeshPath& path) {
    ASSERT_FALSE(path.segments.empty());
    double sum_m = 0.0;
    for (std::size_t i = 0; i < path.segments.size(); ++i) {
        const MeshPathSegment& s = path.segments[i];
        ASSERT_LT(s.face, mesh.num_triangles());
        EXPECT_LE(distance_to_facet_m(mesh, s.face, s.begin_world_m), kRoundingM)
            << "segment " << i;
        EXPECT_LE(distance_to_facet_m(mesh, s.face, s.end_world_m), kRoundingM) << "segment " << i;
        EXPECT_TRUE(s.normal_world.isApprox(triangle_normal(mesh, s.face), 1e-12));
        EXPECT_GE((s.end_world_m - s.begin_world_m).norm(), kRoundingM);
        if (i > 0) {
            EXPECT_LE((path.segments[i - 1].end_world_m - s.begin_world_m).norm(), kRoundingM);
        }
        sum_m += (s.end_world_m - s.begin_world_m).norm();
    }
    EXPECT_NEAR(sum_m, path.length_m, kRoundingM);
}

TEST(MeshPath, IsTheStraightLineOnAFlatPlateCutAtEveryFacet) {
    const TriangleMesh mesh = plate();
    const Eigen::Vector3d start(0.3, 0.2, 0.0), goal(3.7, 1.65, 0.0);
    const MeshPath path = shortest_path_on_mesh(mesh, start, goal);
    expect_well_formed(mesh, path);
    EXPECT_NEAR(path.length_m, (goal - start).norm(), kRoundingM);
    EXPECT_LE((path.segments.front().begin_world_m - start).norm(), kRoundingM);
    EXPECT_LE((path.segments.back().end_world_m - goal).norm(), kRoundingM);
    const Eigen::Vector3d direction = (goal - start).normalized();
    for (const MeshPathSegment& s : path.segments) {
        EXPECT_NEAR(s.begin_world_m.z(), 0.0, kRoundingM);
        EXPECT_NEAR(s.end_world_m.z(), 0.0, kRoundingM);
        EXPECT_NEAR((s.end_world_m - start).cross(direction).norm(), 0.0, kRoundingM);  // on line
        EXPECT_TRUE(s.normal_world.isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
    }
    // Cut at every edge: the line crosses 13 grid lines x = 0.5 … 3.5 and 6 lines y = 0.25 … 1.5.
    EXPECT_GE(path.segments.size(), 20u);
    for (std::size_t i = 1; i < path.segments.size(); ++i) {
        EXPECT_NE(path.segments[i - 1].face, path.segments[i].face);
    }
    std::printf("[ measured ] plate: %zu segments, length %.12f m (straight %.12f m)\n",
                path.segments.size(), path.length_m, (goal - start).norm());
}

TEST(MeshPath, GivesAPieceAlongAnEdgeTheFacetWithTheSmallerIndexInBothDirections) {
    // Along the grid line y = 1 m (through vertices): its facets below (cell row 3, triangle
    // indices 96 … 127) have smaller indices than those above (row 4).
    const TriangleMesh mesh = plate();
    const Eigen::Vector3d a(0.3, 1.0, 0.0), b(3.7, 1.0, 0.0);
    for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, a}}) {
        const MeshPath path = shortest_path_on_mesh(mesh, from, to);
        expect_well_formed(mesh, path);
        EXPECT_NEAR(path.length_m, 3.4, kRoundingM);
        for (const MeshPathSegment& s : path.segments) EXPECT_EQ(s.face / 32, 3u) << s.face;
    }
}

TEST(MeshPath, FollowsAHelixOnAFacetedCylinder) {
    const double radius_m = 1.0;
    const TriangleMesh mesh = cylinder(radius_m, 2.0, 64, 8);
    const double theta0 = 0.05, theta1 = 1.6, z0 = 0.3, z1 = 1.7;
    const Eigen::Vector3d start(std::cos(theta0), std::sin(theta0), z0);
    const Eigen::Vector3d goal(std::cos(theta1), std::sin(theta1), z1);
    const MeshPath path = shortest_path_on_mesh(mesh, start, goal);
    expect_well_formed(mesh, path);
    const double helix_m = std::hypot(radius_m * (theta1 - theta0), z1 - z0);
    const double chord_m = (goal - start).norm();
    const double relative = std::abs(path.length_m - helix_m) / helix_m;
    std::printf(
        "[ measured ] cylinder: %zu segments, length %.6f m, helix %.6f m (%.4f %%), "
        "chord %.6f m\n",
        path.segments.size(), path.length_m, helix_m, 100.0 * relative, chord_m);
    EXPECT_GT(path.length_m, chord_m);
    EXPECT_LT(relative, kCylinderRelative);
}

/// The same path, facet for facet, from the region around the start and goal and from the whole
/// mesh.
void expect_same(const MeshPath& a, const MeshPath& b) {
    ASSERT_EQ(a.segments.size(), b.segments.size());
    EXPECT_NEAR(a.length_m, b.length_m, kRoundingM);
    for (std::size_t i = 0; i < a.segments.size(); ++i) {
        EXPECT_EQ(a.segments[i].face, b.segments[i].face) << i;
        EXPECT_LT((a.segments[i].end_world_m - b.segments[i].end_world_m).norm(), kRoundingM) << i;
    }
}

TEST(MeshPath, TheRegionAroundStartAndGoalGivesTheWholeMeshsPath) {
    // A long cylinder (1 m radius, 8 m, 16 rings): a short helix touches a few rings only.
    const TriangleMesh mesh = cylinder(1.0, 8.0, 64, 32);
    const Eigen::Vector3d start(std::cos(0.05), std::sin(0.05), 3.3),
        goal(std::cos(0.9), std::sin(0.9), 3.9);
    MeshPathConfig whole;
    whole.region_length_ratio = 0.0;
    expect_same(shortest_path_on_mesh(mesh, start, goal),
                shortest_path_on_mesh(mesh, start, goal, whole));
}

TEST(MeshPath, ARegionWithoutAShortEnoughPathFallsBackToTheWholeMesh) {
    // The plate slit from its bottom edge to 0.25 m below its top (the two cells' columns at
    // x = 1.75-2.25 m removed): from one side of the slit to the other the path goes round its
    // end, 3.4 m against 1.0 m straight, longer than the region's twice the distance.
    TriangleMesh slit = plate();
    std::vector<Eigen::Vector3i> kept;
    for (std::size_t t = 0; t < slit.triangles.size(); ++t) {
        const std::size_t cell = t / 2;  // 16 cells per row, 7 of 8 rows slit
        const std::size_t i = cell % 16, j = cell / 16;
        if ((i == 7 || i == 8) && j < 7) continue;
        kept.push_back(slit.triangles[t]);
    }
    slit.triangles = kept;
    const Eigen::Vector3d start(1.5, 0.5, 0.0), goal(2.5, 0.5, 0.0);
    const MeshPath path = shortest_path_on_mesh(slit, start, goal);
    MeshPathConfig whole;
    whole.region_length_ratio = 0.0;
    expect_same(path, shortest_path_on_mesh(slit, start, goal, whole));
    // Round the slit's end at (1.75, 1.75) and (2.25, 1.75).
    EXPECT_NEAR(path.length_m, 2.0 * std::hypot(0.25, 1.25) + 0.5, 1e-8);  // the 1e-9 nudges
}

TEST(MeshPath, CrossesAFoldAsTheStraightLineOfTheUnfoldedSurface) {
    // A 1 × 1 m floor (x ∈ [0, 1]) and a 1 m slope rising at 30° from its edge x = 1.
    const double slope = 30.0 * kDeg;
    const Eigen::Vector3d up(std::cos(slope), 0.0, std::sin(slope));
    const Eigen::Vector3d slope_normal(-std::sin(slope), 0.0, std::cos(slope));
    const Eigen::Vector3d fold(1.0, 0.0, 0.0);
    TriangleMesh mesh = grid(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                             Eigen::Vector3d::UnitY(), 4, 4, 0.25);
    const std::size_t floor_faces = mesh.num_triangles();
    append(mesh, grid(fold, up, Eigen::Vector3d::UnitY(), 4, 4, 0.25));
    weld_vertices(mesh, 1e-12);  // one fold edge shared by both sides
    ASSERT_EQ(mesh.num_triangles(), 2 * floor_faces);

    const Eigen::Vector3d start(0.2, 0.1, 0.0), goal = fold + 0.7 * up + Eigen::Vector3d(0, 0.9, 0);
    const MeshPath path = shortest_path_on_mesh(mesh, start, goal);
    expect_well_formed(mesh, path);
    const double unfolded_m = std::hypot(1.0 - 0.2 + 0.7, 0.9 - 0.1);
    EXPECT_NEAR(path.length_m, unfolded_m, kRoundingM);
    std::size_t on_floor = 0, on_slope = 0;
    for (const MeshPathSegment& s : path.segments) {
        const bool floor = s.face < floor_faces;
        (floor ? on_floor : on_slope)++;
        for (const Eigen::Vector3d& p : {s.begin_world_m, s.end_world_m}) {
            const double off_plane_m = floor ? p.z() : (p - fold).dot(slope_normal);
            EXPECT_NEAR(off_plane_m, 0.0, kRoundingM);
        }
    }
    EXPECT_GT(on_floor, 0u);
    EXPECT_GT(on_slope, 0u);
    for (std::size_t i = 1; i < path.segments.size(); ++i) {  // one crossing, floor then slope
        EXPECT_FALSE(path.segments[i - 1].face >= floor_faces &&
                     path.segments[i].face < floor_faces);
    }
    std::printf("[ measured ] fold: %zu + %zu segments, length %.12f m (unfolded %.12f m)\n",
                on_floor, on_slope, path.length_m, unfolded_m);
}

TEST(MeshPath, RefusesPointsOffTheMeshUnreachableGoalsAndBadMeshes) {
    const TriangleMesh mesh = plate();
    const Eigen::Vector3d on(1.0, 1.0, 0.0), off(1.0, 1.0, 0.5);
    SCANTLING_EXPECT_ERROR(shortest_path_on_mesh(mesh, off, on), InputError,
                           "mesh_path.start_world_m");
    SCANTLING_EXPECT_ERROR(shortest_path_on_mesh(mesh, on, off), InputError,
                           "mesh_path.goal_world_m");
    const Eigen::Vector3d nan(std::nan(""), 0.0, 0.0);
    SCANTLING_EXPECT_ERROR(shortest_path_on_mesh(mesh, nan, on), InputError,
                           "mesh_path.start_world_m");
    SCANTLING_EXPECT_ERROR(shortest_path_on_mesh(mesh, on, nan), InputError,
                           "mesh_path.goal_world_m");
    SCANTLING_EXPECT_ERROR(shortest_path_on_mesh(TriangleMesh{}, on, on), InputError,
                           "mesh_path.mesh");
    MeshPathConfig config;
    config.max_snap_distance_m = 0.0;
    SCANTLING_EXPECT_ERROR(shortest_path_on_mesh(mesh, on, on, config), ConfigError,
                           "mesh_path.max_snap_distance_m");
    config.max_snap_distance_m = 0.6;  // now 0.5 m off is accepted (snapped onto the plate)
    config.region_length_ratio = 0.5;
    SCANTLING_EXPECT_ERROR(shortest_path_on_mesh(mesh, on, on, config), ConfigError,
                           "mesh_path.region_length_ratio = 0.5");
    config.region_length_ratio = 2.0;
    EXPECT_NEAR(shortest_path_on_mesh(mesh, off, on + Eigen::Vector3d(1, 0, 0), config).length_m,
                1.0, kRoundingM);

    TriangleMesh two_plates = plate();
    append(two_plates,
           grid({0.0, 3.0, 0.0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 4, 4, 0.25));
    SCANTLING_EXPECT_ERROR(shortest_path_on_mesh(two_plates, on, {0.5, 3.5, 0.0}), InputError,
                           "no surface path");

    TriangleMesh degenerate = plate();
    degenerate.triangles[5] = {0, 1, 1};
    SCANTLING_EXPECT_ERROR(shortest_path_on_mesh(degenerate, on, on), InputError,
                           "mesh_path.mesh triangle 5 is degenerate");
    TriangleMesh fin = plate();  // a third facet on the edge (0, 1): a non-manifold edge
    fin.vertices.emplace_back(0.1, 0.0, 0.3);
    fin.triangles.emplace_back(0, 1, static_cast<int>(fin.vertices.size() - 1));
    SCANTLING_EXPECT_ERROR(shortest_path_on_mesh(fin, on, on), InputError,
                           "mesh_path.mesh triangle 256 cannot be added");
}

}  // namespace
}  // namespace scantling::planning
