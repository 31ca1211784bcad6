#include <scantling/core/error.hpp>
#include <scantling/core/normals.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/registration/constrained_icp.hpp>

#include <cmath>

#include <fmt/format.h>

#include "detail/config_checks.hpp"
#include "detail/linearize.hpp"
#include "detail/solver.hpp"

namespace scantling::registration {
namespace {

using detail::require_at_least;
using detail::require_open_unit;
using detail::require_positive;

/// SPEC §6 input filter: voxel grid, then a seeded uniform thinning to `max_points`.
PointCloud filtered(const PointCloud& cloud, const ConstrainedIcpConfig& config,
                    std::uint64_t stream) {
    PointCloud out = config.voxel_size_m > 0.0
                         ? voxel_downsample(cloud, {.voxel_size_m = config.voxel_size_m,
                                                    .parallel = config.parallel})
                         : cloud;
    if (config.max_points == 0 || out.size() <= config.max_points) return out;
    const std::vector<std::size_t> keep =
        Rng(config.seed).split(stream).sample_indices(out.size(), config.max_points);
    return select(out, keep);
}

detail::DofBasis dof_basis(bool planar) {
    if (!planar) return Matrix6d::Identity();
    detail::DofBasis basis = detail::DofBasis::Zero(6, 3);
    basis(0, 0) = 1.0;  // x
    basis(1, 1) = 1.0;  // y
    basis(5, 2) = 1.0;  // yaw
    return basis;
}

/// Empty when the correction is within the caps, otherwise which cap and by how much.
std::string cap_violation(const Eigen::Isometry3d& T, const Eigen::Isometry3d& prior,
                          const ConstrainedIcpConfig& config) {
    const Eigen::Isometry3d correction = T * prior.inverse();
    const double angle_rad = rotation_angle_rad(correction.linear());
    const double distance_m = correction.translation().norm();
    if (angle_rad > config.max_rotation_rad) {
        return fmt::format("rotation {:.4f} rad > max_rotation_rad = {}", angle_rad,
                           config.max_rotation_rad);
    }
    if (distance_m > config.max_translation_m) {
        return fmt::format("translation {:.4f} m > max_translation_m = {}", distance_m,
                           config.max_translation_m);
    }
    return "";
}

detail::IterationSettings settings_of(const ConstrainedIcpConfig& config,
                                      const Eigen::Isometry3d& prior) {
    return {.max_iterations = config.max_iterations,
            .translation_tolerance_m = config.translation_tolerance_m,
            .rotation_tolerance_rad = config.rotation_tolerance_rad,
            .min_correspondences = config.min_correspondences,
            .degeneracy_threshold = config.degeneracy_threshold,
            .basis = dof_basis(config.planar),
            .covariance = {},  // kHessian: stop clouds are small patches, few cells
            .cap_violation = [&config, prior](const Eigen::Isometry3d& T) {
                return cap_violation(T, prior, config);
            }};
}

}  // namespace

void ConstrainedIcpConfig::validate(std::string_view prefix) const {
    require_at_least(num_neighbors, 3, prefix, "num_neighbors");
    require_at_least(max_iterations, 1, prefix, "max_iterations");
    require_positive(max_correspondence_distance_m, prefix, "max_correspondence_distance_m");
    require_positive(kernel_scale_m, prefix, "kernel_scale_m");
    require_positive(max_rotation_rad, prefix, "max_rotation_rad");
    require_positive(max_translation_m, prefix, "max_translation_m");
    require_positive(rotation_tolerance_rad, prefix, "rotation_tolerance_rad");
    require_positive(translation_tolerance_m, prefix, "translation_tolerance_m");
    if (!(voxel_size_m >= 0.0) || !std::isfinite(voxel_size_m)) {
        throw ConfigError(fmt::format("{}.voxel_size_m = {}, expected finite >= 0 (0 = off)",
                                      prefix, voxel_size_m));
    }
    require_at_least(min_correspondences, 6, prefix, "min_correspondences");
    require_open_unit(degeneracy_threshold, prefix, "degeneracy_threshold");
    parallel.validate(fmt::format("{}.parallel", prefix));
}

RegistrationResult align_constrained(const PointCloud& source, const PointCloud& target,
                                     const ConstrainedIcpConfig& config,
                                     const Eigen::Isometry3d& T_target_source_prior) {
    config.validate();
    check_usable(source, "constrained_icp source");
    check_usable(target, "constrained_icp target");
    if (!T_target_source_prior.matrix().allFinite()) {
        throw InputError("constrained_icp: T_target_source_prior is not finite");
    }
    const PointCloud src = filtered(source, config, 0);
    PointCloud tgt = filtered(target, config, 1);
    const KdTree tree(tgt.points);
    if (!tgt.has_normals()) {
        estimate_normals(tgt, tree,
                         {.num_neighbors = config.num_neighbors,
                          .viewpoint = Eigen::Vector3d::Zero(),
                          .parallel = config.parallel});
    }
    const detail::Problem problem{
        .source_points = &src.points,
        .target_tree = &tree,
        .target_normals = &tgt.normals,
        .method = IcpMethod::kPointToPlane,
        .max_correspondence_distance_m = config.max_correspondence_distance_m,
        .kernel = config.kernel,
        .kernel_scale_m = config.kernel_scale_m,
        .parallel = config.parallel};
    return detail::iterate(problem, src.size(), T_target_source_prior,
                           settings_of(config, T_target_source_prior));
}

Eigen::Isometry3d corrected_map_pose(const Eigen::Isometry3d& P_prev,
                                     const Eigen::Isometry3d& P_cprev,
                                     const Eigen::Isometry3d& P_cnew, const Eigen::Isometry3d& C) {
    // T_map_new = T_map_prev · T_prev_loc · T_loc_new · T_predicted_new: the localisation's
    // relative motion between the stops, applied to the corrected previous pose, then corrected.
    return P_prev * P_cprev.inverse() * P_cnew * C;
}

}  // namespace scantling::registration
