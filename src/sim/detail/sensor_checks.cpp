#include "sensor_checks.hpp"

#include <scantling/core/error.hpp>

#include <fmt/format.h>

#include <cmath>

namespace scantling::sim::detail {

void require(bool ok, std::string_view prefix, std::string_view field, double value,
             std::string_view expected) {
    if (!ok) {
        throw ConfigError(fmt::format("{}.{} = {}, expected {}", prefix, field, value, expected));
    }
}

void require_positive(std::string_view prefix, std::string_view field, double value) {
    require(std::isfinite(value) && value > 0.0, prefix, field, value, "> 0");
}

void require_non_negative(std::string_view prefix, std::string_view field, double value) {
    require(std::isfinite(value) && value >= 0.0, prefix, field, value, ">= 0");
}

void require_probability(std::string_view prefix, std::string_view field, double value) {
    require(value >= 0.0 && value <= 1.0, prefix, field, value, "in [0, 1]");
}

void require_range_window(std::string_view prefix, double min_range_m, double max_range_m) {
    require_non_negative(prefix, "min_range_m", min_range_m);
    require(std::isfinite(max_range_m) && max_range_m > min_range_m, prefix, "max_range_m",
            max_range_m, fmt::format("finite and > min_range_m = {}", min_range_m));
}

void require_angle(std::string_view prefix, std::string_view field, double value_rad,
                   double max_rad) {
    require(value_rad > 0.0 && value_rad < max_rad, prefix, field, value_rad,
            fmt::format("in (0, {}) rad", max_rad));
}

std::string sub(std::string_view prefix, std::string_view field) {
    return fmt::format("{}.{}", prefix, field);
}

}  // namespace scantling::sim::detail
