#pragma once
/// @file
/// One-dimensional rest-to-rest motion profiles: cover a distance starting and ending at rest
/// within a speed and an acceleration limit. The building block of scripted trajectories
/// (SPEC §10): waypoint legs, turns on the spot, lawnmower sweeps.
///
/// Shapes (both symmetric: acceleration phase, optional cruise, mirrored deceleration):
/// - `kTrapezoidal`: constant ±a_max, so the acceleration jumps (infinite jerk) at phase
///   boundaries; ramp time T_a = v_peak / a_max.
/// - `kSmooth`: raised-cosine acceleration a(t) = (v_peak / T_a)(1 − cos(2π t / T_a)) with
///   T_a = 2 v_peak / a_max, so acceleration and jerk are continuous (s(t) is C³ in the
///   ramps, C² overall): what a simulated IMU wants.
/// A short distance never reaches the speed limit: v_peak = sqrt(D a_max / k), k = 1
/// (trapezoidal) or 2 (smooth), and there is no cruise phase.
///
/// All functions are pure and O(1); determinism and thread-safety are trivial.

namespace scantling::sim {

enum class ProfileShape { kTrapezoidal, kSmooth };

/// Position, speed and acceleration along the profile at one time.
struct ProfileSample {
    double s = 0.0;    ///< distance covered, in the profile's unit (metres, radians, ...)
    double ds = 0.0;   ///< its first time derivative, unit/s
    double dds = 0.0;  ///< its second time derivative, unit/s²
};

/// A planned rest-to-rest profile. Build it with `plan_rest_to_rest`.
struct RestToRestProfile {
    double distance = 0.0;  ///< D >= 0
    double peak_speed = 0.0;
    double ramp_time_s = 0.0;    ///< duration of the acceleration (and of the deceleration)
    double cruise_time_s = 0.0;  ///< duration at peak speed
    ProfileShape shape = ProfileShape::kSmooth;

    double duration_s() const { return 2.0 * ramp_time_s + cruise_time_s; }
};

/// Fastest profile covering `distance` (>= 0) with |ds| <= max_speed and |dds| <= max_accel.
/// A zero distance gives a zero-duration profile. Throws InputError unless distance is
/// finite and >= 0 and both limits are finite and > 0.
RestToRestProfile plan_rest_to_rest(double distance, double max_speed, double max_accel,
                                    ProfileShape shape = ProfileShape::kSmooth);

/// The profile at time `t_s` from its start; clamped to rest at s = 0 before the start and
/// at s = distance after the end.
ProfileSample sample(const RestToRestProfile& profile, double t_s);

}  // namespace scantling::sim
