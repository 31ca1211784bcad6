#include "scantling/localization/localization_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/core/normals.hpp>
#include <scantling/core/voxel_grid.hpp>

#include "detail/config_checks.hpp"

namespace scantling::localization {
namespace {

/// 0..5: the dominant axis of the normal and its sign.
int normal_class(const Eigen::Vector3d& n) {
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    return 2 * axis + (n[axis] < 0.0 ? 1 : 0);
}

PointCloud with_estimated_normals(PointCloud cloud, const LocalizationMapConfig& config) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& p : cloud.points) centroid += p;
    centroid /= static_cast<double>(cloud.size());
    NormalEstimationConfig normals;
    normals.num_neighbors = config.normal_neighbors;
    normals.viewpoint = centroid;
    normals.parallel = config.parallel;
    estimate_normals(cloud, normals);
    return cloud;
}

std::unique_ptr<MapRegion> make_region(int compartment, PointCloud cloud,
                                       registration::FeatureMatrix descriptors) {
    auto region = std::make_unique<MapRegion>();
    region->compartment = compartment;
    region->tree = std::make_unique<KdTree>(cloud.points);
    region->cloud = std::move(cloud);
    region->descriptors = std::move(descriptors);
    return region;
}

std::unique_ptr<MapRegion> compartment_region(const MapRegion& whole, const io::Compartment& c,
                                              double margin_m) {
    std::vector<std::size_t> keep;
    const Eigen::Vector3d lo = c.bounds.min - Eigen::Vector3d::Constant(margin_m);
    const Eigen::Vector3d hi = c.bounds.max + Eigen::Vector3d::Constant(margin_m);
    for (std::size_t i = 0; i < whole.cloud.size(); ++i) {
        const Eigen::Vector3d& p = whole.cloud.points[i];
        if ((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all()) keep.push_back(i);
    }
    registration::FeatureMatrix descriptors(whole.descriptors.rows(),
                                            static_cast<Eigen::Index>(keep.size()));
    for (std::size_t k = 0; k < keep.size(); ++k) {
        descriptors.col(static_cast<Eigen::Index>(k)) =
            whole.descriptors.col(static_cast<Eigen::Index>(keep[k]));
    }
    return make_region(c.id, select(whole.cloud, keep), std::move(descriptors));
}

}  // namespace

void LocalizationMapConfig::validate(std::string_view prefix) const {
    detail::require_positive(voxel_size_m, prefix, "voxel_size_m");
    detail::require(normal_neighbors >= 3, prefix, "normal_neighbors", normal_neighbors, ">= 3");
    detail::require_non_negative(compartment_margin_m, prefix, "compartment_margin_m");
    fpfh.validate(std::string(prefix) + ".fpfh");
    likelihood.validate(std::string(prefix) + ".likelihood");
    parallel.validate(std::string(prefix) + ".parallel");
}

PointCloud downsample_by_normal_class(const PointCloud& cloud, double voxel_size_m,
                                      const ParallelConfig& parallel) {
    if (!cloud.has_normals()) return voxel_downsample(cloud, {voxel_size_m, parallel});
    std::array<std::vector<std::size_t>, 6> classes;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        classes[static_cast<std::size_t>(normal_class(cloud.normals[i]))].push_back(i);
    }
    PointCloud out;
    for (const auto& indices : classes) {
        if (indices.empty()) continue;
        append(out, voxel_downsample(select(cloud, indices), {voxel_size_m, parallel}));
    }
    return out;
}

const MapRegion& LocalizationMap::region(int compartment_id) const {
    for (const auto& r : regions_) {
        if (r->compartment == compartment_id) return *r;
    }
    return whole();
}

LocalizationMap LocalizationMap::build(const PointCloud& map,
                                       std::optional<io::StructuralMap> structure,
                                       const LocalizationMapConfig& config,
                                       const std::string& cache_path) {
    config.validate();
    check_usable(map, "map");
    LocalizationMap out;
    out.config_ = config;
    out.structure_ = std::move(structure);
    PointCloud source = map;
    source.intensities.clear();
    source.colors.clear();
    source.rings.clear();
    source.times_s.clear();
    source.covariances.clear();
    PointCloud cloud =
        map.has_normals()
            ? downsample_by_normal_class(source, config.voxel_size_m, config.parallel)
            : with_estimated_normals(
                  voxel_downsample(source, {config.voxel_size_m, config.parallel}), config);
    if (cloud.size() < 10) {
        throw InputError(fmt::format("map: {} points after {} m voxels, expected >= 10",
                                     cloud.size(), config.voxel_size_m));
    }
    const std::uint64_t key = descriptor_cache_key(cloud, config);
    std::optional<registration::FeatureMatrix> descriptors;
    if (!cache_path.empty()) {
        descriptors = read_descriptor_cache(cache_path, key, cloud.size(), out.cache_message_);
        out.descriptor_source_ = descriptors                  ? DescriptorSource::kCache
                                 : out.cache_message_.empty() ? DescriptorSource::kComputed
                                                              : DescriptorSource::kRecomputedStale;
    }
    auto whole = make_region(-1, std::move(cloud), {});
    if (!descriptors) {
        registration::FpfhConfig fpfh = config.fpfh;
        fpfh.parallel = config.parallel;
        descriptors = registration::compute_fpfh(whole->cloud, *whole->tree, fpfh);
        if (!cache_path.empty()) {
            try {
                write_descriptor_cache(cache_path, key, *descriptors);
            } catch (const Error& e) {
                out.cache_message_ = e.what();
            }
        }
    }
    whole->descriptors = std::move(*descriptors);
    out.regions_.push_back(std::move(whole));
    LikelihoodFieldConfig likelihood = config.likelihood;
    likelihood.parallel = config.parallel;
    out.likelihood_ = LikelihoodField(out.regions_.front()->cloud, likelihood);
    if (out.structure_) {
        for (const io::Compartment& c : out.structure_->compartments) {
            out.regions_.push_back(
                compartment_region(*out.regions_.front(), c, config.compartment_margin_m));
        }
    }
    return out;
}

}  // namespace scantling::localization
