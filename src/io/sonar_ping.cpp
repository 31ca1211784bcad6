#include <scantling/core/error.hpp>
#include <scantling/io/sonar_ping.hpp>

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace scantling::io {
namespace {

[[noreturn]] void fail(std::string_view prefix, std::string_view field, const std::string& what) {
    throw InputError(fmt::format("{}.{}: {}", prefix, field, what));
}

void require(bool ok, std::string_view prefix, std::string_view field, const std::string& what) {
    if (!ok) fail(prefix, field, what);
}

// Strictly increasing finite samples: the beam and bin axes must be monotone for an edge
// image in which neighbouring pixels are neighbouring bearings and ranges.
void require_axis(const std::vector<double>& axis, std::string_view prefix,
                  std::string_view field) {
    // The messages are formatted only on failure: axis[i − 1] does not exist for i = 0, and a
    // message per element would cost more than the check.
    for (std::size_t i = 0; i < axis.size(); ++i) {
        if (!std::isfinite(axis[i])) {
            fail(prefix, fmt::format("{}[{}]", field, i),
                 fmt::format("{}, expected finite", axis[i]));
        }
        if (i > 0 && !(axis[i] > axis[i - 1])) {
            fail(prefix, fmt::format("{}[{}]", field, i),
                 fmt::format("{} after {}, expected strictly increasing", axis[i], axis[i - 1]));
        }
    }
}

void require_sizes(const SonarPing& ping, std::string_view prefix) {
    require(ping.num_beams >= 1, prefix, "num_beams",
            fmt::format("= {}, expected >= 1", ping.num_beams));
    require(ping.num_bins >= 1, prefix, "num_bins",
            fmt::format("= {}, expected >= 1", ping.num_bins));
    const std::size_t cells = static_cast<std::size_t>(ping.num_beams) * ping.num_bins;
    require(
        ping.intensity.size() == cells, prefix, "intensity",
        fmt::format("{} values, expected num_beams · num_bins = {}", ping.intensity.size(), cells));
    require(ping.bearings_rad.size() == static_cast<std::size_t>(ping.num_beams), prefix,
            "bearings_rad",
            fmt::format("{} values, expected num_beams = {}", ping.bearings_rad.size(),
                        ping.num_beams));
    require(ping.ranges_m.size() == static_cast<std::size_t>(ping.num_bins), prefix, "ranges_m",
            fmt::format("{} values, expected num_bins = {}", ping.ranges_m.size(), ping.num_bins));
}

}  // namespace

void SonarPing::validate(std::string_view prefix) const {
    require_sizes(*this, prefix);
    require(std::isfinite(min_range_m) && min_range_m >= 0.0, prefix, "min_range_m",
            fmt::format("= {}, expected finite >= 0", min_range_m));
    require(std::isfinite(max_range_m) && max_range_m > min_range_m, prefix, "max_range_m",
            fmt::format("= {}, expected finite > min_range_m = {}", max_range_m, min_range_m));
    require(std::isfinite(horizontal_fov_rad) && horizontal_fov_rad > 0.0, prefix,
            "horizontal_fov_rad", fmt::format("= {}, expected finite > 0", horizontal_fov_rad));
    require_axis(bearings_rad, prefix, "bearings_rad");
    require_axis(ranges_m, prefix, "ranges_m");
    for (std::size_t i = 0; i < intensity.size(); ++i) {
        if (std::isnan(intensity[i])) {
            fail(prefix,
                 fmt::format("intensity[{}] (beam {}, bin {})", i, i / num_bins, i % num_bins),
                 "NaN, expected a number");
        }
    }
}

}  // namespace scantling::io
