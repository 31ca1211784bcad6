#pragma once
// Evenly spaced stations 0 … length with spacing at most `max_spacing` (the sweep's lines, the
// vertical inspection's legs): coverage never gets coarser than asked, and the far edge is
// always flown.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include <scantling/core/error.hpp>

namespace scantling::planning::detail {

// More lines than this is a unit mistake (mm for m), not a mission: refused before allocating.
inline constexpr std::size_t kMaxStations = 10000;
// A length a hair over a multiple of the spacing (8.000000001 / 1) adds no line.
inline constexpr double kRelativeSlack = 1e-9;

/// Assumes length > 0 and spacing > 0 (validated). Throws ConfigError naming `field` when more
/// than kMaxStations would be needed.
inline std::vector<double> even_stations(double length_m, double max_spacing_m,
                                         std::string_view prefix, std::string_view field) {
    const double segments = std::ceil(length_m / max_spacing_m * (1.0 - kRelativeSlack));
    if (!(segments < static_cast<double>(kMaxStations))) {
        throw ConfigError(fmt::format("{}.{} = {}, expected at most {} lines over {} m", prefix,
                                      field, max_spacing_m, kMaxStations, length_m));
    }
    const std::size_t n = std::max<std::size_t>(1, static_cast<std::size_t>(segments));
    std::vector<double> stations(n + 1);
    for (std::size_t i = 0; i <= n; ++i) stations[i] = length_m * static_cast<double>(i) / n;
    return stations;
}

}  // namespace scantling::planning::detail
