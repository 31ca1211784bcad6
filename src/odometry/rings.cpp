#include <scantling/core/error.hpp>
#include <scantling/odometry/rings.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>

#include <fmt/format.h>

namespace scantling::odometry {
namespace {

using Indices = std::vector<std::uint32_t>;
constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr std::size_t kGrain = 8192;  // points per parallel chunk
// Empty elevation bins (each a quarter of min_ring_gap_rad) that separate two bands.
constexpr int kGapBins = 3;
constexpr int kBinsPerGap = 4;
// Scan order: most segments (lasers) considered, and the least |Kendall's τ| between their
// file order and elevations (the real KITTI-like sweeps: −1; an HDL-64 with random ±0.2 m
// beam offsets seen at 4–60 m: −0.99; a shuffled cloud: thousands of segments).
constexpr std::size_t kMaxScanRings = 1024;
constexpr double kMinTrend = 0.8;

/// A difference of two azimuths in [−π, π], wrapped back into [−π, π].
double wrap_pi(double angle_rad) {
    if (angle_rad > kPi) return angle_rad - kTwoPi;
    return angle_rad < -kPi ? angle_rad + kTwoPi : angle_rad;
}

/// atan2(y, x) within 2e-6 rad (a degree-11 odd minimax polynomial on [0, 1] after octant
/// reduction): std::atan2 was a third of the ring organisation's time on a 124k-point sweep.
double fast_atan2(double y, double x) {
    const double ax = std::abs(x);
    const double ay = std::abs(y);
    const bool steep = ay > ax;
    const double t = steep ? ax / ay : (ax == 0.0 ? 0.0 : ay / ax);
    const double s = t * t;
    double angle =
        t * (0.99997726 +
             s * (-0.33262347 +
                  s * (0.19354346 + s * (-0.11643287 + s * (0.05265332 + s * -0.01172120)))));
    if (steep) angle = kPi / 2 - angle;
    if (x < 0.0) angle = kPi - angle;
    return std::copysign(angle, y);
}

struct Angles {
    std::vector<float> azimuth_rad;    // NaN: not usable
    std::vector<float> tan_elevation;  // z / |(x, y)|, monotone in the elevation
};

Angles compute_angles(const PointCloud& sweep, const ParallelConfig& parallel) {
    Angles a{std::vector<float>(sweep.size(), kNaN), std::vector<float>(sweep.size(), kNaN)};
    parallel_for(parallel, sweep.size(), kGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const Eigen::Vector3d& p = sweep.points[i];
            const double rho = std::sqrt(p.x() * p.x() + p.y() * p.y());
            if (!p.allFinite() || rho == 0.0) continue;
            a.azimuth_rad[i] = static_cast<float>(fast_atan2(p.y(), p.x()));
            a.tan_elevation[i] = static_cast<float>(p.z() / rho);
        }
    });
    return a;
}

Indices valid_indices(const Angles& angles) {
    Indices valid;
    valid.reserve(angles.azimuth_rad.size());
    for (std::size_t i = 0; i < angles.azimuth_rad.size(); ++i) {
        if (!std::isnan(angles.azimuth_rad[i])) valid.push_back(static_cast<std::uint32_t>(i));
    }
    return valid;
}

std::vector<Indices> from_ring_field(const PointCloud& sweep, const Indices& valid,
                                     const RingOrganizerConfig& config) {
    if (!sweep.has_rings()) {
        throw InputError(
            "organize_rings: rings.source = ring_field but the cloud has no ring field");
    }
    int count = config.num_rings;
    if (count == 0) {
        for (std::uint32_t i : valid) count = std::max(count, sweep.rings[i] + 1);
    }
    std::vector<Indices> rings(static_cast<std::size_t>(count));
    for (std::uint32_t i : valid) {
        if (sweep.rings[i] < count) rings[sweep.rings[i]].push_back(i);
    }
    return rings;
}

/// Ring-major firing order: a ring ends where the azimuth from the sweep start (in the
/// direction of rotation) falls back by more than half a turn below the last two points (two,
/// so one stray return cannot end a ring).
std::vector<Indices> split_scan_order(const Angles& angles, const Indices& valid,
                                      double start_azimuth_rad) {
    const auto& az = angles.azimuth_rad;
    std::size_t forward = 0;
    std::size_t backward = 0;
    for (std::size_t k = 1; k < valid.size(); ++k) {
        const double step = wrap_pi(az[valid[k]] - az[valid[k - 1]]);
        if (std::abs(step) >= kPi / 4) continue;  // a ring change or a gap, not a step
        forward += step > 0.0;
        backward += step < 0.0;
    }
    const double direction = forward >= backward ? 1.0 : -1.0;
    const double start = std::isnan(start_azimuth_rad) ? az[valid[0]] : start_azimuth_rad;
    std::vector<Indices> segments(1);
    double last = 0.0;
    double before_last = 0.0;
    for (std::size_t k = 0; k < valid.size(); ++k) {
        double a = direction * wrap_pi(az[valid[k]] - start);
        if (a < 0.0) a += kTwoPi;
        if (k == 0) last = before_last = a;
        if (last - a > kPi && before_last - a > kPi) segments.emplace_back();
        segments.back().push_back(valid[k]);
        before_last = last;
        last = a;
    }
    return segments;
}

/// Median of (at most ~256 evenly spaced samples of) the ring's tan(elevation): enough to tell
/// rings 0.1° apart, at a fraction of the cost.
float median_tan_elevation(const Indices& ring, const Angles& angles) {
    const std::size_t stride = ring.size() / 256 + 1;
    std::vector<float> values;
    for (std::size_t k = 0; k < ring.size(); k += stride) {
        values.push_back(angles.tan_elevation[ring[k]]);
    }
    const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), mid, values.end());
    return *mid;
}

/// Kendall's τ between the file order of the scan-order segments and their elevations: ±1
/// when lasers are stored bottom to top / top to bottom, ~0 when the segments are not lasers.
/// A rank statistic, because per-laser vertical offsets can bias a ring's median elevation
/// past its neighbour's. 0 for more than kMaxScanRings segments (O(S²)).
double elevation_trend(const std::vector<Indices>& segments, const Angles& angles) {
    if (segments.size() < 2 || segments.size() > kMaxScanRings) return 0.0;
    std::vector<float> medians(segments.size());
    for (std::size_t s = 0; s < segments.size(); ++s) {
        medians[s] = median_tan_elevation(segments[s], angles);
    }
    long long concordance = 0;
    for (std::size_t i = 0; i < medians.size(); ++i) {
        for (std::size_t j = i + 1; j < medians.size(); ++j) {
            concordance += (medians[j] > medians[i]) - (medians[j] < medians[i]);
        }
    }
    const double n = static_cast<double>(medians.size());
    const double pairs = n * (n - 1.0) / 2.0;
    return static_cast<double>(concordance) / pairs;
}

struct Band {
    int lo = 0;  // first and last elevation bin
    int hi = 0;
    std::size_t count = 0;
};

/// Longest run of empty bins strictly inside the band: {length, first bin}.
std::pair<int, int> widest_inner_gap(const Band& band, const std::vector<std::size_t>& counts) {
    std::pair<int, int> best{0, 0};
    for (int b = band.lo + 1, run = 0; b < band.hi; ++b) {
        run = counts[b] == 0 ? run + 1 : 0;
        if (run > best.first) best = {run, b - run + 1};
    }
    return best;
}

/// Merges the closest neighbouring bands or splits the widest inner gaps until `target` bands.
void fit_band_count(std::vector<Band>& bands, const std::vector<std::size_t>& counts, int target) {
    while (bands.size() > static_cast<std::size_t>(target)) {
        std::size_t best = 0;
        for (std::size_t i = 1; i + 1 < bands.size(); ++i) {
            if (bands[i + 1].lo - bands[i].hi < bands[best + 1].lo - bands[best].hi) best = i;
        }
        bands[best] = {bands[best].lo, bands[best + 1].hi,
                       bands[best].count + bands[best + 1].count};
        bands.erase(bands.begin() + static_cast<std::ptrdiff_t>(best) + 1);
    }
    while (!bands.empty() && bands.size() < static_cast<std::size_t>(target)) {
        std::size_t best = 0;
        std::pair<int, int> gap{0, 0};
        for (std::size_t i = 0; i < bands.size(); ++i) {
            const auto g = widest_inner_gap(bands[i], counts);
            if (g.first > gap.first) std::tie(best, gap) = std::tie(i, g);
        }
        if (gap.first == 0) return;  // nothing left to split
        const Band whole = bands[best];
        bands[best].hi = gap.second - 1;
        bands.insert(bands.begin() + static_cast<std::ptrdiff_t>(best) + 1,
                     Band{gap.second + gap.first, whole.hi, 0});
    }
}

std::vector<Indices> cluster_elevations(const Angles& angles, const Indices& valid,
                                        const RingOrganizerConfig& config) {
    const double bin_rad = config.min_ring_gap_rad / kBinsPerGap;
    const int num_bins = static_cast<int>(kPi / bin_rad) + 2;
    std::vector<int> bin_of(angles.azimuth_rad.size(), -1);
    std::vector<std::size_t> counts(static_cast<std::size_t>(num_bins), 0);
    for (std::uint32_t i : valid) {
        const double elevation = std::atan(static_cast<double>(angles.tan_elevation[i]));
        bin_of[i] = std::clamp(static_cast<int>((elevation + kPi / 2) / bin_rad), 0, num_bins - 1);
        ++counts[bin_of[i]];
    }
    std::vector<Band> bands;
    for (int b = 0, empty_run = kGapBins; b < num_bins; ++b) {
        if (counts[b] == 0) {
            ++empty_run;
            continue;
        }
        if (empty_run >= kGapBins) bands.push_back({b, b, 0});
        bands.back().hi = b;
        bands.back().count += counts[b];
        empty_run = 0;
    }
    std::erase_if(bands, [&](const Band& band) {
        return band.count < static_cast<std::size_t>(config.min_ring_points);
    });
    if (config.num_rings > 0) fit_band_count(bands, counts, config.num_rings);
    std::vector<int> band_of_bin(counts.size(), -1);
    for (std::size_t r = 0; r < bands.size(); ++r) {
        for (int b = bands[r].lo; b <= bands[r].hi; ++b) band_of_bin[b] = static_cast<int>(r);
    }
    std::vector<Indices> rings(bands.size());
    for (std::uint32_t i : valid) {
        if (const int r = band_of_bin[bin_of[i]]; r >= 0) rings[r].push_back(i);
    }
    return rings;
}

/// True when the points already sweep the ring once in one direction (small backward steps
/// allowed: per-laser azimuth offsets make near and far returns of one column differ slightly).
bool sweeps_monotonically(const Indices& ring, const std::vector<float>& az) {
    double travel = 0.0;
    double net = 0.0;
    for (std::size_t k = 1; k < ring.size(); ++k) {
        const double step = wrap_pi(az[ring[k]] - az[ring[k - 1]]);
        travel += std::abs(step);
        net += step;
    }
    return travel <= 1.25 * kTwoPi && std::abs(net) >= 0.8 * travel;
}

void order_rings(std::vector<Indices>& rings, const std::vector<float>& az,
                 const ParallelConfig& parallel) {
    parallel_for(parallel, rings.size(), 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) {
            if (sweeps_monotonically(rings[r], az)) continue;
            std::sort(rings[r].begin(), rings[r].end(), [&](std::uint32_t a, std::uint32_t b) {
                return az[a] < az[b] || (az[a] == az[b] && a < b);
            });
        }
    });
}

}  // namespace

std::string_view to_string(RingSource source) {
    switch (source) {
        case RingSource::kAuto:
            return "auto";
        case RingSource::kRingField:
            return "ring_field";
        case RingSource::kScanOrder:
            return "scan_order";
        case RingSource::kElevation:
            return "elevation";
    }
    return "unknown";
}

RingSource ring_source_from_string(std::string_view name, std::string_view field) {
    for (RingSource s : {RingSource::kAuto, RingSource::kRingField, RingSource::kScanOrder,
                         RingSource::kElevation}) {
        if (name == to_string(s)) return s;
    }
    throw ConfigError(
        fmt::format("{} = \"{}\", expected one of auto, ring_field, scan_order, "
                    "elevation",
                    field, name));
}

void RingOrganizerConfig::validate(std::string_view prefix) const {
    if (num_rings < 0 || num_rings > std::numeric_limits<std::uint16_t>::max()) {
        throw ConfigError(
            fmt::format("{}.num_rings = {}, expected in [0, 65535]", prefix, num_rings));
    }
    // The upper bound keeps the elevation histogram at >= 4 bins over the half turn.
    if (!(min_ring_gap_rad > 0.0 && min_ring_gap_rad < kPi / 4)) {
        throw ConfigError(fmt::format("{}.min_ring_gap_rad = {}, expected in (0, pi/4)", prefix,
                                      min_ring_gap_rad));
    }
    if (!std::isnan(scan_start_azimuth_rad) && std::abs(scan_start_azimuth_rad) > kPi) {
        throw ConfigError(
            fmt::format("{}.scan_start_azimuth_rad = {}, expected NaN (the first "
                        "return) or in [-pi, pi]",
                        prefix, scan_start_azimuth_rad));
    }
    if (min_ring_points < 1) {
        throw ConfigError(
            fmt::format("{}.min_ring_points = {}, expected >= 1", prefix, min_ring_points));
    }
}

RingLayout organize_rings(const PointCloud& sweep, const RingOrganizerConfig& config,
                          const ParallelConfig& parallel) {
    config.validate();
    parallel.validate();
    check_consistent(sweep, "organize_rings sweep");
    if (sweep.size() > std::numeric_limits<std::uint32_t>::max()) {
        throw InputError(
            fmt::format("organize_rings: {} points, at most 2^32 - 1 supported", sweep.size()));
    }
    Angles angles = compute_angles(sweep, parallel);
    const Indices valid = valid_indices(angles);
    RingLayout layout;
    RingSource source = config.source;
    if (source == RingSource::kAuto && sweep.has_rings()) source = RingSource::kRingField;
    if (source == RingSource::kRingField) {
        layout.rings = from_ring_field(sweep, valid, config);
    } else if (source == RingSource::kScanOrder || source == RingSource::kAuto) {
        std::vector<Indices> segments =
            valid.empty() ? std::vector<Indices>{}
                          : split_scan_order(angles, valid, config.scan_start_azimuth_rad);
        std::erase_if(segments, [&](const Indices& s) {
            return s.size() < static_cast<std::size_t>(config.min_ring_points);
        });
        // Rings are the segments in file order, lowest first; accepted (kAuto) when the file
        // order follows the elevation and the count is as expected.
        const double trend = elevation_trend(segments, angles);
        const bool count_ok =
            config.num_rings == 0 || segments.size() == static_cast<std::size_t>(config.num_rings);
        if (source == RingSource::kScanOrder || (std::abs(trend) >= kMinTrend && count_ok)) {
            source = RingSource::kScanOrder;
            if (trend < 0.0) std::reverse(segments.begin(), segments.end());
            layout.rings = std::move(segments);
        } else {
            source = RingSource::kElevation;
        }
    }
    if (source == RingSource::kElevation) layout.rings = cluster_elevations(angles, valid, config);
    // Scan-order rings are in firing order by construction.
    if (source != RingSource::kScanOrder) order_rings(layout.rings, angles.azimuth_rad, parallel);
    std::size_t kept = 0;
    for (const Indices& ring : layout.rings) kept += ring.size();
    layout.num_dropped = sweep.size() - kept;
    layout.source = source;
    layout.azimuths_rad = std::move(angles.azimuth_rad);
    return layout;
}

}  // namespace scantling::odometry
