#pragma once
/// @file
/// The ConfigError checks every algorithm's `Config::validate` uses, so that an impossible
/// setting reads the same in every module: "<prefix>.<field> = <value>, expected <what>".

#include <cmath>
#include <cstddef>
#include <string_view>

#include <fmt/format.h>

#include <scantling/core/error.hpp>

namespace scantling::config_checks {

/// Throws ConfigError("<prefix>.<field> = <value>, expected <expected>") unless `ok`.
inline void require(bool ok, std::string_view prefix, std::string_view field, double value,
                    std::string_view expected) {
    if (!ok)
        throw ConfigError(fmt::format("{}.{} = {}, expected {}", prefix, field, value, expected));
}

/// Finite and > 0.
inline void require_positive(double value, std::string_view prefix, std::string_view field) {
    require(std::isfinite(value) && value > 0.0, prefix, field, value, "finite > 0");
}

/// Finite and >= 0.
inline void require_non_negative(double value, std::string_view prefix, std::string_view field) {
    require(std::isfinite(value) && value >= 0.0, prefix, field, value, "finite >= 0");
}

/// An integer setting of at least `minimum`.
inline void require_at_least(long long value, long long minimum, std::string_view prefix,
                             std::string_view field) {
    if (value < minimum) {
        throw ConfigError(fmt::format("{}.{} = {}, expected >= {}", prefix, field, value, minimum));
    }
}

/// A count setting (std::size_t) of at least `minimum`, compared without wrapping.
inline void require_count_at_least(std::size_t value, std::size_t minimum, std::string_view prefix,
                                   std::string_view field) {
    if (value < minimum) {
        throw ConfigError(fmt::format("{}.{} = {}, expected >= {}", prefix, field, value, minimum));
    }
}

/// 0 < value < 1.
inline void require_open_unit(double value, std::string_view prefix, std::string_view field) {
    require(value > 0.0 && value < 1.0, prefix, field, value, "in (0, 1)");
}

}  // namespace scantling::config_checks
