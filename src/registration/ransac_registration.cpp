#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/registration/ransac_registration.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "detail/config_checks.hpp"
#include "detail/rigid_fit.hpp"

namespace scantling::registration {
namespace {

// Hypotheses per batch and batches per group: fixed, so the stream of hypotheses and the points
// where the stopping test runs do not depend on the thread count. A group (4096 hypotheses,
// ~5–50 ms) is large enough to keep 2–8 threads busy and small enough to stop early.
constexpr std::size_t kBatchSize = 256;
constexpr std::size_t kBatchesPerGroup = 16;

struct Pairs {
    std::vector<Eigen::Vector3d> source;
    std::vector<Eigen::Vector3d> target;
};

struct Hypothesis {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    std::size_t inliers = 0;
    double sum_sq_m2 = 0.0;

    /// Open3D's IsBetterRANSACThan: higher fitness, then lower inlier RMSE.
    bool better_than(const Hypothesis& other) const {
        if (inliers != other.inliers) return inliers > other.inliers;
        return inliers > 0 && sum_sq_m2 / static_cast<double>(inliers) <
                                  other.sum_sq_m2 / static_cast<double>(other.inliers);
    }
};

Hypothesis evaluate(const Pairs& pairs, const Eigen::Isometry3d& T, double max_sq) {
    Hypothesis h;
    h.T = T;
    for (std::size_t k = 0; k < pairs.source.size(); ++k) {
        const double d2 = (pairs.target[k] - T * pairs.source[k]).squaredNorm();
        if (d2 < max_sq) {
            ++h.inliers;
            h.sum_sq_m2 += d2;
        }
    }
    return h;
}

void draw_sample(Rng& rng, std::size_t n, std::size_t k[3]) {
    k[0] = rng.uniform_index(n);
    do k[1] = rng.uniform_index(n);
    while (k[1] == k[0]);
    do k[2] = rng.uniform_index(n);
    while (k[2] == k[0] || k[2] == k[1]);
}

bool similar_edges(const Eigen::Vector3d s[3], const Eigen::Vector3d t[3], double ratio) {
    for (int e = 0; e < 3; ++e) {
        const double ls = (s[e] - s[(e + 1) % 3]).norm();
        const double lt = (t[e] - t[(e + 1) % 3]).norm();
        if (ls < lt * ratio || lt < ls * ratio) return false;
    }
    return true;
}

/// One hypothesis, or nothing when a checker rejects the sample.
std::optional<Hypothesis> try_sample(const Pairs& pairs, Rng& rng, const RansacConfig& config) {
    std::size_t k[3];
    draw_sample(rng, pairs.source.size(), k);
    const Eigen::Vector3d s[3] = {pairs.source[k[0]], pairs.source[k[1]], pairs.source[k[2]]};
    const Eigen::Vector3d t[3] = {pairs.target[k[0]], pairs.target[k[1]], pairs.target[k[2]]};
    if (!similar_edges(s, t, config.edge_length_ratio)) return std::nullopt;
    const Eigen::Isometry3d T = detail::fit_rigid(s, t, false);
    const double max_d = config.max_correspondence_distance_m;
    if (config.check_distance) {
        for (int i = 0; i < 3; ++i) {
            if ((t[i] - T * s[i]).norm() > max_d) return std::nullopt;
        }
    }
    return evaluate(pairs, T, max_d * max_d);
}

Hypothesis run_batch(const Pairs& pairs, std::size_t batch, std::size_t total,
                     const RansacConfig& config) {
    Rng rng = Rng(config.seed).split(batch);
    Hypothesis best;
    const std::size_t end = std::min((batch + 1) * kBatchSize, total);
    for (std::size_t it = batch * kBatchSize; it < end; ++it) {
        const auto h = try_sample(pairs, rng, config);
        if (h && h->better_than(best)) best = *h;
    }
    return best;
}

/// Iterations after which a sample of 3 inliers has been drawn with probability `confidence`.
double needed_iterations(std::size_t inliers, std::size_t n, double confidence) {
    if (inliers == 0) return std::numeric_limits<double>::infinity();
    const double fitness = static_cast<double>(inliers) / static_cast<double>(n);
    const double miss = 1.0 - fitness * fitness * fitness;
    if (miss <= 0.0) return 0.0;
    return std::log(1.0 - confidence) / std::log(miss);
}

Hypothesis search(const Pairs& pairs, const RansacConfig& config, std::size_t& drawn) {
    const auto total = static_cast<std::size_t>(config.max_iterations);
    const std::size_t batches = (total + kBatchSize - 1) / kBatchSize;
    Hypothesis best;
    drawn = 0;
    for (std::size_t first = 0; first < batches; first += kBatchesPerGroup) {
        const std::size_t count = std::min(kBatchesPerGroup, batches - first);
        std::vector<Hypothesis> local(count);
        parallel_for(config.parallel, count, 1, [&](std::size_t b, std::size_t e) {
            for (std::size_t i = b; i < e; ++i)
                local[i] = run_batch(pairs, first + i, total, config);
        });
        for (const Hypothesis& h : local) {
            if (h.better_than(best)) best = h;
        }
        drawn = std::min((first + count) * kBatchSize, total);
        if (static_cast<double>(drawn) >=
            needed_iterations(best.inliers, pairs.source.size(), config.confidence))
            break;
    }
    return best;
}

std::vector<std::size_t> inliers_of(const Pairs& pairs, const Eigen::Isometry3d& T, double max_sq) {
    std::vector<std::size_t> out;
    for (std::size_t k = 0; k < pairs.source.size(); ++k) {
        if ((pairs.target[k] - T * pairs.source[k]).squaredNorm() < max_sq) out.push_back(k);
    }
    return out;
}

/// Least-squares refit on the best hypothesis' inliers, kept when it loses none.
void refine(const Pairs& pairs, double max_sq, RansacResult& r) {
    std::vector<Eigen::Vector3d> s, t;
    for (std::size_t k : r.inliers) {
        s.push_back(pairs.source[k]);
        t.push_back(pairs.target[k]);
    }
    const Eigen::Isometry3d T = detail::fit_rigid(s, t, false);
    auto inliers = inliers_of(pairs, T, max_sq);
    if (inliers.size() < r.inliers.size()) return;
    r.registration.T_target_source = T;
    r.inliers = std::move(inliers);
}

Pairs make_pairs(std::span<const Eigen::Vector3d> source_points,
                 std::span<const Eigen::Vector3d> target_points,
                 std::span<const Correspondence> correspondences) {
    Pairs pairs;
    for (const Correspondence& c : correspondences) {
        pairs.source.push_back(source_points[c.source_index]);
        pairs.target.push_back(target_points[c.target_index]);
        if (!pairs.source.back().allFinite() || !pairs.target.back().allFinite()) {
            throw InputError(
                fmt::format("ransac_register: correspondence ({}, {}) has a non-finite point",
                            c.source_index, c.target_index));
        }
    }
    return pairs;
}

void fill_statistics(const Pairs& pairs, RansacResult& r) {
    double sum_sq = 0.0;
    for (std::size_t k : r.inliers) {
        sum_sq +=
            (pairs.target[k] - r.registration.T_target_source * pairs.source[k]).squaredNorm();
    }
    const std::size_t n = r.inliers.size();
    r.registration.num_inliers = n;
    r.registration.fitness = static_cast<double>(n) / static_cast<double>(pairs.source.size());
    r.registration.rmse_m = n > 0 ? std::sqrt(sum_sq / static_cast<double>(n)) : 0.0;
}

/// converged only with enough inliers that are not collinear (else the rotation about their
/// line is arbitrary).
void judge(const Pairs& pairs, const RansacConfig& config, RansacResult& r) {
    const std::size_t n = r.inliers.size();
    if (n < static_cast<std::size_t>(config.min_inliers)) {
        r.registration.status =
            fmt::format("too_few_inliers: {} < min_inliers = {}", n, config.min_inliers);
        return;
    }
    std::vector<Eigen::Vector3d> points;
    for (std::size_t k : r.inliers) points.push_back(pairs.source[k]);
    const double spread = detail::principal_spread_m(points, false);
    if (!(spread > config.max_correspondence_distance_m)) {
        r.registration.status = fmt::format(
            "degenerate: inlier spread {:.4g} m <= {:.4g} m (collinear or coincident points)",
            spread, config.max_correspondence_distance_m);
        return;
    }
    r.registration.converged = true;
    r.registration.status = "converged";
}

}  // namespace

void RansacConfig::validate(std::string_view prefix) const {
    detail::require_positive(max_correspondence_distance_m, prefix,
                             "max_correspondence_distance_m");
    detail::require_open_unit(edge_length_ratio, prefix, "edge_length_ratio");
    detail::require_at_least(max_iterations, 1, prefix, "max_iterations");
    detail::require_open_unit(confidence, prefix, "confidence");
    detail::require_at_least(min_inliers, 3, prefix, "min_inliers");
    parallel.validate(fmt::format("{}.parallel", prefix));
}

RansacResult ransac_register(std::span<const Eigen::Vector3d> source_points,
                             std::span<const Eigen::Vector3d> target_points,
                             std::span<const Correspondence> correspondences,
                             const RansacConfig& config) {
    config.validate();
    check_correspondence_indices(correspondences, source_points.size(), target_points.size(),
                                 "ransac_register");
    const Pairs pairs = make_pairs(source_points, target_points, correspondences);
    RansacResult r;
    if (pairs.source.size() < 3) {
        r.registration.status = fmt::format("too_few_correspondences: {} < 3", pairs.source.size());
        return r;
    }
    std::size_t drawn = 0;
    const Hypothesis best = search(pairs, config, drawn);
    r.registration.iterations = static_cast<int>(drawn);
    const double max_sq =
        config.max_correspondence_distance_m * config.max_correspondence_distance_m;
    if (best.inliers == 0) {
        r.registration.status = "no_hypothesis: every sample failed the checkers";
        return r;
    }
    r.registration.T_target_source = best.T;
    r.inliers = inliers_of(pairs, best.T, max_sq);
    if (r.inliers.size() >= 3) refine(pairs, max_sq, r);
    fill_statistics(pairs, r);
    judge(pairs, config, r);
    return r;
}

}  // namespace scantling::registration
