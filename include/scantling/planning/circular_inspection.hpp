#pragma once
/// @file
/// Circular inspection around an isolated structure (SPEC §4; D5.2 §II.1): rings of
/// waypoints on a circle about a vertical axis, one full turn per height, facing the centre.
///
/// Pattern: for each height z_j in `heights_m` (in the order given), N + 1 waypoints at
///   p = (c_x + r cos θ_k, c_y + r sin θ_k, z_j),  θ_k = θ_0 ± 2π k / N,  k = 0 … N
/// (the last closes the turn; + counter-clockwise seen from above, − clockwise), each with the
/// yaw looking at the centre, θ_k + π. Consecutive rings join by a vertical move at θ_0. The
/// straight legs between waypoints cut inside the circle by r (1 − cos(π/N)): 4 cm for
/// r = 2 m, N = 16.
///
/// Frames: world (z up, metres, radians). Thread-safety: pure function. Deterministic.
/// Cost: O(N · number of heights).

#include <Eigen/Core>
#include <cstddef>
#include <string_view>
#include <vector>

#include <scantling/planning/waypoints.hpp>

namespace scantling::planning {

/// What to circle: the structure's vertical axis, the circle's radius and the ring heights.
struct CircleRequest {
    Eigen::Vector2d centre_xy_world_m = Eigen::Vector2d::Zero();  ///< axis of the structure
    double radius_m = 0.0;          ///< > 0: the structure's radius plus the stand-off
    std::vector<double> heights_m;  ///< world z of each ring, flown in this order; non-empty

    /// Throws ConfigError naming "<prefix>.<field>" (non-finite centre, radius ≤ 0, no
    /// heights or a non-finite one).
    void validate(std::string_view prefix) const;
};

/// SPEC gives only WP_tol; the rest are chosen.
struct CircularInspectionConfig {
    /// N, waypoints per turn (≥ 3). 16 keeps the chords within 4 cm of a 2 m circle and the
    /// heading step at 22.5° per leg.
    std::size_t points_per_turn = 16;
    double start_angle_rad = 0.0;                              ///< θ_0, from world x about world z
    bool clockwise = false;                                    ///< seen from above
    double waypoint_tolerance_m = kDefaultWaypointToleranceM;  ///< WP_tol (SPEC §4: 0.20 m)

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "circular_inspection") const;
};

/// The inspection's waypoints. Throws ConfigError for a bad request or config.
WaypointPath plan_circular_inspection(const CircleRequest& request,
                                      const CircularInspectionConfig& config = {});

}  // namespace scantling::planning
