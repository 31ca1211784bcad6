#include <scantling/core/error.hpp>
#include <scantling/core/normals.hpp>
#include <scantling/registration/icp.hpp>

#include <array>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "detail/config_checks.hpp"
#include "detail/linearize.hpp"
#include "detail/solver.hpp"

namespace scantling::registration {
namespace {

using detail::require_at_least;
using detail::require_open_unit;
using detail::require_positive;

constexpr detail::EnumNames<IcpMethod, 3> kMethodNames = {{
    {IcpMethod::kPointToPoint, "point_to_point"},
    {IcpMethod::kPointToPlane, "point_to_plane"},
    {IcpMethod::kGeneralized, "gicp"},
}};

constexpr detail::EnumNames<IcpCovariance, 2> kCovarianceNames = {{
    {IcpCovariance::kHessian, "hessian"},
    {IcpCovariance::kClusteredSandwich, "clustered_sandwich"},
}};

constexpr detail::EnumNames<BackFaces, 3> kBackFaceNames = {{
    {BackFaces::kKeep, "keep"},
    {BackFaces::kPreferFront, "prefer_front"},
    {BackFaces::kReject, "reject"},
}};

/// Normals and covariances estimated here when the clouds lack them (owned for the call).
struct Prepared {
    std::vector<Eigen::Vector3d> target_normals;
    std::vector<Eigen::Matrix3d> target_covariances;
    std::vector<Eigen::Matrix3d> source_covariances;
};

void check_inputs(const PointCloud& source, const PointCloud& target, const KdTree& tree,
                  const Eigen::Isometry3d& T_init, const IcpConfig& config) {
    check_usable(source, "icp source");
    check_usable(target, "icp target");
    if (tree.size() != target.size()) {
        throw InputError(fmt::format("icp: the target k-d tree holds {} points, the target {}",
                                     tree.size(), target.size()));
    }
    if (!T_init.matrix().allFinite()) {
        throw InputError("icp: T_target_source_init is not finite");
    }
    if (config.back_faces == BackFaces::kReject && !target.has_normals()) {
        throw InputError("icp: back_faces = reject needs target normals pointing to the free side");
    }
}

std::vector<Eigen::Vector3d> target_normals(const PointCloud& target, const KdTree& tree,
                                            const IcpConfig& config) {
    PointCloud copy;
    copy.points = target.points;
    estimate_normals(copy, tree,
                     {.num_neighbors = config.num_neighbors,
                      .viewpoint = Eigen::Vector3d::Zero(),
                      .parallel = config.parallel});
    return std::move(copy.normals);
}

std::vector<Eigen::Matrix3d> covariances(const PointCloud& cloud, const KdTree* tree,
                                         const IcpConfig& config) {
    PointCloud copy;
    copy.points = cloud.points;
    const CovarianceConfig covariance_config{.num_neighbors = config.num_neighbors,
                                             .parallel = config.parallel};
    if (tree != nullptr) {
        estimate_covariances(copy, *tree, covariance_config);
    } else {
        estimate_covariances(copy, covariance_config);
    }
    return std::move(copy.covariances);
}

detail::Problem make_problem(const PointCloud& source, const PointCloud& target, const KdTree& tree,
                             const IcpConfig& config, Prepared& prepared) {
    detail::Problem p{.source_points = &source.points,
                      .target_tree = &tree,
                      .method = config.method,
                      .max_correspondence_distance_m = config.max_correspondence_distance_m,
                      .kernel = config.kernel,
                      .kernel_scale_m = config.kernel_scale_m,
                      .parallel = config.parallel,
                      .front_normals = target.has_normals() ? &target.normals : nullptr,
                      .back_faces = config.back_faces};
    if (config.method == IcpMethod::kPointToPlane) {
        if (!target.has_normals()) prepared.target_normals = target_normals(target, tree, config);
        p.target_normals = target.has_normals() ? &target.normals : &prepared.target_normals;
    }
    if (config.method == IcpMethod::kGeneralized) {
        if (!target.has_covariances())
            prepared.target_covariances = covariances(target, &tree, config);
        if (!source.has_covariances())
            prepared.source_covariances = covariances(source, nullptr, config);
        p.target_covariances =
            target.has_covariances() ? &target.covariances : &prepared.target_covariances;
        p.source_covariances =
            source.has_covariances() ? &source.covariances : &prepared.source_covariances;
    }
    return p;
}

}  // namespace

std::string_view to_string(IcpMethod method) { return detail::enum_name(kMethodNames, method); }

IcpMethod icp_method_from_string(std::string_view name, std::string_view field) {
    return detail::enum_value(kMethodNames, name, field);
}

std::string_view to_string(BackFaces mode) { return detail::enum_name(kBackFaceNames, mode); }

BackFaces back_faces_from_string(std::string_view name, std::string_view field) {
    return detail::enum_value(kBackFaceNames, name, field);
}

std::string_view to_string(IcpCovariance model) {
    return detail::enum_name(kCovarianceNames, model);
}

IcpCovariance icp_covariance_from_string(std::string_view name, std::string_view field) {
    return detail::enum_value(kCovarianceNames, name, field);
}

void IcpConfig::validate(std::string_view prefix) const {
    require_at_least(max_iterations, 1, prefix, "max_iterations");
    require_positive(max_correspondence_distance_m, prefix, "max_correspondence_distance_m");
    require_positive(kernel_scale_m, prefix, "kernel_scale_m");
    require_positive(translation_tolerance_m, prefix, "translation_tolerance_m");
    require_positive(rotation_tolerance_rad, prefix, "rotation_tolerance_rad");
    require_at_least(min_correspondences, 6, prefix, "min_correspondences");
    require_at_least(num_neighbors, 3, prefix, "num_neighbors");
    require_open_unit(degeneracy_threshold, prefix, "degeneracy_threshold");
    require_positive(covariance_cell_size_m, prefix, "covariance_cell_size_m");
    if (!(map_error_sigma_m >= 0.0) || !std::isfinite(map_error_sigma_m)) {
        throw ConfigError(fmt::format("{}.map_error_sigma_m = {}, expected finite >= 0", prefix,
                                      map_error_sigma_m));
    }
    parallel.validate(fmt::format("{}.parallel", prefix));
}

RegistrationResult align(const PointCloud& source, const PointCloud& target,
                         const Eigen::Isometry3d& T_target_source_init, const IcpConfig& config) {
    config.validate();
    check_usable(target, "icp target");
    const KdTree tree(target.points);
    return align(source, target, tree, T_target_source_init, config);
}

RegistrationResult align(const PointCloud& source, const PointCloud& target,
                         const KdTree& target_tree, const Eigen::Isometry3d& T_target_source_init,
                         const IcpConfig& config) {
    config.validate();
    check_inputs(source, target, target_tree, T_target_source_init, config);
    Prepared prepared;
    const detail::Problem problem = make_problem(source, target, target_tree, config, prepared);
    const detail::IterationSettings settings{
        .max_iterations = config.max_iterations,
        .translation_tolerance_m = config.translation_tolerance_m,
        .rotation_tolerance_rad = config.rotation_tolerance_rad,
        .min_correspondences = config.min_correspondences,
        .degeneracy_threshold = config.degeneracy_threshold,
        .basis = Matrix6d::Identity(),
        .covariance = {.model = config.covariance,
                       .cell_size_m = config.covariance_cell_size_m,
                       .map_error_sigma_m = config.map_error_sigma_m},
        .cap_violation = {}};
    return detail::iterate(problem, source.size(), T_target_source_init, settings);
}

}  // namespace scantling::registration
