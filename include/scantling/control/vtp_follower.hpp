#pragma once
/// @file
/// The Virtual Target Point (VTP) trajectory follower of SPEC §4 (D5.2 §II.1): instead of
/// flying straight at the current waypoint WP, the position controller chases a point on the
/// segment WP_prev → WP, which pulls the vehicle back onto the intended path.
///
/// With P the vehicle position, C the closest point to P on the *line* WP_prev–WP (parameter
/// t = (P − WP_prev)·(WP − WP_prev) / |WP − WP_prev|², C between them for 0 ≤ t ≤ 1),
/// d = |P − C|, λ the largest allowed separation from the path and δ the largest distance to
/// the VTP, exactly SPEC's five cases:
///   1. C between WP_prev and WP, d < λ: VTP = C + L û, L = δ (1 − d/λ), û the unit direction
///      WP_prev → WP; VTP = WP if L > |C − WP|.
///   2. C between them, d ≥ λ: VTP = C (back to the path first).
///   3. C before WP_prev (t < 0) and |C − WP_prev| > WP_tol: VTP = WP_prev.
///   4. C before WP_prev but |C − WP_prev| ≤ WP_tol: as case 1 or 2, by d (L measured from C).
///   5. C beyond WP (t > 1): VTP = WP.
/// Boundaries: C exactly at WP_prev or WP (t = 0 or 1) is "between"; d = λ is case 2 (where
/// case 1's L would be 0 anyway, so the VTP is continuous there); |C − WP_prev| = WP_tol is
/// inside (case 4). A zero-length segment (WP_prev = WP, within 1 µm) has no line: case 5,
/// VTP = WP. For the first waypoint there is no WP_prev: the caller passes the vehicle's start
/// position (waypoint_sequencer.hpp does).
///
/// δ sets the approach speed (D5.2: the position controller sees an error of up to δ), λ how
/// hard the path attracts. Frames: world (metres). Thread-safety: pure function. Cost: O(1).

#include <Eigen/Core>
#include <string_view>

namespace scantling::control {

/// SPEC §4's values (D5.2's HIL runs; its Figure 10 uses λ = 0.5 m).
struct VtpConfig {
    double max_vtp_distance_m = 2.0;     ///< δ, > 0
    double max_path_separation_m = 0.2;  ///< λ, > 0

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "vtp") const;
};

/// SPEC §4's case numbers.
enum class VtpCase {
    kOnPath = 1,          ///< 1: between, d < λ: ahead along the path
    kOffPath = 2,         ///< 2: between, d ≥ λ: VTP = C
    kBeforeStart = 3,     ///< 3: before WP_prev, outside WP_tol: VTP = WP_prev
    kNearStart = 4,       ///< 4: before WP_prev, inside WP_tol: as 1 or 2
    kBeyondWaypoint = 5,  ///< 5: beyond WP (or a zero-length segment): VTP = WP
};

struct VtpResult {
    Eigen::Vector3d vtp_world_m = Eigen::Vector3d::Zero();      ///< the point to chase
    Eigen::Vector3d closest_world_m = Eigen::Vector3d::Zero();  ///< C
    double distance_to_path_m = 0.0;                            ///< d = |P − C|
    double along_segment = 0.0;  ///< t (0 at WP_prev, 1 at WP; 0 for a zero-length one)
    VtpCase vtp_case = VtpCase::kBeyondWaypoint;
};

/// The VTP for vehicle position `p_world_m` on the segment `wp_prev_world_m` → `wp_world_m`
/// with WP's tolerance `waypoint_tolerance_m` (> 0). Throws InputError for non-finite
/// positions, ConfigError for a bad config or a tolerance ≤ 0
/// ("virtual_target_point.waypoint_tolerance_m = 0, expected finite > 0").
VtpResult virtual_target_point(const Eigen::Vector3d& p_world_m,
                               const Eigen::Vector3d& wp_prev_world_m,
                               const Eigen::Vector3d& wp_world_m, double waypoint_tolerance_m,
                               const VtpConfig& config = {});

std::string_view to_string(VtpCase vtp_case);

}  // namespace scantling::control
