#pragma once
/// @file
/// Replanning a crawler's path around a mapped obstacle that stopped it (SPEC: no reactive
/// swerving; "when stopped by an obstacle, replan a globally valid path or ask the operator").
///
/// Shape. Let s_o be the arc length of the blocking obstacle's centre projected onto the old
/// path, r its radius, R = rejoin_m, and "lateral" the surface normal × the old path's direction
/// (left of the direction of travel). The new path follows the old one to the leave point
/// s_o − r − R, crosses to A, beside the old path at s_o − r − R/2 and d to the side, runs beside
/// it to B at s_o + r + R/2, and comes back onto it at the rejoin point C, s_o + r + R; then it
/// is the old path to its end. A crawler already nearer than the leave point steps sideways
/// from where it stands (to A = the old path's point abreast of it, d to the side): a diagonal
/// from a crawler stopped at the clearance would cut into it. A footprint that ends less than R
/// before the goal leaves less room: C is the goal and B half-way between the footprint and it.
/// Every leg is a surface_line (surface_rectangle.hpp), sideways offsets are walks on the
/// surface, so the path lies on the surface and a leg that leaves it (a plate's edge, a hole)
/// fails that side.
///
/// Offsets and sides. The offset d is first r + clearance_m, then grows by offset_step_m up to
/// max_offset_m while the path passes another obstacle too near; at each d the rejoin distance
/// R is rejoin_m, then twice and three times it (an obstacle beside the old path near the first
/// rejoin point is passed by rejoining later); the first clear path wins on each side. Of the
/// two sides, the shorter path is chosen (ties: left).
///
/// Clear. Every footprint is measured from its centre projected onto the surface, in 3D (a
/// chord: on a curved surface no longer than the distance along it, so on the safe side), to
/// every new segment (the old path's pieces before the leave and after the rejoin were the
/// plan already: an obstacle beside them, outside the crawler's corridor but inside the
/// clearance, would otherwise forbid every detour): each must be at least the
/// radius + clearance_m (1 µm of rounding allowed). A footprint the crawler already stands
/// within radius + clearance_m of (it stopped short of it) needs only radius +
/// inside_clearance_m: the first move sideways may graze nearer, as it must when the obstacle
/// lies ahead and to that side (measured in closed loop: the bracket's centroid 5 cm right of
/// the path blocked the right side at every offset under a "never nearer" rule).
///
/// Not found (an outcome, not an error): the goal (the old path's end) lies within the blocking
/// footprint's radius + clearance; or both sides fail, the reason naming each side and what
/// failed at its last offset (the surface left, or the obstacle passed too near).
///
/// Frames: world, metres. Thread-safety: pure function. Cost: per side and offset, the new
/// path's length / march_step_m projections plus O(segments × obstacles). Deterministic.

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/surface_projector.hpp>
#include <scantling/planning/mesh_path.hpp>
#include <scantling/planning/surface_rectangle.hpp>

namespace scantling::planning {

/// An obstacle's footprint on the surface: a disc around its centre. World frame, metres.
struct ObstacleFootprint {
    Eigen::Vector3d centre_world_m = Eigen::Vector3d::Zero();  ///< on or near the surface
    double radius_m = 0.0;                                     ///< >= 0
};

struct DetourConfig {
    /// > 0: the crawler's centre passes every footprint at least this far, m (half its width +
    /// a margin).
    double clearance_m = 0.2;
    /// > 0: the detour rejoins the old path this far past the obstacle's footprint, m (and
    /// leaves it as far before, or where the crawler is if that is nearer).
    double rejoin_m = 0.3;
    double max_offset_m = 1.0;    ///< > 0: largest lateral offset tried, m
    double offset_step_m = 0.05;  ///< > 0: how much the offset grows per try, m
    /// > 0, <= clearance_m: how near a footprint the crawler already stands within
    /// clearance_m of may be passed, m (see the file comment).
    double inside_clearance_m = 0.05;

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "detour") const;
};

struct Detour {
    bool found = false;
    std::string reason;  ///< why not (names the side(s) and what failed), empty when found
    std::vector<MeshPathSegment> path;  ///< from the crawler's position to the old path's end
    int side = 0;                       ///< +1 passed on the left (normal × forward), −1 right
    double offset_m = 0.0;              ///< lateral offset of the passing leg from the old path
    double length_m = 0.0;              ///< the new path's length (sum of its segments)
    /// C, where the new path is back on the old one (the old path follows from here).
    Eigen::Vector3d rejoin_world_m = Eigen::Vector3d::Zero();
};

/// The detour of the @file around `obstacles[blocking]`, from the crawler at `p_world_m`.
/// `remaining`: the old path ahead of the crawler (its first segment begins near the crawler).
/// `blocking`: index into `obstacles` of the one that stopped the crawler.
/// Throws InputError naming the argument: "p_world_m" not finite or farther than
/// walk.max_start_distance_m from the surface, "remaining" empty or not finite, "blocking" out
/// of range, "obstacles[i]" with a non-finite centre or a radius not finite >= 0; ConfigError
/// naming "detour.<field>" / "surface_walk.<field>" for a bad config.
Detour plan_detour(const SurfaceProjector& surface, const Eigen::Vector3d& p_world_m,
                   const std::vector<MeshPathSegment>& remaining,
                   std::span<const ObstacleFootprint> obstacles, std::size_t blocking,
                   const SurfaceWalkConfig& walk = {}, const DetourConfig& config = {});

}  // namespace scantling::planning
