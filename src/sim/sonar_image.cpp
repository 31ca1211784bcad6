#include <scantling/core/error.hpp>
#include <scantling/sim/multibeam_sonar.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

constexpr std::size_t kMaxCartesianPixels = std::size_t{1} << 26;

void check_image(const SonarImage& image) {
    const bool ok =
        image.num_beams >= 1 && image.num_bins >= 1 &&
        image.intensity.size() == static_cast<std::size_t>(image.num_beams) * image.num_bins &&
        image.bearings_rad.size() == static_cast<std::size_t>(image.num_beams) &&
        image.ranges_m.size() == static_cast<std::size_t>(image.num_bins) &&
        image.max_range_m > image.min_range_m;
    if (!ok) {
        throw InputError(fmt::format(
            "sonar image: {} beams × {} bins with {} intensities, {} bearings, {} ranges and "
            "range [{}, {}] m, expected consistent sizes, max_range_m > min_range_m and a fan",
            image.num_beams, image.num_bins, image.intensity.size(), image.bearings_rad.size(),
            image.ranges_m.size(), image.min_range_m, image.max_range_m));
    }
}

}  // namespace

int SonarImage::bin_of(double range_m) const {
    if (!(range_m >= min_range_m && range_m < max_range_m)) return -1;
    const double bin_m = (max_range_m - min_range_m) / num_bins;
    return std::min(num_bins - 1, static_cast<int>((range_m - min_range_m) / bin_m));
}

int SonarImage::beam_of(double bearing_rad) const {
    if (!std::isfinite(bearing_rad) || num_beams < 1) return -1;
    const double k =
        std::floor((bearing_rad + 0.5 * horizontal_fov_rad) / horizontal_fov_rad * num_beams);
    if (k < 0.0 || k >= num_beams) return -1;
    return static_cast<int>(k);
}

CartesianSonarImage to_cartesian(const SonarImage& image, double resolution_m) {
    check_image(image);
    if (!(std::isfinite(resolution_m) && resolution_m > 0.0)) {
        throw InputError(
            fmt::format("to_cartesian: resolution_m = {}, expected > 0", resolution_m));
    }
    const double half_fov =
        std::max(std::abs(image.bearings_rad.front()), std::abs(image.bearings_rad.back()));
    CartesianSonarImage out;
    out.resolution_m = resolution_m;
    out.x_max_m = image.max_range_m;
    out.y_max_m = image.max_range_m * std::sin(std::min(half_fov, std::numbers::pi / 2.0));
    const double width = std::ceil(2.0 * out.y_max_m / resolution_m);
    const double height = std::ceil(out.x_max_m / resolution_m);
    if (width * height > static_cast<double>(kMaxCartesianPixels)) {
        throw InputError(
            fmt::format("to_cartesian: {} × {} pixels at resolution_m = {}, expected "
                        "at most 2^26",
                        width, height, resolution_m));
    }
    out.width = std::max(1, static_cast<int>(width));
    out.height = std::max(1, static_cast<int>(height));
    out.intensity.assign(static_cast<std::size_t>(out.width) * out.height, 0.0F);
    for (int v = 0; v < out.height; ++v) {
        const double x = out.x_max_m - (v + 0.5) * resolution_m;
        for (int u = 0; u < out.width; ++u) {
            const double y = out.y_max_m - (u + 0.5) * resolution_m;
            const int bin = image.bin_of(std::hypot(x, y));
            const int beam = image.beam_of(std::atan2(y, x));
            if (bin >= 0 && beam >= 0) {
                out.intensity[static_cast<std::size_t>(v) * out.width + u] = image.at(beam, bin);
            }
        }
    }
    return out;
}

}  // namespace scantling::sim
