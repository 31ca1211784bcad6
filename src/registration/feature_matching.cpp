#include <scantling/core/error.hpp>
#include <scantling/registration/feature_matching.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "detail/config_checks.hpp"
#include "detail/feature_index.hpp"

namespace scantling::registration {
namespace {

constexpr std::size_t kGrain = 64;  // queries per parallel chunk (each costs ~10–100 µs)
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

void check_features(const FeatureMatrix& features, std::string_view what) {
    for (Eigen::Index c = 0; c < features.cols(); ++c) {
        if (!features.col(c).allFinite()) {
            throw InputError(
                fmt::format("match_features: {} descriptor {} is not finite", what, c));
        }
    }
}

/// Nearest (and second nearest when `k` = 2) column of `index` for every column of `queries`
/// (both already rotated into the principal axes).
std::vector<detail::FeatureNeighbors> query_all(const detail::FeatureIndex& index,
                                                const FeatureMatrix& queries, int k,
                                                const ParallelConfig& parallel) {
    std::vector<detail::FeatureNeighbors> out(static_cast<std::size_t>(queries.cols()));
    parallel_for(parallel, out.size(), kGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t q = begin; q < end; ++q) {
            out[q] = index.nearest(queries.col(static_cast<Eigen::Index>(q)).data(), k);
        }
    });
    return out;
}

/// For each source i: is i also its nearest target's nearest source? Per target only the
/// closest of the sources that chose it (ties: lower index) can be; that one is confirmed by a
/// search of the source descriptors bounded by its own distance.
std::vector<char> mutual_mask(const std::vector<detail::FeatureNeighbors>& forward,
                              const FeatureMatrix& source_rotated,
                              const FeatureMatrix& target_rotated, const ParallelConfig& parallel) {
    std::vector<std::uint32_t> closest(static_cast<std::size_t>(target_rotated.cols()), kNone);
    for (std::size_t i = 0; i < forward.size(); ++i) {
        std::uint32_t& c = closest[forward[i].index[0]];
        if (c == kNone || forward[i].distance_sq[0] < forward[c].distance_sq[0]) {
            c = static_cast<std::uint32_t>(i);
        }
    }
    const detail::FeatureIndex source_index(source_rotated);
    std::vector<char> keep(forward.size(), 0);
    parallel_for(parallel, closest.size(), kGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t j = begin; j < end; ++j) {
            const std::uint32_t i = closest[j];
            if (i == kNone) continue;
            const float* query = target_rotated.col(static_cast<Eigen::Index>(j)).data();
            keep[i] = source_index.is_nearest(query, i, forward[i].distance_sq[0]) ? 1 : 0;
        }
    });
    return keep;
}

bool passes_ratio(const detail::FeatureNeighbors& nn, double ratio) {
    if (ratio <= 0.0 || nn.count < 2) return true;
    // Compare squared distances: d1 < r d2  <=>  d1² < r² d2².
    return nn.distance_sq[0] < ratio * ratio * nn.distance_sq[1];
}

std::vector<Correspondence> keep_best(std::vector<Correspondence> matches, int max_count) {
    if (max_count <= 0 || matches.size() <= static_cast<std::size_t>(max_count)) return matches;
    std::stable_sort(matches.begin(), matches.end(), [](const auto& a, const auto& b) {
        return a.feature_distance < b.feature_distance;
    });
    matches.resize(static_cast<std::size_t>(max_count));
    std::sort(matches.begin(), matches.end(),
              [](const auto& a, const auto& b) { return a.source_index < b.source_index; });
    return matches;
}

double edge(std::span<const Eigen::Vector3d> points, std::size_t a, std::size_t b) {
    return (points[a] - points[b]).norm();
}

/// True when the three edges of the source and target triangles agree within `scale`.
bool similar_triangles(const Correspondence* c[3], std::span<const Eigen::Vector3d> source,
                       std::span<const Eigen::Vector3d> target, double scale) {
    for (int e = 0; e < 3; ++e) {
        const Correspondence& a = *c[e];
        const Correspondence& b = *c[(e + 1) % 3];
        const double ls = edge(source, a.source_index, b.source_index);
        const double lt = edge(target, a.target_index, b.target_index);
        if (!(ls * scale < lt && lt * scale < ls)) return false;
    }
    return true;
}

}  // namespace

void MatchConfig::validate(std::string_view prefix) const {
    if (!(ratio == 0.0 || (ratio > 0.0 && ratio < 1.0))) {
        throw ConfigError(
            fmt::format("{}.ratio = {}, expected 0 (off) or in (0, 1)", prefix, ratio));
    }
    detail::require_at_least(max_correspondences, 0, prefix, "max_correspondences");
    parallel.validate(fmt::format("{}.parallel", prefix));
}

std::vector<Correspondence> match_features(const FeatureMatrix& source, const FeatureMatrix& target,
                                           const MatchConfig& config) {
    config.validate();
    if (source.rows() != target.rows()) {
        throw InputError(
            fmt::format("match_features: source descriptors have {} rows, target {}; "
                        "expected the same dimension",
                        source.rows(), target.rows()));
    }
    check_features(source, "source");
    check_features(target, "target");
    if (source.cols() == 0 || target.cols() == 0) return {};
    const Eigen::MatrixXf axes = detail::principal_axes(source, target);
    const FeatureMatrix source_rotated = axes * source;
    const FeatureMatrix target_rotated = axes * target;
    const detail::FeatureIndex target_index(target_rotated);
    const auto forward =
        query_all(target_index, source_rotated, config.ratio > 0.0 ? 2 : 1, config.parallel);
    std::vector<char> keep(forward.size(), 1);
    if (config.mutual) keep = mutual_mask(forward, source_rotated, target_rotated, config.parallel);
    std::vector<Correspondence> matches;
    for (std::size_t i = 0; i < forward.size(); ++i) {
        if (!keep[i] || !passes_ratio(forward[i], config.ratio)) continue;
        matches.push_back({i, forward[i].index[0], std::sqrt(forward[i].distance_sq[0])});
    }
    return keep_best(std::move(matches), config.max_correspondences);
}

void TupleFilterConfig::validate(std::string_view prefix) const {
    detail::require_open_unit(scale, prefix, "scale");
    detail::require_at_least(max_tuples, 1, prefix, "max_tuples");
    detail::require_at_least(trials_per_correspondence, 1, prefix, "trials_per_correspondence");
}

void check_correspondence_indices(std::span<const Correspondence> correspondences,
                                  std::size_t source_size, std::size_t target_size,
                                  std::string_view what) {
    for (std::size_t k = 0; k < correspondences.size(); ++k) {
        const Correspondence& c = correspondences[k];
        if (c.source_index >= source_size || c.target_index >= target_size) {
            throw InputError(
                fmt::format("{}: correspondence {} = ({}, {}) out of range, expected < ({}, {})",
                            what, k, c.source_index, c.target_index, source_size, target_size));
        }
    }
}

std::vector<Correspondence> tuple_filter(std::span<const Correspondence> correspondences,
                                         std::span<const Eigen::Vector3d> source_points,
                                         std::span<const Eigen::Vector3d> target_points,
                                         const TupleFilterConfig& config, Rng& rng) {
    config.validate();
    check_correspondence_indices(correspondences, source_points.size(), target_points.size(),
                                 "tuple_filter");
    const std::size_t n = correspondences.size();
    if (n < 3) return {correspondences.begin(), correspondences.end()};
    std::vector<char> keep(n, 0);
    const std::size_t trials = n * static_cast<std::size_t>(config.trials_per_correspondence);
    int accepted = 0;
    for (std::size_t t = 0; t < trials && accepted < config.max_tuples; ++t) {
        const std::size_t k[3] = {rng.uniform_index(n), rng.uniform_index(n), rng.uniform_index(n)};
        const Correspondence* c[3] = {&correspondences[k[0]], &correspondences[k[1]],
                                      &correspondences[k[2]]};
        if (!similar_triangles(c, source_points, target_points, config.scale)) continue;
        for (std::size_t m : k) keep[m] = 1;
        ++accepted;
    }
    std::vector<Correspondence> out;
    for (std::size_t m = 0; m < n; ++m) {
        if (keep[m]) out.push_back(correspondences[m]);
    }
    return out;
}

}  // namespace scantling::registration
