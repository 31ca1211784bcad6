#pragma once
/// @file
/// The ROV's initial hull survey plan (SPEC §5; D4.2 §III; issue 14 item 1): a lawnmower of
/// horizontal or vertical slices over the hull side from the water surface to the keel, from the
/// vessel's length and draught only. The slice spacing follows from the camera footprint at the
/// stand-off distance and the wanted overlap; the hull is assumed flat (the sonar-based
/// adaptation of SPEC §5 corrects the path during the survey).
///
/// Hull frame (right-handed, metres): the hull side is the plane y = 0; x runs along the hull
/// (0 at one end of the surveyed section, `length_m` at the other); z is up, 0 at the water
/// surface, the keel at z = −draught_m; the vehicle stands off on the −y side, at
/// y = −stand_off_m, and faces the hull along +y (yaw π/2 about z, 0 along x).
///
/// Camera footprint on the flat hull at stand-off d (camera level, facing the hull):
/// w = 2 d tan(hfov/2) along x, h = 2 d tan(vfov/2) along z. Camera centres range over
///   x ∈ [w/2, L − w/2]  (L/2 when L < w): the footprint reaches both ends of the section;
///   depth ∈ [m + h/2, D − h/2] (m + h/2 when D < m + h): the shallowest footprint's upper edge
///   is `surface_margin_m` = m below the surface (so no image shows air) and the deepest one's
///   lower edge is at the keel.
/// Across the slices the centres are evenly spaced over that range, as few as give a spacing of
/// at most footprint × (1 − overlap) (the achieved overlap is never less than asked; both edges
/// of the range always get a slice). Horizontal slices run along x, the shallowest first;
/// vertical slices run along z at increasing x, the first one downwards. Directions alternate
/// (boustrophedon). Two waypoints per slice, its ends; the path is the waypoints in order.
///
/// Thread-safety: pure functions. Deterministic. Cost: O(number of slices).

#include <Eigen/Geometry>
#include <cstddef>
#include <numbers>
#include <string_view>

#include <scantling/planning/waypoints.hpp>

namespace scantling::io {
template <class T>
class ConfigSchema;
}  // namespace scantling::io

namespace scantling::planning {

enum class SliceOrientation {
    kHorizontal,  ///< slices along the hull at constant depth, stacked from surface to keel
    kVertical,    ///< slices from surface to keel at constant x, side by side along the hull
};

/// Defaults: the reported horizontal survey (SPEC §5: a ~30 × 5 m hull section, horizontal
/// slices at 1.0 m stand-off; the vertical one used 1.3 m) and the Blueye X3 class camera
/// (issue 14: ~77° × 48°). Overlap, margin and speed are chosen here: SPEC gives none.
struct HullSurveyPlanConfig {
    double length_m = 30.0;    ///< length of the surveyed hull section along x, m, > 0
    double draught_m = 5.0;    ///< water surface to keel, m, > 0
    double stand_off_m = 1.0;  ///< camera to hull distance, m, > 0
    double hfov_rad = 77.0 * std::numbers::pi / 180.0;  ///< camera horizontal FOV, rad, (0, π)
    double vfov_rad = 48.0 * std::numbers::pi / 180.0;  ///< camera vertical FOV, rad, (0, π)
    /// Wanted share of a footprint seen again by the neighbouring slice, [0, 1). 0.2 leaves
    /// room for the stand-off error the survey tolerates (issue 14: mean ≤ 0.10 m, i.e. ~10 %
    /// of the footprint at 1 m) without opening gaps.
    double overlap = 0.2;
    SliceOrientation orientation = SliceOrientation::kHorizontal;  ///< slice direction
    /// Gap between the water surface and the upper edge of the shallowest footprint, m, ≥ 0.
    /// 0: the survey reaches the surface; larger keeps waves out of the images and leaves that
    /// band unseen.
    double surface_margin_m = 0.0;
    double speed_m_s = 0.25;  ///< survey speed for the time estimate, m/s, > 0
    double waypoint_tolerance_m = kDefaultWaypointToleranceM;  ///< WP_tol (SPEC §4: 0.20 m)

    /// Throws ConfigError naming "<prefix>.<field>", the value and the expectation for a bad
    /// field (NaN included), and for a plan of more than kMaxHullSurveyWaypoints waypoints.
    void validate(std::string_view prefix = "hull_survey") const;
};

/// A plan needing more waypoints is a unit mistake, not a survey: refused before allocating.
inline constexpr std::size_t kMaxHullSurveyWaypoints = 10000;

/// Camera footprint on a flat surface at the stand-off, facing it (see the file comment).
struct CameraFootprint {
    double width_m = 0.0;   ///< along the image rows (hull x), m
    double height_m = 0.0;  ///< along the image columns (hull z), m
};

/// w = 2 d tan(hfov/2), h = 2 d tan(vfov/2). Assumes a validated config.
CameraFootprint camera_footprint(const HullSurveyPlanConfig& config);

/// The plan and the figures a surveyor wants.
struct HullSurveyPlan {
    /// The waypoints in the HULL frame (the `p_world_m` and `yaw_rad` of each waypoint are hull
    /// coordinates; place them with hull_survey_in_world). Yaw π/2: facing the hull.
    WaypointPath path_hull;
    std::size_t num_slices = 0;
    double slice_spacing_m = 0.0;   ///< between neighbouring slice centres, m (0: one slice)
    CameraFootprint footprint;      ///< at the stand-off
    double path_length_m = 0.0;     ///< first to last waypoint, slices and the steps between, m
    double estimated_time_s = 0.0;  ///< path_length_m / speed_m_s, s (no turns, no approach)
};

/// Throws ConfigError (see validate, prefix "hull_survey").
HullSurveyPlan plan_hull_survey(const HullSurveyPlanConfig& config = {});

/// The plan's waypoints in the world: p_world = T_world_hull · p_hull, and the yaw that faces
/// the hull (its +y axis) in the world. Throws InputError unless T_world_hull is finite and
/// keeps z up (a rotation about z only, within 1e-6): depth and the 4-DoF vehicle's yaw need a
/// vertical hull z axis.
WaypointPath hull_survey_in_world(const HullSurveyPlan& plan,
                                  const Eigen::Isometry3d& T_world_hull);

/// YAML binding (io::ConfigSchema, unknown keys are errors); `orientation` is spelled
/// `horizontal` or `vertical`. Defined with the other schemas' style; not yet a mission type of
/// config_yaml.hpp's mission_from_yaml.
const io::ConfigSchema<HullSurveyPlanConfig>& hull_survey_plan_config_schema();

}  // namespace scantling::planning
