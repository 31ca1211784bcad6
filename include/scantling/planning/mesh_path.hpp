#pragma once
/// @file
/// Shortest paths on a triangle surface mesh between two surface points (SPEC §6, "Path
/// following on a triangle mesh"; D5.2 §III.3): the exact geodesic (CGAL's
/// Surface_mesh_shortest_path, Xin & Wang's improved Chen–Han algorithm), cut into per-facet
/// segments for the crawler's segment follower (control/segment_follower.hpp).
///
/// Frames: the mesh, the start, the goal and every segment in the world frame, metres.
///
/// Facets. Each segment lies in one facet of the input mesh, in order from start to goal, the end
/// of one the begin of the next; pieces shorter than 1e-6 m are dropped (the next segment then
/// begins where the previous one ended), the shortest control::SegmentFollower accepts. A piece
/// that runs exactly along an edge (or between two vertices of one edge) lies in both facets of
/// that edge; it is given the one with the smaller index (deterministic, and the same for both
/// directions). A start and goal that snap to the same point give an empty path. CGAL 5.5 may
/// report an edge crossing with its parameter off the edge where the path runs along an edge; it is
/// clamped onto the edge.
///
/// Thread-safety: pure function. Cost: O(T) to select the region's facets, then O(R log R) to
/// build the geodesic structure and the AABB tree for the R facets of the region (worst case
/// O(R²) for the exact algorithm; the whole mesh's T when the region holds no path short enough),
/// then O(k) for a path crossing k edges. Deterministic.

#include <Eigen/Core>
#include <cstddef>
#include <string_view>
#include <vector>

#include <scantling/core/triangle_mesh.hpp>

namespace scantling::planning {

/// One piece of a surface path: it lies in one facet of the mesh. World frame, metres.
struct MeshPathSegment {
    Eigen::Vector3d begin_world_m = Eigen::Vector3d::Zero();  ///< B_i
    Eigen::Vector3d end_world_m = Eigen::Vector3d::Zero();    ///< E_i
    /// The facet's unit normal (outward as the mesh's counter-clockwise winding gives it).
    Eigen::Vector3d normal_world = Eigen::Vector3d::UnitZ();
    std::size_t face = 0;  ///< index of the facet in the input mesh's `triangles`
};

struct MeshPathConfig {
    /// > 0, a start or goal farther than this from the mesh surface is refused, m (the point is
    /// snapped to the closest surface point otherwise).
    double max_snap_distance_m = 0.05;
    /// >= 1, or 0 (off): the exact algorithm runs first on the facets within the ellipsoid
    /// |x − start| + |x − goal| <= ratio · |goal − start| (plus a facet's longest edge), the
    /// whole mesh only when that finds no path or a longer one. Exact either way: a shortest
    /// path of length L lies inside the ellipsoid of L. Why: CGAL propagates over every facet;
    /// on the Möbius strip's mesh a 1.3 m go-to took 2.5 s and 400 MB on the whole mesh.
    double region_length_ratio = 2.0;

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "mesh_path") const;
};

struct MeshPath {
    std::vector<MeshPathSegment> segments;  ///< start → goal, each in one facet
    double length_m = 0.0;                  ///< geodesic length (the sum of the segments)
};

/// The shortest surface path from the surface point closest to `start_world_m` to the one
/// closest to `goal_world_m` (the start and goal are snapped onto the mesh).
/// Throws InputError naming "start_world_m" / "goal_world_m" when a point is not finite or
/// farther than max_snap_distance_m from the mesh; ConfigError for a bad config; InputError
/// naming "mesh" for an empty or invalid mesh (check_valid), a degenerate facet, a mesh that is
/// not a valid manifold polygon mesh (non-manifold edge or vertex, inconsistent winding), and
/// when the goal is not reachable from the start (another connected component).
MeshPath shortest_path_on_mesh(const TriangleMesh& mesh, const Eigen::Vector3d& start_world_m,
                               const Eigen::Vector3d& goal_world_m,
                               const MeshPathConfig& config = {});

}  // namespace scantling::planning
