#include <scantling/core/error.hpp>
#include <scantling/sim/speed_profile.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

/// Ramp time per unit of peak speed over max_accel: how many times slower than a bang-bang
/// ramp a shape reaches its speed at the same peak acceleration.
double ramp_factor(ProfileShape shape) { return shape == ProfileShape::kSmooth ? 2.0 : 1.0; }

void require_limit(double value, const char* name) {
    if (!(std::isfinite(value) && value > 0.0)) {
        throw InputError(fmt::format("plan_rest_to_rest: {} = {}, expected > 0", name, value));
    }
}

/// Acceleration ramp from rest to `peak` over `ramp_s`, at time t in [0, ramp_s].
ProfileSample ramp_up(ProfileShape shape, double peak, double ramp_s, double t) {
    const double a_mean = peak / ramp_s;
    if (shape == ProfileShape::kTrapezoidal) return {0.5 * a_mean * t * t, a_mean * t, a_mean};
    const double w = 2.0 * std::numbers::pi / ramp_s;
    const double s = a_mean * (0.5 * t * t + (std::cos(w * t) - 1.0) / (w * w));
    return {s, a_mean * (t - std::sin(w * t) / w), a_mean * (1.0 - std::cos(w * t))};
}

}  // namespace

RestToRestProfile plan_rest_to_rest(double distance, double max_speed, double max_accel,
                                    ProfileShape shape) {
    if (!(std::isfinite(distance) && distance >= 0.0)) {
        throw InputError(fmt::format("plan_rest_to_rest: distance = {}, expected >= 0", distance));
    }
    require_limit(max_speed, "max_speed");
    require_limit(max_accel, "max_accel");
    RestToRestProfile p;
    p.distance = distance;
    p.shape = shape;
    if (distance == 0.0) return p;
    const double k = ramp_factor(shape);
    // Each ramp covers peak · ramp_time / 2 = k peak² / (2 a_max).
    p.peak_speed = std::min(max_speed, std::sqrt(distance * max_accel / k));
    p.ramp_time_s = k * p.peak_speed / max_accel;
    p.cruise_time_s = std::max(0.0, (distance - p.peak_speed * p.ramp_time_s) / p.peak_speed);
    return p;
}

ProfileSample sample(const RestToRestProfile& p, double t_s) {
    const double total_s = p.duration_s();
    if (p.distance == 0.0 || t_s <= 0.0) return {};
    if (t_s >= total_s) return {p.distance, 0.0, 0.0};
    if (t_s < p.ramp_time_s) return ramp_up(p.shape, p.peak_speed, p.ramp_time_s, t_s);
    if (t_s <= p.ramp_time_s + p.cruise_time_s) {
        const double ramp_distance = 0.5 * p.peak_speed * p.ramp_time_s;
        return {ramp_distance + p.peak_speed * (t_s - p.ramp_time_s), p.peak_speed, 0.0};
    }
    // Deceleration mirrors the ramp in time and distance.
    const ProfileSample m = ramp_up(p.shape, p.peak_speed, p.ramp_time_s, total_s - t_s);
    return {p.distance - m.s, m.ds, -m.dds};
}

}  // namespace scantling::sim
