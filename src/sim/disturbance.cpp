#include <scantling/core/error.hpp>
#include <scantling/sim/disturbance.hpp>

#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <cmath>

namespace scantling::sim {

void GustConfig::validate(std::string_view prefix) const {
    if (!mean.allFinite()) {
        throw ConfigError(fmt::format("{}.mean = ({}, {}, {}), expected finite", prefix, mean.x(),
                                      mean.y(), mean.z()));
    }
    if (!sigma.allFinite() || sigma.minCoeff() < 0.0) {
        throw ConfigError(fmt::format("{}.sigma = ({}, {}, {}), expected finite and >= 0", prefix,
                                      sigma.x(), sigma.y(), sigma.z()));
    }
    detail::require_positive(prefix, "correlation_time_s", correlation_time_s);
}

GustProcess::GustProcess(const GustConfig& config, std::uint64_t seed, std::string_view prefix)
    : config_(config), rng_(seed) {
    config_.validate(prefix);
    for (int i = 0; i < 3; ++i) gust_[i] = config_.sigma[i] * rng_.normal();
}

void GustProcess::step(double dt_s) {
    if (!(std::isfinite(dt_s) && dt_s > 0.0)) {
        throw InputError(fmt::format("GustProcess::step: dt_s = {}, expected > 0", dt_s));
    }
    const double decay = std::exp(-dt_s / config_.correlation_time_s);
    const double drive = std::sqrt(1.0 - decay * decay);
    for (int i = 0; i < 3; ++i)
        gust_[i] = decay * gust_[i] + drive * config_.sigma[i] * rng_.normal();
}

}  // namespace scantling::sim
