#pragma once
// ConfigError checks shared by the localisation configs (private).
#include <fmt/format.h>

#include <cmath>
#include <string_view>

#include <scantling/core/error.hpp>

namespace scantling::localization::detail {

/// Throws ConfigError("<prefix>.<field> = <value>, expected <expected>") unless `ok`.
inline void require(bool ok, std::string_view prefix, std::string_view field, double value,
                    std::string_view expected) {
    if (!ok)
        throw ConfigError(fmt::format("{}.{} = {}, expected {}", prefix, field, value, expected));
}

inline void require_positive(double value, std::string_view prefix, std::string_view field) {
    require(std::isfinite(value) && value > 0.0, prefix, field, value, "finite > 0");
}

inline void require_non_negative(double value, std::string_view prefix, std::string_view field) {
    require(std::isfinite(value) && value >= 0.0, prefix, field, value, "finite >= 0");
}

}  // namespace scantling::localization::detail
