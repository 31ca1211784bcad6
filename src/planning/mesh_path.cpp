// The only translation unit that includes CGAL (its headers cost most of this file's compile
// time; keep them out of every other file). SPEC §6: the crawler's path on the mesh.
#include <scantling/planning/mesh_path.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>

#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>
#include <CGAL/boost/graph/helpers.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::planning {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;
using FaceIndex = SurfaceMesh::Face_index;
using HalfedgeIndex = SurfaceMesh::Halfedge_index;
using VertexIndex = SurfaceMesh::Vertex_index;
using ShortestPathTraits = CGAL::Surface_mesh_shortest_path_traits<Kernel, SurfaceMesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<ShortestPathTraits>;
using Barycentric = ShortestPath::Barycentric_coordinates;
using FaceLocation = ShortestPath::Face_location;
using AabbPrimitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using AabbTraits = CGAL::AABB_traits<Kernel, AabbPrimitive>;
using AabbTree = CGAL::AABB_tree<AabbTraits>;

constexpr double kMinFacetAreaM2 = 1e-12;  // 1 µm²: a facet without a usable normal
constexpr double kMinPieceM = 1e-6;  // shorter pieces are rounding (and the follower's minimum)
constexpr double kOnFacetM = 1e-9;   // a point this close to a facet lies in it

Eigen::Vector3d to_eigen(const Point3& p) { return {p.x(), p.y(), p.z()}; }

void check_facets(const TriangleMesh& mesh) {
    if (mesh.empty()) throw InputError("mesh_path.mesh has no triangles");
    check_valid(mesh, "mesh_path.mesh");
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
        if (triangle_area(mesh, t) < kMinFacetAreaM2) {
            throw InputError(fmt::format(
                "mesh_path.mesh triangle {} is degenerate (area {:.3g} m², expected >= {:g})", t,
                triangle_area(mesh, t), kMinFacetAreaM2));
        }
    }
}

// Face i of the result is triangle i of the input (faces are added in order and none is
// skipped); only referenced vertices are added (an isolated vertex has no halfedge).
SurfaceMesh to_surface_mesh(const TriangleMesh& mesh) {
    SurfaceMesh out;
    std::vector<VertexIndex> vertex(mesh.num_vertices(), SurfaceMesh::null_vertex());
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
        std::array<VertexIndex, 3> corners;
        for (int c = 0; c < 3; ++c) {
            VertexIndex& v = vertex[static_cast<std::size_t>(mesh.triangles[t][c])];
            const Eigen::Vector3d& p =
                mesh.vertices[static_cast<std::size_t>(mesh.triangles[t][c])];
            if (v == SurfaceMesh::null_vertex()) v = out.add_vertex(Point3(p.x(), p.y(), p.z()));
            corners[static_cast<std::size_t>(c)] = v;
        }
        if (out.add_face(corners[0], corners[1], corners[2]) == SurfaceMesh::null_face()) {
            throw InputError(fmt::format(
                "mesh_path.mesh triangle {} cannot be added to a manifold surface (a non-manifold "
                "edge or vertex, a duplicate facet, or a winding that flips against a neighbour)",
                t));
        }
    }
    if (!CGAL::is_valid_polygon_mesh(out)) {
        throw InputError("mesh_path.mesh is not a valid polygon mesh");
    }
    return out;
}

// CGAL 5.5 returns a longer, wrong path from a source on an edge of the facet it is located in
// (a barycentric coordinate exactly 0): on a flat 8 × 8 grid plate, from (-0.6, -0.5) on a grid
// line, 1.6225 m against the straight 1.5811 m, zig-zagging 1.5 cm off the line
// (SurfaceTasks.GoToTakesTheGeodesicOnAMeshAndIsAnApproach). A point nudged 1e-9 into the
// facet gives the straight line; the nudge moves it by a nanometre of the facet's size.
constexpr double kBarycentricNudge = 1e-9;

FaceLocation inside_facet(FaceLocation location) {
    Barycentric& b = location.second;
    double sum = 0.0;
    for (std::size_t i = 0; i < 3; ++i) {
        b[i] = std::max(b[i], kBarycentricNudge);
        sum += b[i];
    }
    for (std::size_t i = 0; i < 3; ++i) b[i] /= sum;
    return location;
}

// A located start or goal: the closest surface point, refused if too far.
FaceLocation snap(const ShortestPath& paths, const AabbTree& tree, const Eigen::Vector3d& p_world_m,
                  std::string_view field, double max_snap_distance_m) {
    if (!p_world_m.allFinite()) {
        throw InputError(fmt::format("mesh_path.{} = ({}, {}, {}) is not finite", field,
                                     p_world_m.x(), p_world_m.y(), p_world_m.z()));
    }
    const FaceLocation location =
        paths.locate(Point3(p_world_m.x(), p_world_m.y(), p_world_m.z()), tree);
    const double distance_m =
        (to_eigen(paths.point(location.first, location.second)) - p_world_m).norm();
    if (!(distance_m <= max_snap_distance_m)) {
        throw InputError(fmt::format(
            "mesh_path.{} = ({:.3f}, {:.3f}, {:.3f}) is {:.3f} m from the mesh, expected <= "
            "max_snap_distance_m {:.3f} m",
            field, p_world_m.x(), p_world_m.y(), p_world_m.z(), distance_m, max_snap_distance_m));
    }
    return inside_facet(location);
}

// One point of the path and the facets it may lie in: every facet around a corner of the
// simplex CGAL reports it on (a superset: CGAL reports a run along an edge as crossings of the
// edges fanning out of its vertices, so the simplex alone would pick a wrong facet).
struct PathEvent {
    Eigen::Vector3d p_world_m;
    std::set<std::size_t> faces;
};

// The SurfaceMeshShortestPathVisitor: records the simplices the path passes, goal first.
class EventRecorder {
  public:
    EventRecorder(const ShortestPath& paths, const SurfaceMesh& mesh)
        : paths_(paths), mesh_(mesh) {}

    // CGAL 5.5 can report a crossing parameter off the edge where the path runs along an edge
    // (seen: t = −12.2 on the plate); the crossing is on the edge, so t is clamped onto it.
    void operator()(HalfedgeIndex edge, Kernel::FT t) {
        const Kernel::FT on_edge = std::clamp(t, Kernel::FT(0), Kernel::FT(1));
        record(to_eigen(paths_.point(edge, on_edge)), {mesh_.source(edge), mesh_.target(edge)});
    }
    void operator()(VertexIndex vertex) { record(to_eigen(mesh_.point(vertex)), {vertex}); }
    void operator()(FaceIndex face, const Barycentric& location) {
        const HalfedgeIndex h = mesh_.halfedge(face);
        record(to_eigen(paths_.point(face, location)),
               {mesh_.source(h), mesh_.target(h), mesh_.target(mesh_.next(h))});
    }

    std::vector<PathEvent>& events() { return events_; }

  private:
    void record(const Eigen::Vector3d& p_world_m, std::initializer_list<VertexIndex> corners) {
        PathEvent event{p_world_m, {}};
        for (const VertexIndex v : corners) {
            for (const FaceIndex f : mesh_.faces_around_target(mesh_.halfedge(v))) {
                if (f != SurfaceMesh::null_face()) event.faces.insert(f.idx());
            }
        }
        events_.push_back(std::move(event));
    }

    const ShortestPath& paths_;
    const SurfaceMesh& mesh_;
    std::vector<PathEvent> events_;
};

double distance_to_facet_m(const TriangleMesh& mesh, std::size_t face, const Eigen::Vector3d& p) {
    const Eigen::Vector3i& tri = mesh.triangles[face];
    return (closest_point_on_triangle(p, mesh.vertices[static_cast<std::size_t>(tri[0])],
                                      mesh.vertices[static_cast<std::size_t>(tri[1])],
                                      mesh.vertices[static_cast<std::size_t>(tri[2])]) -
            p)
        .norm();
}

// The facet of the piece a → b: the smallest index among the candidate facets that hold both
// ends and the midpoint (two along an edge: see the @file); should rounding leave none, the
// candidate nearest the midpoint.
std::size_t piece_facet(const TriangleMesh& mesh, const PathEvent& a, const PathEvent& b) {
    const Eigen::Vector3d mid = 0.5 * (a.p_world_m + b.p_world_m);
    for (const std::size_t f : a.faces) {
        if (distance_to_facet_m(mesh, f, a.p_world_m) <= kOnFacetM &&
            distance_to_facet_m(mesh, f, b.p_world_m) <= kOnFacetM &&
            distance_to_facet_m(mesh, f, mid) <= kOnFacetM) {
            return f;
        }
    }
    std::size_t best = *a.faces.begin();
    for (const std::size_t f : a.faces) {
        if (distance_to_facet_m(mesh, f, mid) < distance_to_facet_m(mesh, best, mid)) best = f;
    }
    return best;
}

MeshPath cut_into_segments(const TriangleMesh& mesh, const std::vector<PathEvent>& events) {
    MeshPath path;
    for (std::size_t i = 1; i < events.size(); ++i) {
        const PathEvent& a = events[i - 1];
        const PathEvent& b = events[i];
        const double length_m = (b.p_world_m - a.p_world_m).norm();
        if (length_m < kMinPieceM) continue;
        const std::size_t face = piece_facet(mesh, a, b);
        // Joined: begin at the previous segment's end even if a dropped piece lay between.
        const Eigen::Vector3d begin =
            path.segments.empty() ? a.p_world_m : path.segments.back().end_world_m;
        path.segments.push_back({begin, b.p_world_m, triangle_normal(mesh, face), face});
        path.length_m += (b.p_world_m - begin).norm();
    }
    return path;
}

/// The facets that may hold a path of length <= limit_m from `a` to `b`, as a mesh of their own
/// (`faces[i]`: facet i's index in the input).
struct Region {
    TriangleMesh mesh;
    std::vector<std::size_t> faces;
};

Region region_of(const TriangleMesh& mesh, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                 double limit_m) {
    Region region;
    std::vector<int> vertex(mesh.num_vertices(), -1);
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        double longest_m = 0.0, nearest_m = std::numeric_limits<double>::infinity();
        for (int c = 0; c < 3; ++c) {
            const Eigen::Vector3d& v = mesh.vertices[static_cast<std::size_t>(tri[c])];
            const Eigen::Vector3d& w = mesh.vertices[static_cast<std::size_t>(tri[(c + 1) % 3])];
            longest_m = std::max(longest_m, (w - v).norm());
            nearest_m = std::min(nearest_m, (v - a).norm() + (v - b).norm());
        }
        // A point of the facet inside the ellipsoid is within the longest edge of a corner.
        if (nearest_m > limit_m + 2.0 * longest_m) continue;
        Eigen::Vector3i out;
        for (int c = 0; c < 3; ++c) {
            int& id = vertex[static_cast<std::size_t>(tri[c])];
            if (id < 0) {
                id = static_cast<int>(region.mesh.vertices.size());
                region.mesh.vertices.push_back(mesh.vertices[static_cast<std::size_t>(tri[c])]);
            }
            out[c] = id;
        }
        region.mesh.triangles.push_back(out);
        region.faces.push_back(t);
    }
    return region;
}

/// The exact path on `mesh` (`surface` its CGAL form); nullopt when the goal is not reachable
/// from the start and `whole` is false (a region may cut the way), InputError when it is true.
std::optional<MeshPath> path_in(const TriangleMesh& mesh, const SurfaceMesh& surface,
                                const Eigen::Vector3d& start_world_m,
                                const Eigen::Vector3d& goal_world_m, const MeshPathConfig& config,
                                bool whole) {
    ShortestPath paths(surface);
    AabbTree tree;
    paths.build_aabb_tree(tree);
    const FaceLocation start =
        snap(paths, tree, start_world_m, "start_world_m", config.max_snap_distance_m);
    const FaceLocation goal =
        snap(paths, tree, goal_world_m, "goal_world_m", config.max_snap_distance_m);
    paths.add_source_point(start);
    EventRecorder recorder(paths, surface);
    const auto result =
        paths.shortest_path_sequence_to_source_points(goal.first, goal.second, recorder);
    if (result.first < 0.0) {
        if (!whole) return std::nullopt;
        throw InputError(
            "mesh_path.mesh has no surface path from start_world_m to goal_world_m (they lie "
            "on different connected components)");
    }
    std::vector<PathEvent>& events = recorder.events();
    std::reverse(events.begin(), events.end());  // CGAL visits goal → source
    return cut_into_segments(mesh, events);
}

}  // namespace

void MeshPathConfig::validate(std::string_view prefix) const {
    config_checks::require_positive(max_snap_distance_m, prefix, "max_snap_distance_m");
    config_checks::require(std::isfinite(region_length_ratio) &&
                               (region_length_ratio == 0.0 || region_length_ratio >= 1.0),
                           prefix, "region_length_ratio", region_length_ratio, "0 (off) or >= 1");
}

MeshPath shortest_path_on_mesh(const TriangleMesh& mesh, const Eigen::Vector3d& start_world_m,
                               const Eigen::Vector3d& goal_world_m, const MeshPathConfig& config) {
    config.validate();
    check_facets(mesh);
    // Converted (and so checked to be a manifold polygon mesh) whole even when the region's path
    // is used: the contract covers the whole mesh, and the conversion is a small share of the
    // propagation's cost.
    const SurfaceMesh whole = to_surface_mesh(mesh);
    if (config.region_length_ratio > 0.0 && start_world_m.allFinite() && goal_world_m.allFinite()) {
        const double limit_m = config.region_length_ratio * ((goal_world_m - start_world_m).norm() +
                                                             2.0 * config.max_snap_distance_m);
        const Region region = region_of(mesh, start_world_m, goal_world_m, limit_m);
        if (!region.faces.empty() && region.faces.size() < mesh.num_triangles()) {
            std::optional<MeshPath> path;
            try {
                path = path_in(region.mesh, to_surface_mesh(region.mesh), start_world_m,
                               goal_world_m, config, false);
            } catch (const InputError&) {
                // A region cut out of a manifold mesh may pinch at a vertex: the whole mesh.
            }
            if (path && path->length_m <= limit_m) {
                for (MeshPathSegment& segment : path->segments) {
                    segment.face = region.faces[segment.face];
                }
                return *path;
            }
        }
    }
    return *path_in(mesh, whole, start_world_m, goal_world_m, config, true);
}

}  // namespace scantling::planning
