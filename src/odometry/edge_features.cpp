#include <scantling/core/error.hpp>
#include <scantling/odometry/edge_features.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>

#include <fmt/format.h>

namespace scantling::odometry {
namespace {

using Indices = std::vector<std::uint32_t>;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr float kNoCurvature = std::numeric_limits<float>::quiet_NaN();

/// |azimuth step| in [0, π] between two azimuths in [−π, π].
double abs_step(float from_rad, float to_rad) {
    const double step = std::abs(static_cast<double>(to_rad) - from_rad);
    return step > std::numbers::pi ? kTwoPi - step : step;
}

/// The ring's nominal azimuth resolution: the median step between consecutive points (of at
/// most ~256 evenly spread steps: a full median cost a third of the extraction).
double median_step_rad(const Indices& ring, const std::vector<float>& az) {
    if (ring.size() < 2) return std::numeric_limits<double>::infinity();
    const std::size_t stride = ring.size() / 256 + 1;
    std::vector<double> steps;
    for (std::size_t k = 1; k < ring.size(); k += stride) {
        steps.push_back(abs_step(az[ring[k - 1]], az[ring[k]]));
    }
    const auto mid = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
    std::nth_element(steps.begin(), mid, steps.end());
    return *mid;
}

/// What the end of a segment faces across its boundary.
enum class EndRole : std::uint8_t {
    kNone,        // inside a segment, or a plain cut (ring end, a surface leaving the gate)
    kSilhouette,  // missing returns or a farther surface behind: the outline of an object
    kOccluded,    // a nearer surface in front: this end moves with the viewpoint
};

/// The in-range points of one ring, in firing order, with the boundaries between them.
struct RingPoints {
    Indices index;  // into the sweep
    std::vector<double> range_m;
    std::vector<double> step_rad;          // azimuth step from the previous in-range point
    std::vector<std::uint8_t> adjacent;    // no return missing or gated out since the last point
    std::vector<std::uint8_t> starts;      // a segment starts here
    std::vector<EndRole> left, right;      // role of the boundary before / after the point
    std::vector<int> seg_first, seg_last;  // the point's segment
    double nominal_step_rad = 0.0;

    int size() const { return static_cast<int>(index.size()); }
    bool silhouette(int k) const {
        return left[k] == EndRole::kSilhouette || right[k] == EndRole::kSilhouette;
    }
};

void add_segments(RingPoints& rp) {
    const int n = rp.size();
    rp.seg_first.resize(n);
    rp.seg_last.resize(n);
    for (int k = 0; k < n; ++k) rp.seg_first[k] = rp.starts[k] ? k : rp.seg_first[k - 1];
    for (int k = n - 1; k >= 0; --k) {
        rp.seg_last[k] = k + 1 == n || rp.starts[k + 1] ? k : rp.seg_last[k + 1];
    }
}

/// Keeps the ring's in-range points and classifies the boundary between each and the previous
/// one from the returns around it (`gated_*`: the nearest gated-out returns, NaN if none).
class RingGate {
  public:
    RingGate(const EdgeExtractionConfig& config, double nominal_step_rad, std::size_t capacity)
        : config_(config), max_step_rad_(config.max_azimuth_gap_factor * nominal_step_rad) {
        RingPoints& rp = points_;
        rp.nominal_step_rad = nominal_step_rad;
        rp.index.reserve(capacity);
        rp.range_m.reserve(capacity);
        rp.step_rad.reserve(capacity);
        rp.adjacent.reserve(capacity);
        rp.starts.reserve(capacity);
        rp.left.reserve(capacity);
        rp.right.reserve(capacity);
    }

    void add(std::uint32_t index, double range_m, double step_rad, double gated_after_last_m,
             double gated_before_this_m) {
        RingPoints& rp = points_;
        EndRole left = EndRole::kNone;
        bool starts = rp.index.empty();
        const bool gated = !std::isnan(gated_after_last_m);
        if (!starts) {
            const double last_m = rp.range_m.back();
            if (gated) {  // the gated returns decide what each end faces
                rp.right.back() = role(last_m, gated_after_last_m);
                left = role(range_m, gated_before_this_m);
                starts = true;
            } else if (step_rad > max_step_rad_) {  // missing returns: nothing behind either end
                rp.right.back() = left = EndRole::kSilhouette;
                starts = true;
            } else if (role(range_m, last_m) != EndRole::kNone) {  // occlusion boundary
                rp.right.back() = role(last_m, range_m);
                left = role(range_m, last_m);
                starts = true;
            }
        }
        rp.index.push_back(index);
        rp.range_m.push_back(range_m);
        rp.step_rad.push_back(step_rad);
        rp.adjacent.push_back(rp.index.size() > 1 && !gated && step_rad <= max_step_rad_);
        rp.starts.push_back(starts);
        rp.left.push_back(left);
        rp.right.push_back(EndRole::kNone);
    }

    RingPoints finish() {
        add_segments(points_);
        return std::move(points_);
    }

  private:
    /// What an end at `own_m` sees in a neighbouring return at `other_m`.
    EndRole role(double own_m, double other_m) const {
        if (std::abs(own_m - other_m) <= config_.range_jump_ratio * std::min(own_m, other_m)) {
            return EndRole::kNone;
        }
        return own_m < other_m ? EndRole::kSilhouette : EndRole::kOccluded;
    }

    const EdgeExtractionConfig& config_;
    double max_step_rad_;
    RingPoints points_;
};

RingPoints gate_ring(const PointCloud& sweep, const Indices& ring, const std::vector<float>& az,
                     const EdgeExtractionConfig& config) {
    RingGate gate(config, median_step_rad(ring, az), ring.size());
    constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
    std::size_t last = 0;
    bool any = false;
    double first_gated_m = kNone;
    double last_gated_m = kNone;
    for (std::size_t k = 0; k < ring.size(); ++k) {
        const double range_m = sweep.points[ring[k]].norm();
        if (range_m < config.min_range_m || range_m > config.max_range_m) {
            if (std::isnan(first_gated_m)) first_gated_m = range_m;
            last_gated_m = range_m;
            continue;
        }
        const double step_rad = any ? abs_step(az[ring[last]], az[ring[k]]) : 0.0;
        gate.add(ring[k], range_m, step_rad, any ? first_gated_m : kNone, last_gated_m);
        first_gated_m = last_gated_m = kNone;
        last = k;
        any = true;
    }
    return gate.finish();
}

/// c_k over the full window (h points each side): within the point's segment, or across the
/// boundary for a silhouette; NaN when the window does not fit.
float curvature(const PointCloud& sweep, const RingPoints& rp, int k, int h) {
    const bool silhouette = rp.silhouette(k);
    const int first = silhouette ? 0 : rp.seg_first[k];
    const int last = silhouette ? rp.size() - 1 : rp.seg_last[k];
    if (k - first < h || last - k < h) return kNoCurvature;
    Eigen::Vector3d sum = -2.0 * h * sweep.points[rp.index[k]];
    for (int l = 1; l <= h; ++l)
        sum += sweep.points[rp.index[k - l]] + sweep.points[rp.index[k + l]];
    const double scale = 2.0 * h * rp.range_m[k];
    return static_cast<float>(sum.squaredNorm() / (scale * scale));
}

/// LOAM's occluded points: segment ends with a nearer surface in front, and the h points
/// behind each; such an end moves with the viewpoint.
std::vector<char> occluded_points(const RingPoints& rp, int h) {
    std::vector<char> occluded(rp.index.size(), 0);
    for (int k = 0; k < rp.size(); ++k) {
        if (rp.left[k] == EndRole::kOccluded) {
            for (int j = k; j <= std::min(rp.seg_last[k], k + h); ++j) occluded[j] = 1;
        }
        if (rp.right[k] == EndRole::kOccluded) {
            for (int j = k; j >= std::max(rp.seg_first[k], k - h); --j) occluded[j] = 1;
        }
    }
    return occluded;
}

/// LOAM's beam-parallel test: the range rises towards one adjacent return and falls towards
/// the other (a receding surface, not a thin object in front of its neighbours), each by more
/// than tan(max_incidence) · r · Δφ.
bool parallel_to_beam(const RingPoints& rp, int k, double tan_max_incidence) {
    if (k + 1 >= rp.size() || !rp.adjacent[k] || !rp.adjacent[k + 1]) return false;
    const double rise_before_m = rp.range_m[k] - rp.range_m[k - 1];
    const double rise_after_m = rp.range_m[k + 1] - rp.range_m[k];
    auto steep = [&](double rise_m, double step_rad) {
        return std::abs(rise_m) >
               tan_max_incidence * rp.range_m[k] * std::max(step_rad, rp.nominal_step_rad);
    };
    return rise_before_m * rise_after_m > 0.0 && steep(rise_before_m, rp.step_rad[k]) &&
           steep(rise_after_m, rp.step_rad[k + 1]);
}

struct RingEdges {
    Indices index;
    std::vector<float> curvature;
    Indices plane_index;
    std::size_t num_in_range = 0;
};

/// LOAM's reliability test of a ring point: not occluded, not on a surface along the beam.
class Reliability {
  public:
    Reliability(const RingPoints& rp, const EdgeExtractionConfig& config)
        : rp_(rp),
          check_(config.reject_unreliable),
          occluded_(check_ ? occluded_points(rp, config.curvature_half_window)
                           : std::vector<char>()),
          tan_max_incidence_(std::tan(config.max_incidence_rad)) {}

    /// Only for points with a full curvature window (k >= 1).
    bool operator()(int k) const {
        return !check_ || (!occluded_[k] && !parallel_to_beam(rp_, k, tan_max_incidence_));
    }

  private:
    const RingPoints& rp_;
    bool check_;
    std::vector<char> occluded_;
    double tan_max_incidence_;
};

/// Per sector of the ring, up to `cap` of the `eligible` points, best first by `better` (a
/// strict total order), each pick suppressing the points within `h` of it: within its segment
/// when `within_segment`, else across segment ends. Returns positions in the ring, ascending.
template <typename Eligible, typename Better>
std::vector<int> pick_per_sector(const RingPoints& rp, int num_sectors, int cap, int h,
                                 bool within_segment, Eligible&& eligible, Better&& better) {
    const int n = rp.size();
    std::vector<char> suppressed(static_cast<std::size_t>(n), 0);
    std::vector<int> picked, candidates;
    // A heap ordered so that its top is the best: only the first few are usually needed.
    auto worse = [&](int a, int b) { return better(b, a); };
    for (int s = 0; s < num_sectors; ++s) {
        const int begin = static_cast<int>(static_cast<long long>(n) * s / num_sectors);
        const int end = static_cast<int>(static_cast<long long>(n) * (s + 1) / num_sectors);
        candidates.clear();
        for (int k = begin; k < end; ++k) {
            if (eligible(k)) candidates.push_back(k);
        }
        std::make_heap(candidates.begin(), candidates.end(), worse);
        int count = 0;
        for (auto top = candidates.end(); top != candidates.begin() && count < cap;) {
            std::pop_heap(candidates.begin(), top, worse);
            const int k = *--top;
            if (suppressed[k]) continue;
            picked.push_back(k);
            ++count;
            const int first =
                within_segment ? std::max(rp.seg_first[k], k - h) : std::max(0, k - h);
            const int last =
                within_segment ? std::min(rp.seg_last[k], k + h) : std::min(n - 1, k + h);
            for (int j = first; j <= last; ++j) suppressed[j] = 1;
        }
    }
    std::sort(picked.begin(), picked.end());
    return picked;
}

/// Per sector, the highest-curvature reliable candidates (ties: lower position first),
/// suppressing the neighbours of each pick within its segment.
std::vector<int> select_edges(const RingPoints& rp, const std::vector<float>& c,
                              const Reliability& reliable, const EdgeExtractionConfig& config) {
    return pick_per_sector(
        rp, config.num_sectors, config.max_edges_per_sector, config.curvature_half_window, true,
        [&](int k) { return c[k] > config.min_edge_curvature && reliable(k); },  // NaN: no window
        [&](int a, int b) { return c[a] > c[b] || (c[a] == c[b] && a < b); });
}

/// Per sector, the lowest-curvature reliable points (ties: lower position first), each
/// suppressing its neighbours within the curvature window, so that they spread along the ring.
std::vector<int> select_planes(const RingPoints& rp, const std::vector<float>& c,
                               const Reliability& reliable, const EdgeExtractionConfig& config) {
    return pick_per_sector(
        rp, config.num_sectors, config.max_planes_per_sector, config.curvature_half_window, false,
        [&](int k) { return c[k] <= config.max_plane_curvature && reliable(k); },  // NaN: no window
        [&](int a, int b) { return c[a] < c[b] || (c[a] == c[b] && a < b); });
}

RingEdges extract_ring(const PointCloud& sweep, const Indices& ring, const std::vector<float>& az,
                       const EdgeExtractionConfig& config) {
    const RingPoints rp = gate_ring(sweep, ring, az, config);
    RingEdges edges;
    edges.num_in_range = rp.index.size();
    std::vector<float> c(rp.index.size());
    for (int k = 0; k < rp.size(); ++k)
        c[k] = curvature(sweep, rp, k, config.curvature_half_window);
    const Reliability reliable(rp, config);
    for (int k : select_edges(rp, c, reliable, config)) {
        edges.index.push_back(rp.index[k]);
        edges.curvature.push_back(c[k]);
    }
    if (config.max_planes_per_sector > 0) {
        for (int k : select_planes(rp, c, reliable, config)) {
            edges.plane_index.push_back(rp.index[k]);
        }
    }
    return edges;
}

void require(bool ok, std::string_view prefix, std::string_view field, double value,
             std::string_view expected) {
    if (!ok)
        throw ConfigError(fmt::format("{}.{} = {}, expected {}", prefix, field, value, expected));
}

}  // namespace

void EdgeExtractionConfig::validate(std::string_view prefix) const {
    require(min_range_m >= 0.0 && std::isfinite(min_range_m), prefix, "min_range_m", min_range_m,
            "finite >= 0");
    require(min_range_m < max_range_m, prefix, "min_range_m", min_range_m,
            fmt::format("< max_range_m = {}", max_range_m));
    require(std::isfinite(max_range_m), prefix, "max_range_m", max_range_m, "finite");
    require(curvature_half_window >= 1, prefix, "curvature_half_window", curvature_half_window,
            ">= 1");
    require(num_sectors >= 1, prefix, "num_sectors", num_sectors, ">= 1");
    require(max_edges_per_sector >= 1, prefix, "max_edges_per_sector", max_edges_per_sector,
            ">= 1");
    require(min_edge_curvature >= 0.0 && std::isfinite(min_edge_curvature), prefix,
            "min_edge_curvature", min_edge_curvature, "finite >= 0");
    require(max_azimuth_gap_factor > 1.0 && std::isfinite(max_azimuth_gap_factor), prefix,
            "max_azimuth_gap_factor", max_azimuth_gap_factor, "finite > 1");
    require(range_jump_ratio > 0.0 && std::isfinite(range_jump_ratio), prefix, "range_jump_ratio",
            range_jump_ratio, "finite > 0");
    require(max_incidence_rad > 0.0 && max_incidence_rad < std::numbers::pi / 2, prefix,
            "max_incidence_rad", max_incidence_rad, "in (0, pi/2)");
    require(max_planes_per_sector >= 0, prefix, "max_planes_per_sector", max_planes_per_sector,
            ">= 0");
    require(max_plane_curvature >= 0.0 && std::isfinite(max_plane_curvature), prefix,
            "max_plane_curvature", max_plane_curvature, "finite >= 0");
    rings.validate(std::string(prefix) + ".rings");
    parallel.validate(std::string(prefix) + ".parallel");
}

EdgeFeatures extract_edges(const PointCloud& sweep, const EdgeExtractionConfig& config) {
    config.validate();
    const RingLayout layout = organize_rings(sweep, config.rings, config.parallel);
    std::vector<RingEdges> per_ring(layout.rings.size());
    parallel_for(config.parallel, layout.rings.size(), 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) {
            per_ring[r] = extract_ring(sweep, layout.rings[r], layout.azimuths_rad, config);
        }
    });
    EdgeFeatures features;
    features.num_input = sweep.size();
    features.num_rings = layout.rings.size();
    for (const RingEdges& ring : per_ring) {
        features.num_in_range += ring.num_in_range;
        for (std::size_t e = 0; e < ring.index.size(); ++e) {
            const std::uint32_t i = ring.index[e];
            features.points.push_back(sweep.points[i]);
            features.ranges_m.push_back(sweep.points[i].norm());
            if (sweep.has_times()) features.times_s.push_back(sweep.times_s[i]);
            features.curvatures.push_back(ring.curvature[e]);
        }
        for (const std::uint32_t i : ring.plane_index) {
            features.plane_points.push_back(sweep.points[i]);
            features.plane_ranges_m.push_back(sweep.points[i].norm());
        }
    }
    return features;
}

}  // namespace scantling::odometry
