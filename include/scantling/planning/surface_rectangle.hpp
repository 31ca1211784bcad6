#pragma once
/// @file
/// The crawler's rectangle mission on a surface (SPEC §6: start_mission(x, y, z, W, H)), and the
/// straight lines it is made of, laid on the surface itself.
///
/// Rectangle. At the start point (snapped onto the surface, normal n there) "up" is the world's
/// up direction with its normal part removed, and "across" = up × n (to the right for a robot
/// facing the surface from outside). The W × H rectangle is covered by vertical transects: the
/// first at the start, the last W across, n = ⌈W / max_step⌉ + 1 of them, so the step is
/// adjusted to W / (n − 1) ≤ max_step and no strip is left uncovered (SPEC: "if the last step
/// leaves a strip uncovered the step is adjusted"). The waypoints are the transects' ends in
/// boustrophedon order: bottom 0, top 0, top 1, bottom 1, bottom 2, ...
///
/// Lines on the surface. A point "walks" on the surface: it advances by `march_step_m` along a
/// direction kept tangent (its normal part removed at every step, as the crawler transports its
/// heading), and is projected back onto the surface. On a plate that is the straight line, on a
/// cylinder the helix of constant direction (a geodesic); on a mesh it follows the facets. A
/// line to a goal is walked the same way, aimed at the goal at every step, and cut into segments
/// of `segment_length_m` that carry the surface normal at their middle: the segments of
/// control/segment_follower.hpp, as planning/mesh_path.hpp's geodesics are for a mesh path.
///
/// Errors: InputError naming the request's field: non-finite or non-positive sizes, a start
/// farther than `max_start_distance_m` from the surface, an up direction along the normal (no
/// vertical on a floor), and a rectangle that leaves the surface, naming the transect and the
/// point: a walking step is refused at the surface's border, which is an open mesh edge, the
/// rim of a hole, a sharp fold (the 1 cm rim of a thick plate or of the Möbius strip) or a
/// PlateSurface's edge (an unbounded PlaneSurface has none): the step advances by less than
/// half its length (the border met head on), or the projection pulls consecutive steps back
/// along the surface by more than half a step in all (the border met at a grazing angle, along
/// which the walk would otherwise slide). A rectangle whose
/// transects or legs cross a hole of the mesh is therefore refused, not routed around it; one
/// that fits between the holes is planned, the holes being left uncovered. A non-manifold mesh
/// (an edge of three triangles, a fin on a plate) is walked as the nearest triangle says: no
/// error, and no hang (every walk is bounded by its length or its budget).
///
/// Frames: world, metres. Thread-safety: pure functions. Cost: O(length / march_step_m)
/// projections. Deterministic.

#include <Eigen/Core>
#include <cstddef>
#include <string_view>
#include <vector>

#include <scantling/core/surface_projector.hpp>
#include <scantling/planning/mesh_path.hpp>

namespace scantling::planning {

struct SurfaceRectangleRequest {
    Eigen::Vector3d start_world_m = Eigen::Vector3d::Zero();  ///< lower-left corner
    double width_m = 1.0;                                     ///< W, across, > 0
    double height_m = 1.0;                                    ///< H, up, > 0
    double max_step_m = 0.3;  ///< largest transect spacing (the swath), > 0
    Eigen::Vector3d up_world = Eigen::Vector3d::UnitZ();
};

struct SurfaceWalkConfig {
    double march_step_m = 0.01;          ///< > 0, a walking step
    double segment_length_m = 0.05;      ///< > 0, the follower's segments
    double max_start_distance_m = 0.05;  ///< > 0, how far off the surface a start may be

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "surface_walk") const;
};

struct SurfaceRectanglePlan {
    std::vector<Eigen::Vector3d> waypoints_world_m;  ///< transect ends, boustrophedon
    std::size_t transects = 0;
    double step_m = 0.0;  ///< the adjusted spacing (0 for a single transect)
    Eigen::Vector3d up_world = Eigen::Vector3d::UnitZ();      ///< at the start, tangent
    Eigen::Vector3d across_world = Eigen::Vector3d::UnitX();  ///< at the start, tangent
};

/// The rectangle mission of the @file. InputError as the @file says, ConfigError for a bad
/// config.
SurfaceRectanglePlan plan_surface_rectangle(const SurfaceRectangleRequest& request,
                                            const SurfaceProjector& surface,
                                            const SurfaceWalkConfig& config = {});

/// `p_world` snapped onto the surface. InputError "<field> = (x, y, z) is d m from the surface,
/// expected <= max m" when it is farther than `max_distance_m` (a start off the mesh), or
/// "<field> ... is not finite".
SurfacePoint snap_to_surface(const SurfaceProjector& surface, const Eigen::Vector3d& p_world,
                             double max_distance_m, std::string_view field);

/// `start` walked `distance_m` along `direction_world` (made tangent at the start) on the
/// surface. InputError when the walk leaves the surface ("<what> leaves the surface ...").
Eigen::Vector3d walk_on_surface(const SurfaceProjector& surface, const Eigen::Vector3d& start,
                                const Eigen::Vector3d& direction_world, double distance_m,
                                const SurfaceWalkConfig& config = {},
                                std::string_view what = "walk");

/// The line on the surface from `start` to `goal` (both snapped), as follower segments. Empty
/// when they snap to the same point. InputError when the line leaves the surface or does not
/// reach the goal within 3× their distance.
std::vector<MeshPathSegment> surface_line(const SurfaceProjector& surface,
                                          const Eigen::Vector3d& start, const Eigen::Vector3d& goal,
                                          const SurfaceWalkConfig& config = {});

}  // namespace scantling::planning
