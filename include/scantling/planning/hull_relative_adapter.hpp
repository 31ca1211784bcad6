#pragma once
/// @file
/// Hull-relative adaptation of the ROV's remaining survey path (SPEC §5; D4.2 §III; issue 14
/// item 3): per sonar scan, the hull line the sonar measured moves and turns the rest of the
/// path so that the vehicle keeps its stand-off distance and faces the hull.
///
/// The survey plan (hull_survey_plan.hpp) assumes a flat hull where the vessel's length and
/// draught put it; the real hull curves, and the vehicle's own position drifts. Each waypoint
/// carries the heading that faces the hull it was planned for, so its expected hull normal is
/// n_exp = (cos ψ, sin ψ), and the next waypoint w lies on the line the vehicle should fly,
/// parallel to that hull. The measured line (a point q on the hull, unit normal n from the
/// vehicle towards the hull) gives, at the pivot c (the vehicle projected on the line through w
/// along the expected hull, horizontally: the along-hull place where the sonar looked):
///   Δθ = wrap(∠n − ∠n_exp)              the turn that faces the measured hull,
///   k  = −s − n · (c' − q)               the shift along n that puts c' (c after the turn)
///                                        at the stand-off s, on the vehicle's side;
/// and every remaining waypoint p (from the next one on) becomes p' = c + R(g Δθ)(p − c) + g k n
/// with yaw ψ' = ψ + g Δθ, where g is the gain (a low-pass over scans), and g Δθ, g k are
/// clamped to the per-scan limits (a single spurious line moves the path a little, a real
/// curve a little every scan). Depths (z) are not changed: heave has its own controller.
/// An appendage in view (a bilge keel) measures closer than the plating: the path backs off,
/// which is how the adaptation avoids it.
///
/// Frames: world, z up, yaw about z, 0 along x (waypoints.hpp). Thread-safety: one adapter per
/// vehicle. Deterministic. Cost: O(remaining waypoints) per scan.

#include <Eigen/Core>
#include <cstddef>
#include <numbers>
#include <string_view>

#include <scantling/planning/waypoints.hpp>

namespace scantling::planning {

/// A hull line measured by the sonar, in the world's horizontal plane.
struct HullLineObservation {
    Eigen::Vector2d point_world_m = Eigen::Vector2d::Zero();  ///< the hull point nearest the sonar
    Eigen::Vector2d normal_world = Eigen::Vector2d::UnitX();  ///< unit, sonar → hull
};

/// The observation of a line at `distance_m` on bearing `angle_rad` (sonar frame, positive to
/// the left: perception::SonarHullLine) seen from a sonar at `p_sonar_world_m` looking along
/// `yaw_sonar_rad`. InputError for non-finite values or a negative distance.
HullLineObservation hull_line_in_world(double distance_m, double angle_rad,
                                       const Eigen::Vector2d& p_sonar_world_m,
                                       double yaw_sonar_rad);

struct HullRelativeAdapterConfig {
    double stand_off_m = 1.0;  ///< wanted distance vehicle–hull, m, > 0 (SPEC §5: 1.0 / 1.3)
    /// Share of the measured correction applied per scan, (0, 1]: 0.5 at 5 Hz settles a step
    /// in ~1 s while a single outlier line moves the path by half its error at most.
    double gain = 0.5;
    double max_shift_per_scan_m = 0.2;                               ///< clamp of g k, m, > 0
    double max_turn_per_scan_rad = 10.0 * std::numbers::pi / 180.0;  ///< clamp of g Δθ, > 0
    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "hull_adapter") const;
};

/// What one scan did to the path.
struct AdaptationStep {
    double stand_off_measured_m = 0.0;  ///< n · (q − p_vehicle): the vehicle's distance to the hull
    double shift_m = 0.0;               ///< g k applied, along n
    double turn_rad = 0.0;              ///< g Δθ applied
    bool clamped = false;               ///< a per-scan limit acted
    std::size_t waypoints_moved = 0;
};

class HullRelativeAdapter {
  public:
    /// Validates the config and the path (ConfigError); every waypoint needs a yaw (the
    /// heading that faces the hull), else ConfigError naming it.
    HullRelativeAdapter(WaypointPath path, const HullRelativeAdapterConfig& config = {});

    /// Adapts the waypoints from `next_index` on (the one the vehicle flies to; the leg is
    /// from next_index − 1) to `observation`, seen from `p_vehicle_world_m`. Nothing to move
    /// when next_index ≥ size. InputError for non-finite input or a non-unit normal.
    AdaptationStep adapt(const HullLineObservation& observation,
                         const Eigen::Vector3d& p_vehicle_world_m, std::size_t next_index);

    const WaypointPath& path() const { return path_; }
    const HullRelativeAdapterConfig& config() const { return config_; }

  private:
    Eigen::Vector2d pivot(const Eigen::Vector3d& p_vehicle_world_m, std::size_t next_index) const;

    WaypointPath path_;
    HullRelativeAdapterConfig config_;
};

}  // namespace scantling::planning
