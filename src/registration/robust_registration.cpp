#include <scantling/core/error.hpp>
#include <scantling/registration/robust_registration.hpp>

#include <cmath>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "detail/config_checks.hpp"
#include "detail/consistency_graph.hpp"
#include "detail/hypothesis_cliques.hpp"
#include "detail/hypothesis_scoring.hpp"
#include "detail/rigid_fit.hpp"
#include "detail/tls_estimators.hpp"

namespace scantling::registration {
namespace {

using Points = std::vector<Eigen::Vector3d>;

void check_pairs(std::span<const Eigen::Vector3d> source, std::span<const Eigen::Vector3d> target) {
    if (source.size() != target.size()) {
        throw InputError(
            fmt::format("robust_register: {} source points but {} target points, "
                        "expected one target point per source point",
                        source.size(), target.size()));
    }
    for (std::size_t k = 0; k < source.size(); ++k) {
        if (!source[k].allFinite() || !target[k].allFinite()) {
            throw InputError(fmt::format("robust_register: correspondence {} is not finite", k));
        }
    }
}

/// TEASER++'s chain of TIMs over the clique: member i to member i + 1 (cyclic).
void chain_tims(std::span<const Eigen::Vector3d> points, const std::vector<std::uint32_t>& clique,
                Points& tims) {
    tims.resize(clique.size());
    for (std::size_t i = 0; i < clique.size(); ++i) {
        tims[i] = points[clique[(i + 1) % clique.size()]] - points[clique[i]];
    }
}

/// Rotation from the clique's TIMs, and the clique members it keeps as inliers.
struct RotationStep {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    int iterations = 0;
    std::vector<std::uint32_t> members;
};

RotationStep estimate_rotation(std::span<const Eigen::Vector3d> source,
                               std::span<const Eigen::Vector3d> target,
                               const std::vector<std::uint32_t>& clique,
                               const RobustRegistrationConfig& config) {
    Points s_tims, t_tims;
    chain_tims(source, clique, s_tims);
    chain_tims(target, clique, t_tims);
    // A TIM is the difference of two noisy points: its error is bounded by 2β.
    const double tim_bound = 2.0 * config.noise_bound_m * std::sqrt(config.cbar2);
    if (config.rotation == RobustRotation::kYawOnly) {
        return {detail::yaw_rotation(detail::yaw_tls(s_tims, t_tims, tim_bound)), 1, clique};
    }
    const detail::RotationEstimate est = detail::gnc_tls_rotation(
        s_tims, t_tims,
        {tim_bound, config.gnc_max_iterations, config.gnc_factor, config.rotation_cost_threshold});
    RotationStep step{est.R, est.iterations, {}};
    for (std::size_t i = 0; i < clique.size(); ++i) {
        if (est.inliers[i]) step.members.push_back(clique[i]);
    }
    if (step.members.empty()) step.members = clique;  // keep the voting well defined
    return step;
}

/// Component-wise TLS by adaptive voting over t_k − R s_k of the rotation inliers.
Eigen::Vector3d estimate_translation(std::span<const Eigen::Vector3d> source,
                                     std::span<const Eigen::Vector3d> target,
                                     const std::vector<std::uint32_t>& members,
                                     const Eigen::Matrix3d& R, double bound) {
    Eigen::Vector3d t;
    std::vector<double> values(members.size());
    for (int axis = 0; axis < 3; ++axis) {
        for (std::size_t i = 0; i < members.size(); ++i) {
            values[i] = (target[members[i]] - R * source[members[i]])(axis);
        }
        t(axis) = detail::scalar_tls(values, bound);
    }
    return t;
}

std::vector<std::size_t> find_inliers(std::span<const Eigen::Vector3d> source,
                                      std::span<const Eigen::Vector3d> target,
                                      const Eigen::Isometry3d& T, double bound) {
    std::vector<std::size_t> inliers;
    for (std::size_t k = 0; k < source.size(); ++k) {
        if ((target[k] - T * source[k]).norm() <= bound) inliers.push_back(k);
    }
    return inliers;
}

/// Least-squares refit on the inliers, then the inliers of the refitted pose (kept only when
/// the refit does not lose inliers, so the TLS consensus is never traded for a smaller one).
void refit(std::span<const Eigen::Vector3d> source, std::span<const Eigen::Vector3d> target,
           bool yaw_only, double bound, Eigen::Isometry3d& T, std::vector<std::size_t>& inliers) {
    if (inliers.empty()) return;
    Points s, t;
    for (std::size_t k : inliers) {
        s.push_back(source[k]);
        t.push_back(target[k]);
    }
    const Eigen::Isometry3d T_refit = detail::fit_rigid(s, t, yaw_only);
    auto refit_inliers = find_inliers(source, target, T_refit, bound);
    if (refit_inliers.size() < inliers.size()) return;
    T = T_refit;
    inliers = std::move(refit_inliers);
}

void fill_statistics(std::span<const Eigen::Vector3d> source,
                     std::span<const Eigen::Vector3d> target, RobustRegistrationResult& r) {
    double sum_sq = 0.0;
    for (std::size_t k : r.inliers) {
        sum_sq += (target[k] - r.registration.T_target_source * source[k]).squaredNorm();
    }
    const std::size_t n = r.inliers.size();
    r.registration.num_inliers = n;
    r.registration.fitness = static_cast<double>(n) / static_cast<double>(source.size());
    r.registration.rmse_m = n > 0 ? std::sqrt(sum_sq / static_cast<double>(n)) : 0.0;
}

/// converged only with enough inliers that spread in space (else the rotation is not fixed).
void judge(std::span<const Eigen::Vector3d> source, const RobustRegistrationConfig& config,
           RobustRegistrationResult& r) {
    const auto count = r.inliers.size();
    if (count < static_cast<std::size_t>(config.min_inliers)) {
        r.registration.status =
            fmt::format("too_few_inliers: {} < min_inliers = {}", count, config.min_inliers);
        return;
    }
    const bool yaw_only = config.rotation == RobustRotation::kYawOnly;
    Points inlier_points;
    for (std::size_t k : r.inliers) inlier_points.push_back(source[k]);
    const double spread = detail::principal_spread_m(inlier_points, yaw_only);
    const double min_spread = config.min_spread_in_noise_bounds * config.noise_bound_m;
    if (!(spread > min_spread) || spread == 0.0) {
        r.registration.status = fmt::format(
            "degenerate: inlier spread {:.4g} m <= {:.4g} m (collinear or coincident points)",
            spread, min_spread);
        return;
    }
    r.registration.converged = true;
    r.registration.status = "converged";
}

/// The pose of one clique (steps 3–5) and its correspondence inliers.
struct Candidate {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    std::vector<std::size_t> inliers;
    int iterations = 0;
    double overlap = 0.0;
};

Candidate solve_clique(std::span<const Eigen::Vector3d> source,
                       std::span<const Eigen::Vector3d> target,
                       const std::vector<std::uint32_t>& clique,
                       const RobustRegistrationConfig& config) {
    const bool yaw_only = config.rotation == RobustRotation::kYawOnly;
    const double bound = config.noise_bound_m * std::sqrt(config.cbar2);
    const RotationStep rotation = estimate_rotation(source, target, clique, config);
    Candidate c;
    c.iterations = rotation.iterations;
    c.T.linear() = rotation.R;
    c.T.translation() = estimate_translation(source, target, rotation.members, rotation.R, bound);
    c.inliers = find_inliers(source, target, c.T, bound);
    refit(source, target, yaw_only, bound, c.T, c.inliers);
    return c;
}

/// Whether `a` and `b` are the same pose up to the noise: then the overlap difference between
/// them is sampling chance, and the earlier (larger) clique's pose should stand.
bool same_pose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double bound) {
    constexpr double kSameRotationRad = std::numbers::pi / 180.0;
    const Eigen::Isometry3d d = a.inverse() * b;
    return Eigen::AngleAxisd(d.linear()).angle() < kSameRotationRad &&
           d.translation().norm() < bound;
}

/// Solves every clique and scores its pose (in parallel: each writes only its own slot), then
/// returns the index of the best: most overlap, then most inliers, then the earliest clique. A
/// candidate with the same pose as the best so far never replaces it.
std::size_t verify(std::span<const Eigen::Vector3d> source, std::span<const Eigen::Vector3d> target,
                   const std::vector<std::vector<std::uint32_t>>& cliques,
                   const RobustRegistrationConfig& config, const detail::OverlapScorer& scorer,
                   std::vector<Candidate>& candidates) {
    candidates.resize(cliques.size());
    parallel_for(config.parallel, cliques.size(), 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            candidates[i] = solve_clique(source, target, cliques[i], config);
            candidates[i].overlap = scorer.score(candidates[i].T);
        }
    });
    const double bound = config.noise_bound_m * std::sqrt(config.cbar2);
    std::size_t best = 0;
    for (std::size_t i = 1; i < candidates.size(); ++i) {
        const Candidate& c = candidates[i];
        const Candidate& b = candidates[best];
        const bool better = c.overlap > b.overlap ||
                            (c.overlap == b.overlap && c.inliers.size() > b.inliers.size());
        if (better && !same_pose(c.T, b.T, bound)) best = i;
    }
    return best;
}

/// The whole method on validated config; `scorer` (may be null: no verification) holds the
/// clouds for the overlap score.
RobustRegistrationResult register_pairs(std::span<const Eigen::Vector3d> source,
                                        std::span<const Eigen::Vector3d> target,
                                        const RobustRegistrationConfig& config,
                                        const detail::OverlapScorer* scorer) {
    check_pairs(source, target);
    RobustRegistrationResult r;
    if (source.size() < 3) {
        r.registration.status = fmt::format("too_few_correspondences: {} < 3", source.size());
        return r;
    }
    const bool yaw_only = config.rotation == RobustRotation::kYawOnly;
    const double bound = config.noise_bound_m * std::sqrt(config.cbar2);
    const UndirectedGraph graph =
        detail::build_consistency_graph(source, target, 2.0 * bound, yaw_only, config.parallel);
    r.num_consistent_pairs = graph.num_edges();
    MaxCliqueResult clique = find_max_clique(graph, config.max_clique);
    r.max_clique_size = clique.vertices.size();
    r.max_clique_method = clique.method;
    if (clique.vertices.size() < 3) {
        r.registration.status = fmt::format("clique_too_small: {} < 3", clique.vertices.size());
        return r;
    }
    Candidate best;
    if (scorer == nullptr) {
        best = solve_clique(source, target, clique.vertices, config);
    } else {
        const auto cliques =
            detail::disjoint_cliques(graph, std::move(clique.vertices),
                                     static_cast<std::size_t>(config.hypotheses.num_hypotheses), 3);
        std::vector<Candidate> candidates;
        r.winning_hypothesis = verify(source, target, cliques, config, *scorer, candidates);
        r.num_hypotheses_scored = candidates.size();
        best = std::move(candidates[r.winning_hypothesis]);
        r.overlap = best.overlap;
    }
    r.registration.iterations = best.iterations;
    r.registration.T_target_source = best.T;
    r.inliers = std::move(best.inliers);
    fill_statistics(source, target, r);
    judge(source, config, r);
    return r;
}

}  // namespace

void RobustRegistrationConfig::validate(std::string_view prefix) const {
    detail::require_positive(noise_bound_m, prefix, "noise_bound_m");
    detail::require_positive(cbar2, prefix, "cbar2");
    if (estimate_scaling) {
        throw ConfigError(fmt::format(
            "{}.estimate_scaling = true, expected false (the scale is fixed to 1, SPEC §7)",
            prefix));
    }
    max_clique.validate(fmt::format("{}.max_clique", prefix));
    detail::require_at_least(gnc_max_iterations, 1, prefix, "gnc_max_iterations");
    if (!(gnc_factor > 1.0) || !std::isfinite(gnc_factor)) {
        throw ConfigError(
            fmt::format("{}.gnc_factor = {}, expected finite > 1", prefix, gnc_factor));
    }
    detail::require_positive(rotation_cost_threshold, prefix, "rotation_cost_threshold");
    detail::require_at_least(min_inliers, 3, prefix, "min_inliers");
    if (!(min_spread_in_noise_bounds >= 0.0) || !std::isfinite(min_spread_in_noise_bounds)) {
        throw ConfigError(fmt::format("{}.min_spread_in_noise_bounds = {}, expected finite >= 0",
                                      prefix, min_spread_in_noise_bounds));
    }
    hypotheses.validate(fmt::format("{}.hypotheses", prefix));
    parallel.validate(fmt::format("{}.parallel", prefix));
}

void HypothesisConfig::validate(std::string_view prefix) const {
    detail::require_at_least(num_hypotheses, 1, prefix, "num_hypotheses");
    detail::require_positive(overlap_distance_m, prefix, "overlap_distance_m");
    if (max_scored_points < 1) {
        throw ConfigError(fmt::format("{}.max_scored_points = 0, expected >= 1", prefix));
    }
}

RobustRegistrationResult robust_register(std::span<const Eigen::Vector3d> source,
                                         std::span<const Eigen::Vector3d> target,
                                         const RobustRegistrationConfig& config) {
    config.validate();
    return register_pairs(source, target, config, nullptr);
}

RobustRegistrationResult robust_register(const PointCloud& source, const PointCloud& target,
                                         std::span<const Correspondence> correspondences,
                                         const RobustRegistrationConfig& config) {
    check_correspondence_indices(correspondences, source.size(), target.size(), "robust_register");
    Points s(correspondences.size()), t(correspondences.size());
    for (std::size_t k = 0; k < correspondences.size(); ++k) {
        s[k] = source.points[correspondences[k].source_index];
        t[k] = target.points[correspondences[k].target_index];
    }
    config.validate();
    if (config.hypotheses.num_hypotheses == 1) return register_pairs(s, t, config, nullptr);
    const detail::OverlapScorer scorer(source, target, config.hypotheses.overlap_distance_m,
                                       config.hypotheses.max_scored_points);
    return register_pairs(s, t, config, &scorer);
}

}  // namespace scantling::registration
