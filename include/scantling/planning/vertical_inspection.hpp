#pragma once
/// @file
/// Vertical-structure inspection (SPEC §4; D5.2 §II.1): up on the left side of a virtual
/// rectangle in front of the structure, down on the right.
///
/// Pattern (axes of wall_rectangle.hpp; a along "right", b along "up"): vertical legs at
/// a = 0, s', 2 s', …, W with s' = W / ceil(W / s) ≤ s; the first leg climbs (b = 0 → H) on
/// the left, the next descends, alternately. Two waypoints per leg (bottom and top). With no
/// leg spacing (the default) there are exactly two legs, at the left and right edges: SPEC's
/// "up on the left side, down on the right", 4 waypoints. Every waypoint is `standoff_m` in
/// front of the structure, facing it with `face_wall`.
///
/// Frames: world (z up, metres, radians). Thread-safety: pure function. Deterministic.
/// Cost: O(number of legs).

#include <optional>
#include <string_view>

#include <scantling/planning/wall_rectangle.hpp>
#include <scantling/planning/waypoints.hpp>

namespace scantling::planning {

/// Stand-off default as the sweep's (sweep_mission.hpp: 0.7 m beyond collision prevention's
/// d_min); SPEC gives only WP_tol.
struct VerticalInspectionConfig {
    double standoff_m = 1.5;  ///< distance from the structure, m, ≥ 0
    /// Maximum distance between an up leg and the next down leg, m (> 0); nullopt: the
    /// rectangle's width, i.e. one leg up on the left and one down on the right (SPEC).
    std::optional<double> leg_spacing_m;
    double waypoint_tolerance_m = kDefaultWaypointToleranceM;  ///< WP_tol (SPEC §4: 0.20 m)
    bool face_wall = true;  ///< give each waypoint the yaw looking at the structure

    /// Throws ConfigError naming "<prefix>.<field>": standoff ≥ 0, spacing and tolerance > 0.
    void validate(std::string_view prefix = "vertical_inspection") const;
};

/// The inspection's waypoints. Throws ConfigError for a bad rectangle
/// ("vertical_inspection.rectangle.height_m = 0, expected finite > 0") or config.
WaypointPath plan_vertical_inspection(const WallRectangle& rectangle,
                                      const VerticalInspectionConfig& config = {});

}  // namespace scantling::planning
