#pragma once
/// @file
/// MAV collision prevention on the raw LiDAR sweep (SPEC §3; D4.2 §II.3, D5.2 §III.1): the
/// "attenuated go" and "prevent collision" behaviours of the drone's safety manager.
///
///   d_o     = min |p| over the points p inside the frustum along v_ud (below)
///   λ       = clamp((d_o − d_min) / (d_att − d_min), 0, 1)   (1 when no point is in it)
///   vel_att = λ · vel_ud
///   rep_p   = −p/|p| · K (d_min − |p|)         for every point with |p| < d_min
///   vel_rep = mean of rep_p, magnitude clamped to v_max
///   vel_cmd = vel_att + vel_rep
///
/// The seeds disagree on how the rep_p combine ("added together" in their overviews, "the mean"
/// in their formulas; RESULTS-TO-REPRODUCE item 12); SPEC §3 says the mean, and so does this.
///
/// Frame: everything is in the body frame (x forward, y left, z up; metres, m/s), the cloud
/// already mapped from the LiDAR into it; the body origin is the vehicle's centre.
///
/// Distances: d_p = |p| is measured from the body origin, not from the hull (|p| − d_r). SPEC's
/// near plane at d_r only makes sense for centre distances (it drops returns from inside the
/// vehicle's own radius), and the LiDAR measures from its centre; so d_min and d_att are centre
/// distances, the free space left between hull and obstacle is d_min − d_r, and a config needs
/// d_att > d_min > d_r.
///
/// Frustum: a pyramid whose axis f is the direction of v_ud. Its "horizontal" axis h is
/// perpendicular to f and to body z (h = z × f, normalised), its "vertical" axis u = f × h lies
/// in the plane of f and body z; for a purely vertical v_ud (f ∥ z) h is body y. A point p is
/// inside when d_r ≤ p·f ≤ d_att, |p·h| ≤ tan(θ_h) p·f and |p·u| ≤ tan(θ_v) p·f (boundaries
/// included), θ_h = θ_v = 22.5° by default (SPEC's 45° × 45° field of view). Body z stands for
/// gravity: a multirotor tilts by its acceleration only (a few degrees), which turns the
/// frustum by as much about f. A zero v_ud has no frustum; the repulsion still acts.
///
/// Not guaranteed by SPEC §3 (and so not by this): a point closer than d_min but outside the
/// frustum does not attenuate, so an oblique approach to a wall already inside d_min keeps a
/// component towards it, opposed only by the (mean) repulsion; and the mean over many points
/// of a far-ish surface can outweigh one nearer point. Nor does it bound the braking: the
/// defaults stop a vehicle with the simulator's velocity lag at d_min only for |v_ud| ≤ v_max
/// (2 v_max overshoots to 0.66 m; from 4 v_max the hull passes d_r, where the near plane
/// empties the frustum); a faster vehicle needs d_att − d_min ≳ 1.2 s · |v_ud|.
/// tests/safety/collision_prevention_property_test.cpp pins all three.
///
/// Input contract: NaN/infinite points are skipped (a sweep's no-returns), as is a point at
/// the origin (no direction to push away from); a non-finite v_ud or a bad config throws.
/// Cost: one pass over the points, ~20 flops each, no allocation (≤ 1 ms per 64 × 1024 sweep
/// on one core: docs/benchmarks.md). Thread-safety: pure functions. Deterministic.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include <scantling/core/point_cloud.hpp>

namespace scantling::safety {

/// Defaults: SPEC §3 gives none (RESULTS-TO-REPRODUCE item 12), so these are chosen for a small
/// inspection quadrotor (~0.6 m across its guards) flying inside a tank or cargo hold, with the
/// simulator's velocity loop (τ = 0.3 s, sim/mav_dynamics.hpp) and a 10 Hz OS1-64.
struct CollisionPreventionConfig {
    /// d_att: attenuation starts here. With λ linear in d_o, a straight approach slows as
    /// e^(−t/T), T = (d_att − d_min) / |v_ud| = 1.2 s at 1 m/s: four times the velocity
    /// loop's τ, so the vehicle follows the braking; a 2 m reach also leaves a 1 m inspection
    /// stand-off plus frustum margin while sweeping parallel to a wall unattenuated.
    double d_att_m = 2.0;
    /// d_min: no closer (centre distance). 0.8 m keeps 0.45 m between the guards (d_r) and
    /// the steel: room for 0.3 m stiffeners, LiDAR noise (~3 cm) and a gust's overshoot.
    double d_min_m = 0.8;
    /// d_r: near plane of the frustum; the vehicle's radius (0.3 m half-span + guard margin).
    double robot_radius_m = 0.35;
    /// K: repulsion per metre inside d_min, 1/s. A point 0.3 m inside pushes at 0.3 m/s; the
    /// push-back settles with time constant 1/K = 1 s, slow against τ = 0.3 s (no ringing).
    double repulsion_gain_per_s = 1.0;
    /// v_max: the repulsion's magnitude clamp; also the speed the other defaults assume.
    /// 1 m/s is a careful indoor speed: 0.1 m of travel per 10 Hz sweep.
    double max_speed_mps = 1.0;
    /// Half the frustum's horizontal field of view (SPEC: 45° full), degrees, in (0, 90).
    double half_fov_horizontal_deg = 22.5;
    /// Half the frustum's vertical field of view (SPEC: 45° full), degrees, in (0, 90).
    double half_fov_vertical_deg = 22.5;

    /// Throws ConfigError naming "<prefix>.<field>", its value and what was expected:
    /// d_att > d_min > d_r ≥ 0, K > 0, v_max > 0, half-angles in (0, 90).
    void validate(std::string_view prefix = "collision_prevention") const;
};

/// What the attenuation did (the repulsion is `num_points_within_d_min > 0`).
enum class AttenuationStatus {
    kNoData,      ///< no usable point in the sweep: the command is the desired velocity
    kClear,       ///< no point in the frustum at d_o < d_att (or v_ud = 0): λ = 1
    kAttenuated,  ///< d_min < d_o < d_att: 0 < λ < 1
    kStopped,     ///< d_o ≤ d_min: λ = 0, the desired velocity is removed
};

struct CollisionPreventionResult {
    Eigen::Vector3d v_cmd_body_mps = Eigen::Vector3d::Zero();  ///< vel_cmd = vel_att + vel_rep
    Eigen::Vector3d v_att_body_mps = Eigen::Vector3d::Zero();  ///< λ · vel_ud
    Eigen::Vector3d v_rep_body_mps = Eigen::Vector3d::Zero();  ///< mean repulsion, clamped
    double lambda = 1.0;                                       ///< attenuation factor, [0, 1]
    std::optional<double> d_o_m;         ///< nearest frustum point; nullopt: none (or v_ud = 0)
    std::size_t num_valid_points = 0;    ///< finite, not at the origin
    std::size_t num_frustum_points = 0;  ///< inside the frustum
    std::size_t num_points_within_d_min = 0;  ///< repelling (|p| < d_min)
    bool repulsion_clamped = false;           ///< |mean rep| exceeded v_max
    AttenuationStatus status = AttenuationStatus::kNoData;
};

/// SPEC §3 on one sweep: the command for desired body velocity `v_desired_body_mps` given the
/// sweep `cloud_body` (points in the body frame). Throws ConfigError / InputError (non-finite
/// desired velocity).
CollisionPreventionResult prevent_collision(const Eigen::Vector3d& v_desired_body_mps,
                                            const PointCloud& cloud_body,
                                            const CollisionPreventionConfig& config = {});

/// λ for a nearest frustum distance (1 when nullopt). Assumes a validated config.
double attenuation_factor(std::optional<double> d_o_m, const CollisionPreventionConfig& config);

/// The frustum along a desired velocity (see the file comment); nullopt for a zero velocity.
struct Frustum {
    Eigen::Vector3d axis_f = Eigen::Vector3d::UnitX();        ///< unit, along v_ud
    Eigen::Vector3d horizontal_h = Eigen::Vector3d::UnitY();  ///< unit, ⟂ f and body z
    Eigen::Vector3d vertical_u = Eigen::Vector3d::UnitZ();    ///< unit, f × h
    double near_m = 0.0;
    double far_m = 0.0;
    double tan_half_h = 0.0;
    double tan_half_v = 0.0;

    bool contains(const Eigen::Vector3d& p_body) const {
        const double a = p_body.dot(axis_f);
        return a >= near_m && a <= far_m && std::abs(p_body.dot(horizontal_h)) <= tan_half_h * a &&
               std::abs(p_body.dot(vertical_u)) <= tan_half_v * a;
    }
};
std::optional<Frustum> make_frustum(const Eigen::Vector3d& v_desired_body_mps,
                                    const CollisionPreventionConfig& config);

/// One line for logs, e.g. "attenuated: d_o = 1.21 m, lambda = 0.34; repelled by 12 points
/// closer than d_min = 0.80 m (|v_rep| = 0.05 m/s)".
std::string describe(const CollisionPreventionResult& result,
                     const CollisionPreventionConfig& config);
std::string_view to_string(AttenuationStatus status);

}  // namespace scantling::safety
