#include <scantling/core/error.hpp>
#include <scantling/registration/robust_registration.hpp>

#include <cmath>

#include <fmt/format.h>

#include "detail/config_checks.hpp"
#include "detail/consistency_graph.hpp"
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
    parallel.validate(fmt::format("{}.parallel", prefix));
}

RobustRegistrationResult robust_register(std::span<const Eigen::Vector3d> source,
                                         std::span<const Eigen::Vector3d> target,
                                         const RobustRegistrationConfig& config) {
    config.validate();
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
    const MaxCliqueResult clique = find_max_clique(graph, config.max_clique);
    r.max_clique_size = clique.vertices.size();
    r.max_clique_method = clique.method;
    if (clique.vertices.size() < 3) {
        r.registration.status = fmt::format("clique_too_small: {} < 3", clique.vertices.size());
        return r;
    }
    const RotationStep rotation = estimate_rotation(source, target, clique.vertices, config);
    r.registration.iterations = rotation.iterations;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = rotation.R;
    T.translation() = estimate_translation(source, target, rotation.members, rotation.R, bound);
    r.inliers = find_inliers(source, target, T, bound);
    refit(source, target, yaw_only, bound, T, r.inliers);
    r.registration.T_target_source = T;
    fill_statistics(source, target, r);
    judge(source, config, r);
    return r;
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
    return robust_register(s, t, config);
}

}  // namespace scantling::registration
