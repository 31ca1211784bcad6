#include <scantling/core/error.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/registration/robust_registration.hpp>

#include <memory>

#include <fmt/format.h>

#include "detail/config_checks.hpp"

namespace scantling::registration {
namespace {

/// A downsampled cloud with normals, its tree and its descriptors.
struct Prepared {
    PointCloud cloud;
    std::unique_ptr<KdTree> tree;
    FeatureMatrix features;
};

Prepared prepare(const PointCloud& input, const FpfhPipelineConfig& config, std::string_view what) {
    check_usable(input, what);
    Prepared p;
    VoxelGridConfig voxel;
    voxel.voxel_size_m = config.voxel_size_m;
    voxel.parallel = config.fpfh.parallel;
    p.cloud = voxel_downsample(input, voxel);
    if (p.cloud.size() < 3) {
        throw InputError(
            fmt::format("register_fpfh_teaser: {} has {} points after {} m voxels, "
                        "expected >= 3",
                        what, p.cloud.size(), config.voxel_size_m));
    }
    p.tree = std::make_unique<KdTree>(p.cloud.points);
    estimate_normals(p.cloud, *p.tree, config.normals);
    p.features = compute_fpfh(p.cloud, *p.tree, config.fpfh);
    return p;
}

}  // namespace

void FpfhPipelineConfig::validate(std::string_view prefix) const {
    detail::require_positive(voxel_size_m, prefix, "voxel_size_m");
    normals.validate(fmt::format("{}.normals", prefix));
    fpfh.validate(fmt::format("{}.fpfh", prefix));
    match.validate(fmt::format("{}.match", prefix));
    if (tuple_filter) tuple_filter->validate(fmt::format("{}.tuple_filter", prefix));
    robust.validate(fmt::format("{}.robust", prefix));
    if (refine) refine->validate(fmt::format("{}.refine", prefix));
}

FpfhPipelineResult register_fpfh_teaser(const PointCloud& source, const PointCloud& target,
                                        const FpfhPipelineConfig& config) {
    config.validate();
    const Prepared src = prepare(source, config, "source");
    const Prepared tgt = prepare(target, config, "target");
    std::vector<Correspondence> matches = match_features(src.features, tgt.features, config.match);
    if (config.tuple_filter) {
        Rng rng(config.seed);
        matches =
            tuple_filter(matches, src.cloud.points, tgt.cloud.points, *config.tuple_filter, rng);
    }
    FpfhPipelineResult result;
    result.num_source_points = src.cloud.size();
    result.num_target_points = tgt.cloud.size();
    result.num_correspondences = matches.size();
    result.robust = robust_register(src.cloud, tgt.cloud, matches, config.robust);
    result.registration = result.robust.registration;
    if (!config.refine || !result.robust.registration.converged) return result;
    RegistrationResult icp = align(src.cloud, tgt.cloud, *tgt.tree,
                                   result.robust.registration.T_target_source, *config.refine);
    if (icp.converged) {
        result.registration = std::move(icp);
        result.refined = true;
    }
    return result;
}

}  // namespace scantling::registration
