#pragma once
/// @file
/// Height keeping, the safety manager's vertical behaviour (SPEC §4 "the behaviours of §3 plus
/// height keeping"; D5.2 §II.1): a minimum height above the floor and a minimum clearance
/// below the ceiling, by the same two ideas as collision prevention (collision_prevention.hpp)
/// applied to the vertical speed alone:
///
///   descending (v_z < 0): λ = clamp((h_floor − floor_min) / (floor_att − floor_min), 0, 1)
///   climbing   (v_z > 0): λ = clamp((h_ceil − ceiling_min) / (ceiling_att − ceiling_min), 0, 1)
///   v_z_att = λ · v_z
///   push    = K (floor_min − h_floor)⁺ − K (ceiling_min − h_ceil)⁺, clamped to ±v_z_max
///   v_z_cmd = v_z_att + push
///
/// Why separate from §3: the OS1-64 sees ±22.5° about the horizon, so a frustum along a
/// vertical velocity holds no LiDAR point; the floor comes from the down-looking range finder
/// (and the ceiling from the optional up-looking ToF), or, lacking those, from the LiDAR points
/// inside the vehicle's footprint cylinder (clearance_from_cloud; these exist only under the
/// vehicle's own tilt or with a wider-FOV sensor). The two pushes add: one per surface, so
/// between a floor and a ceiling both inside their minimum the vehicle settles where the two
/// balance.
///
/// Frame: body (z up), metres, m/s; clearances from the body origin (the centre), as in §3. A
/// range finder's range along body −z is taken as the vertical clearance; at a tilt θ it
/// overstates it by 1/cos θ (1.5 % at 10°): pass range · cos θ when the tilt is known.
/// Thread-safety: pure functions. Cost: O(1); clearance_from_cloud one pass over the cloud.

#include <optional>
#include <string_view>

#include <scantling/core/point_cloud.hpp>
#include <scantling/safety/collision_prevention.hpp>

namespace scantling::safety {

/// Defaults chosen (SPEC gives none) for the inspection quadrotor of collision_prevention.hpp:
/// 0.6 m above the floor keeps ~0.45 m under its legs; the 0.6 m attenuation band at the
/// 0.5 m/s vertical speed limit brakes with T = 1.2 s, four times the velocity loop's τ.
struct HeightKeepingConfig {
    double floor_min_m = 0.6;             ///< minimum centre height above the floor, > 0
    double floor_att_m = 1.2;             ///< descent attenuation starts here, > floor_min_m
    double ceiling_min_m = 0.6;           ///< minimum centre clearance below the ceiling, > 0
    double ceiling_att_m = 1.2;           ///< climb attenuation starts here, > ceiling_min_m
    double gain_per_s = 1.0;              ///< K: push-back per metre inside a minimum, 1/s, > 0
    double max_vertical_speed_mps = 0.5;  ///< clamp of the push, > 0
    /// Horizontal radius of the cylinder whose LiDAR points count as floor or ceiling
    /// (clearance_from_cloud): the vehicle's radius plus a margin, > 0.
    double footprint_radius_m = 0.5;

    /// Throws ConfigError naming "<prefix>.<field>", its value and what was expected.
    void validate(std::string_view prefix = "height_keeping") const;
};

/// Vertical clearances from the body centre; nullopt: unknown, +inf: nothing within range.
struct VerticalClearance {
    std::optional<double> floor_m;
    std::optional<double> ceiling_m;
};

struct HeightKeepingResult {
    double v_z_cmd_mps = 0.0;  ///< v_z_att + push
    double lambda = 1.0;       ///< attenuation of the desired vertical speed, [0, 1]
    double push_mps = 0.0;     ///< push away from floor (+) / ceiling (−), clamped
    AttenuationStatus status = AttenuationStatus::kNoData;  ///< of the attenuation
};

/// The vertical command for desired vertical speed `v_z_desired_mps` (body z, + up). Throws
/// InputError for a non-finite speed or a NaN / negative clearance, ConfigError for a bad
/// config. No clearance known: the command is the desired speed (status kNoData).
HeightKeepingResult keep_height(double v_z_desired_mps, const VerticalClearance& clearance,
                                const HeightKeepingConfig& config = {});

/// The nearest LiDAR points straight below and above: the points whose horizontal distance from
/// body z is within footprint_radius_m, below (z < 0) giving the floor, above the ceiling.
/// Non-finite points are skipped.
VerticalClearance clearance_from_cloud(const PointCloud& cloud_body,
                                       const HeightKeepingConfig& config = {});

/// The nearer of two sources per side (e.g. the range finder and the LiDAR).
VerticalClearance nearest(const VerticalClearance& a, const VerticalClearance& b);

}  // namespace scantling::safety
