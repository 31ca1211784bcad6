#pragma once
/// @file
/// Re-inspection of the coverage holes of the sonar inspection map in the same mission (SPEC §5;
/// issue 14 item 4): each hole's centroid is visited at the stand-off, facing the hull; a hole
/// wider than the camera footprint also gets a short pass across its bounding box. Holes are
/// taken greedily nearest-first from the vehicle's current position.
///
/// Geometry, per hole (world frame, metres): the hull is locally the plane through the hole's
/// centroid c with unit normal n pointing from the hull into the water (towards the vehicle);
/// the vehicle stands at c + stand_off · n + a · axis, with yaw facing −n. When the hole's box
/// is wider than footprint_width_m along its wider in-plane axis, the pass runs along that axis
/// through c from box_min + w/2 to box_max − w/2 (w = footprint width: the footprint just
/// reaches the box's ends), with c's own waypoint in between; otherwise c is the only waypoint.
/// A pass starts at its end nearer to where the vehicle comes from.
///
/// Thread-safety: pure function. Deterministic: distance ties go to the lower hole index.
/// Cost: O(h²) for h holes.

#include <Eigen/Core>
#include <span>
#include <string_view>

#include <scantling/planning/waypoints.hpp>

namespace scantling::planning {

/// A hole to re-inspect, frame-free (a mapping::CoverageHole expressed with its surface's axes).
struct ReinspectionHole {
    Eigen::Vector3d centroid_world_m = Eigen::Vector3d::Zero();  ///< on the hull, world, m
    Eigen::Vector3d axis_u_world = Eigen::Vector3d::UnitX();     ///< unit, in the hull plane
    Eigen::Vector3d axis_v_world = Eigen::Vector3d::UnitZ();     ///< unit, in-plane, ⟂ axis_u
    /// Bounding box along axis_u / axis_v relative to the centroid, m: min <= 0 <= max.
    double box_min_u_m = 0.0, box_max_u_m = 0.0;
    double box_min_v_m = 0.0, box_max_v_m = 0.0;
};

struct HoleReinspectionConfig {
    /// Camera to hull distance, m, finite > 0. SPEC §5's horizontal survey: 1.0 m.
    double stand_off_m = 1.0;
    /// Camera footprint across a pass at the stand-off, m, finite > 0. 1.59 m: the Blueye X3
    /// class camera's 77° at 1.0 m, 2 · 1.0 · tan(38.5°) (planning::camera_footprint).
    double footprint_width_m = 1.59;
    double waypoint_tolerance_m = kDefaultWaypointToleranceM;  ///< WP_tol, m, finite > 0

    /// Throws ConfigError("<prefix>.stand_off_m = 0, expected finite > 0").
    void validate(std::string_view prefix = "hole_reinspection") const;
};

/// The path over every hole, each once, nearest-first from `p_start_world_m`: distance from the
/// current position (the start, then the last waypoint of the previous hole) to the hole's
/// centroid at the stand-off. `normal_world` (any length > 0) points from the hull into the
/// water and must not be vertical (within 1e-6 of the horizontal part's norm): the 4-DoF ROV
/// faces the hull by yaw only. An empty `holes` gives an empty path.
/// Throws ConfigError for a bad config; InputError naming the field ("holes[2].axis_u_world",
/// "normal_world", "p_start_world_m") for non-finite values, non-unit or non-orthogonal axes
/// (1e-6), a box not containing its centroid.
WaypointPath plan_hole_reinspection(std::span<const ReinspectionHole> holes,
                                    const Eigen::Vector3d& normal_world,
                                    const Eigen::Vector3d& p_start_world_m,
                                    const HoleReinspectionConfig& config = {});

}  // namespace scantling::planning
