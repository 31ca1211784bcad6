#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/registration/icp.hpp>
#include <scantling/registration/quality.hpp>
#include <scantling/registration/stein_icp.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "detail/config_checks.hpp"
#include "detail/stein_gradient.hpp"
#include "detail/stein_summary.hpp"
#include "detail/stein_update.hpp"

namespace scantling::registration {
namespace {

using detail::require_at_least;
using detail::require_open_unit;
using detail::require_positive;

// Stream of the initial sampling: batch streams are t · K + i, far below this id.
constexpr std::uint64_t kInitStream = ~std::uint64_t{0};

void require_non_negative(const Vector6d& v, std::string_view prefix, std::string_view field) {
    for (int d = 0; d < 6; ++d) {
        if (!(v[d] >= 0.0) || !std::isfinite(v[d])) {
            throw ConfigError(
                fmt::format("{}.{}[{}] = {}, expected finite >= 0", prefix, field, d, v[d]));
        }
    }
}

void check_inputs(const PointCloud& source, const PointCloud& target, const KdTree& tree,
                  const Eigen::Isometry3d& T_guess, BackFaces back_faces) {
    check_usable(source, "stein_icp source");
    check_usable(target, "stein_icp target");
    if (tree.size() != target.size()) {
        throw InputError(
            fmt::format("stein_icp: the target k-d tree holds {} points, the target {}",
                        tree.size(), target.size()));
    }
    if (!T_guess.matrix().allFinite()) throw InputError("stein_icp: non-finite initial guess");
    if (back_faces == BackFaces::kReject && !target.has_normals()) {
        throw InputError(
            "stein_icp: back_faces = reject needs target normals pointing to the free side");
    }
}

std::vector<Vector6d> init_from_bounds(const Vector6d& guess, const SteinIcpConfig& config,
                                       std::span<const int> free_dofs, Rng& rng) {
    std::vector<Vector6d> particles(static_cast<std::size_t>(config.num_particles), guess);
    for (Vector6d& x : particles) {
        for (const int d : free_dofs) {
            x[d] += rng.uniform(-1.0, 1.0) * config.init_half_widths[d];
            if (detail::is_angle(d)) x[d] = detail::wrap_angle(x[d]);
        }
    }
    return particles;
}

/// SPEC §7: ICP runs from the structure centre with yaws spread over [−π, π].
std::vector<Vector6d> icp_seeds(const PointCloud& source, const PointCloud& target,
                                const KdTree& tree, const Vector6d& guess,
                                const SteinIcpConfig& config) {
    IcpConfig icp;
    icp.method = target.has_normals() ? IcpMethod::kPointToPlane : IcpMethod::kPointToPoint;
    icp.max_iterations = config.seed_icp_iterations;
    icp.max_correspondence_distance_m = config.max_correspondence_distance_m;
    icp.covariance = IcpCovariance::kHessian;  // only the pose is used: skip the scores
    icp.parallel = config.parallel;
    std::vector<Vector6d> seeds;
    for (int s = 0; s < config.num_yaw_seeds; ++s) {
        Vector6d start = guess;
        start[5] = -std::numbers::pi + 2.0 * std::numbers::pi * s / config.num_yaw_seeds;
        const RegistrationResult r =
            align(source, target, tree, isometry_from_pose_params(start), icp);
        Vector6d x = pose_params_from_isometry(r.T_target_source);
        if (config.reduced_3dof) x.segment<3>(2) = guess.segment<3>(2);
        seeds.push_back(x);
    }
    return seeds;
}

std::vector<Vector6d> init_from_icp(const PointCloud& source, const PointCloud& target,
                                    const KdTree& tree, const Vector6d& guess,
                                    const SteinIcpConfig& config, std::span<const int> free_dofs,
                                    Rng& rng) {
    const std::vector<Vector6d> seeds = icp_seeds(source, target, tree, guess, config);
    std::vector<Vector6d> particles;
    for (int i = 0; i < config.num_particles; ++i) {
        Vector6d x = seeds[static_cast<std::size_t>(i) % seeds.size()];
        for (const int d : free_dofs) {
            x[d] += rng.uniform(-1.0, 1.0) * config.seed_jitter[d];
            if (detail::is_angle(d)) x[d] = detail::wrap_angle(x[d]);
        }
        particles.push_back(x);
    }
    return particles;
}

std::vector<int> free_dofs_of(const SteinIcpConfig& config) {
    return config.reduced_3dof ? std::vector<int>{0, 1, 5} : std::vector<int>{0, 1, 2, 3, 4, 5};
}

}  // namespace

void SteinIcpConfig::validate(std::string_view prefix) const {
    require_at_least(num_particles, 2, prefix, "num_particles");
    require_at_least(iterations, 1, prefix, "iterations");
    require_at_least(batch_size, 1, prefix, "batch_size");
    require_positive(max_correspondence_distance_m, prefix, "max_correspondence_distance_m");
    require_positive(noise_sigma_m, prefix, "noise_sigma_m");
    require_positive(translation_lr_m, prefix, "translation_lr_m");
    require_positive(rotation_lr_rad, prefix, "rotation_lr_rad");
    if (!(final_lr_fraction > 0.0 && final_lr_fraction <= 1.0)) {
        throw ConfigError(fmt::format("{}.final_lr_fraction = {}, expected in (0, 1]", prefix,
                                      final_lr_fraction));
    }
    require_at_least(refine_iterations, 0, prefix, "refine_iterations");
    if (!(refine_step > 0.0 && refine_step <= 1.0)) {
        throw ConfigError(
            fmt::format("{}.refine_step = {}, expected in (0, 1]", prefix, refine_step));
    }
    require_non_negative(init_half_widths, prefix, "init_half_widths");
    require_at_least(num_yaw_seeds, 1, prefix, "num_yaw_seeds");
    require_at_least(seed_icp_iterations, 1, prefix, "seed_icp_iterations");
    require_non_negative(seed_jitter, prefix, "seed_jitter");
    require_open_unit(min_mode_fraction, prefix, "min_mode_fraction");
    parallel.validate(fmt::format("{}.parallel", prefix));
}

SteinIcpResult stein_icp(const PointCloud& source, const PointCloud& target,
                         const Eigen::Isometry3d& T_target_source_guess,
                         const SteinIcpConfig& config) {
    config.validate();
    check_usable(target, "stein_icp target");
    const KdTree tree(target.points);
    return stein_icp(source, target, tree, T_target_source_guess, config);
}

SteinIcpResult stein_icp(const PointCloud& source, const PointCloud& target,
                         const KdTree& target_tree, const Eigen::Isometry3d& T_target_source_guess,
                         const SteinIcpConfig& config) {
    config.validate();
    check_inputs(source, target, target_tree, T_target_source_guess, config.back_faces);
    const Vector6d guess = pose_params_from_isometry(T_target_source_guess);
    const std::vector<int> free_dofs = free_dofs_of(config);
    Rng init_rng = Rng(config.seed).split(kInitStream);
    SteinIcpResult result;
    result.particles =
        config.init == SteinInit::kBounds
            ? init_from_bounds(guess, config, free_dofs, init_rng)
            : init_from_icp(source, target, target_tree, guess, config, free_dofs, init_rng);
    detail::run_svgd(result.particles, source.points, target_tree, target.normals, config);
    detail::summarize_particles(result, free_dofs, config.min_mode_fraction);
    const CorrespondenceQuality q =
        evaluate_correspondences(transformed(source, result.T_target_source), target_tree,
                                 config.max_correspondence_distance_m, config.parallel);
    result.fitness = q.fitness;
    result.rmse_m = q.rmse_m;
    return result;
}

}  // namespace scantling::registration
