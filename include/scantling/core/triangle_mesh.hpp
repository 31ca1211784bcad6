#pragma once
/// @file Indexed triangle mesh (worlds, CAD maps, crawler path planning).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <string_view>
#include <vector>

#include <scantling/core/bounds.hpp>
#include <scantling/core/point_cloud.hpp>

namespace scantling {

class Rng;

struct TriangleMesh {
    std::vector<Eigen::Vector3d> vertices;        ///< metres
    std::vector<Eigen::Vector3i> triangles;       ///< vertex indices, counter-clockwise = outside
    std::vector<Eigen::Vector3d> vertex_normals;  ///< optional, unit length

    std::size_t num_vertices() const { return vertices.size(); }
    std::size_t num_triangles() const { return triangles.size(); }
    bool empty() const { return triangles.empty(); }
};

/// Throws InputError naming `what` when an index is out of range, a vertex is not finite or
/// `vertex_normals` is neither empty nor one per vertex.
void check_valid(const TriangleMesh& mesh, std::string_view what);

Aabb compute_bounds(const TriangleMesh& mesh);

/// Unit normal of triangle `i` (zero vector for a degenerate triangle).
Eigen::Vector3d triangle_normal(const TriangleMesh& mesh, std::size_t i);

/// Area of triangle `i`, m².
double triangle_area(const TriangleMesh& mesh, std::size_t i);

/// Total surface area, m².
double surface_area(const TriangleMesh& mesh);

/// Area-weighted vertex normals (overwrites `vertex_normals`).
void compute_vertex_normals(TriangleMesh& mesh);

/// Applies T_to_from to vertices (and rotates normals).
void transform_in_place(TriangleMesh& mesh, const Eigen::Isometry3d& T_to_from);

/// Appends `other` (re-indexing its triangles).
void append(TriangleMesh& dst, const TriangleMesh& other);

/// Merges vertices closer than `tolerance_m` (STL stores each facet's corners separately)
/// and drops triangles that become degenerate. Deterministic.
///
/// Vertices are visited in index order through a hash grid of cell max(tolerance_m, tiny); each
/// joins the first kept vertex within `tolerance_m` (distance <= tolerance_m, so 0 merges exact
/// duplicates only) or is kept. Kept vertices stay in their original order. Triangles with a
/// repeated index after welding are dropped. Present vertex normals are recomputed.
/// Throws InputError on an invalid mesh or a negative / non-finite tolerance. O(V + T) expected.
void weld_vertices(TriangleMesh& mesh, double tolerance_m);

/// The point of triangle (a, b, c) closest to `p` (Ericson, Real-Time Collision Detection
/// §5.1.5). Works for degenerate triangles (returns a point of the segment / vertex).
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Result of `closest_point_on_mesh`.
struct MeshClosestPoint {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< closest surface point, mesh frame
    std::size_t triangle = 0;                         ///< index of the triangle it lies on
    double distance_m = 0.0;                          ///< |p - point|
};

/// Closest surface point to `p` by brute force over all triangles: O(T). For tests and small
/// meshes; build a spatial index for many queries. Throws InputError on an empty mesh.
MeshClosestPoint closest_point_on_mesh(const TriangleMesh& mesh, const Eigen::Vector3d& p);

/// `count` points drawn uniformly over the surface (triangle chosen with probability
/// proportional to its area, then a uniform barycentric point), each with its triangle's unit
/// normal, in the mesh frame. Deterministic for a given `rng` state; draws 3 uniforms per point.
/// Throws InputError on an invalid mesh, or when count > 0 and the surface area is zero.
/// O(T + count log T).
PointCloud sample_surface_count(const TriangleMesh& mesh, std::size_t count, Rng& rng);

/// Uniform surface sampling with density 1 / spacing_m²: round(surface_area / spacing_m²)
/// points, as `sample_surface_count` (e.g. the simulator's "CAD map" export). Points are i.i.d.,
/// so `spacing_m` is the mean spacing, not a minimum distance. Throws InputError unless
/// spacing_m is finite and > 0, or when the count would exceed 1e9 points.
PointCloud sample_surface_spacing(const TriangleMesh& mesh, double spacing_m, Rng& rng);

}  // namespace scantling
