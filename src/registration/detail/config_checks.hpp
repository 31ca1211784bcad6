#pragma once
/// @file
/// ConfigError helpers shared by the registration configs (private).

#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include <scantling/core/error.hpp>

namespace scantling::registration::detail {

/// Throws ConfigError("<prefix>.<field> = <value>, expected finite > 0").
inline void require_positive(double value, std::string_view prefix, std::string_view field) {
    if (!(value > 0.0) || !std::isfinite(value)) {
        throw ConfigError(fmt::format("{}.{} = {}, expected finite > 0", prefix, field, value));
    }
}

/// Throws ConfigError("<prefix>.<field> = <value>, expected >= <minimum>").
inline void require_at_least(int value, int minimum, std::string_view prefix,
                             std::string_view field) {
    if (value < minimum) {
        throw ConfigError(fmt::format("{}.{} = {}, expected >= {}", prefix, field, value, minimum));
    }
}

/// Throws ConfigError unless 0 < value < 1.
inline void require_open_unit(double value, std::string_view prefix, std::string_view field) {
    if (!(value > 0.0 && value < 1.0)) {
        throw ConfigError(fmt::format("{}.{} = {}, expected in (0, 1)", prefix, field, value));
    }
}

}  // namespace scantling::registration::detail
