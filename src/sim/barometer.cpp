#include <scantling/sim/barometer.hpp>

#include <fmt/format.h>

#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/sim/sensor_mount.hpp>

#include "detail/sensor_checks.hpp"

namespace scantling::sim {

void BarometerConfig::validate(std::string_view prefix) const {
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require_non_negative(prefix, "altitude_sigma_m", altitude_sigma_m);
    detail::require_non_negative(prefix, "initial_bias_sigma_m", initial_bias_sigma_m);
    detail::require_non_negative(prefix, "bias_random_walk_m_per_sqrt_s",
                                 bias_random_walk_m_per_sqrt_s);
    validate_mount(T_body_sensor, prefix);
}

BarometerConfig noiseless(BarometerConfig config) {
    config.altitude_sigma_m = 0.0;
    config.initial_bias_sigma_m = 0.0;
    config.bias_random_walk_m_per_sqrt_s = 0.0;
    return config;
}

Barometer::Barometer(BarometerConfig config, Rng& rng) : config_(std::move(config)) {
    config_.validate();
    bias_m_ = rng.normal(0.0, config_.initial_bias_sigma_m);
}

BarometerSample Barometer::measure(const Eigen::Isometry3d& T_world_body, Rng& rng,
                                   double stamp_s) {
    if (!T_world_body.matrix().allFinite() || !std::isfinite(stamp_s)) {
        throw InputError(fmt::format("barometer: vehicle pose at t = {} s is not finite", stamp_s));
    }
    if (has_previous_ && stamp_s < previous_stamp_s_) {
        throw InputError(fmt::format("barometer: stamp {} s is before the previous {} s", stamp_s,
                                     previous_stamp_s_));
    }
    const double dt_s = has_previous_ ? stamp_s - previous_stamp_s_ : 0.0;
    bias_m_ += rng.normal(0.0, config_.bias_random_walk_m_per_sqrt_s * std::sqrt(dt_s));
    has_previous_ = true;
    previous_stamp_s_ = stamp_s;
    const double z_m = (T_world_body * config_.T_body_sensor).translation().z();
    return {.stamp_s = stamp_s,
            .altitude_m = z_m + bias_m_ + rng.normal(0.0, config_.altitude_sigma_m)};
}

}  // namespace scantling::sim
