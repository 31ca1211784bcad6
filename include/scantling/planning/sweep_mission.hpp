#pragma once
/// @file
/// Sweeping mission (SPEC §4; D5.2 §II.1): a zig-zag over a virtual rectangle in front of a
/// wall, side to side, top to bottom, at a constant stand-off.
///
/// Pattern (axes of wall_rectangle.hpp; a along "right", b along "up"): horizontal lines at
/// b = H, H − s', …, 0 with s' = H / ceil(H / s) ≤ s (the line spacing s is a maximum, so the
/// coverage is never coarser than asked and the bottom edge is always flown); the top line goes
/// left to right (a = 0 → W), the next right to left, and so on. Two waypoints per line (its
/// ends), so an 8 × 5 m rectangle with s = 1 m gives 6 lines, 12 waypoints. Every waypoint
/// lies `standoff_m` in front of the wall and, with `face_wall`, holds the yaw that looks at it
/// (along −n).
///
/// Frames: world (z up, metres, radians). Thread-safety: pure function. Deterministic.
/// Cost: O(number of lines).

#include <string_view>

#include <scantling/planning/wall_rectangle.hpp>
#include <scantling/planning/waypoints.hpp>

namespace scantling::planning {

/// SPEC §4 gives WP_tol only; the stand-off and spacing are chosen here (say so: SPEC and the
/// seeds give neither) for the collision-prevention defaults (safety: d_min 0.8 m, d_att 2 m).
struct SweepConfig {
    /// Distance from the wall, m. 1.5 m keeps 0.7 m over d_min = 0.8 m (room for WP_tol and a
    /// gust's overshoot without the repulsion fighting the controller) and, sideways to the
    /// motion, the wall out of the 22.5° frustum up to 3.6 m ahead (> d_att: no braking).
    double standoff_m = 1.5;
    /// Maximum distance between lines, m. A ~48° vertical camera field of view covers
    /// 2 · 1.5 · tan 24° ≈ 1.3 m of wall at 1.5 m: 1 m lines overlap by ~25 %.
    double line_spacing_m = 1.0;
    double waypoint_tolerance_m = kDefaultWaypointToleranceM;  ///< WP_tol (SPEC §4: 0.20 m)
    bool face_wall = true;  ///< give each waypoint the yaw looking at the wall

    /// Throws ConfigError naming "<prefix>.<field>": standoff ≥ 0, spacing and tolerance > 0.
    void validate(std::string_view prefix = "sweep") const;
};

/// The sweep's waypoints. Throws ConfigError for a bad rectangle ("sweep.rectangle.width_m =
/// 0, expected finite > 0") or config, or more than 10 000 lines.
WaypointPath plan_sweep(const WallRectangle& rectangle, const SweepConfig& config = {});

}  // namespace scantling::planning
