#include <scantling/mapping/occupancy_octree.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <ostream>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <octomap/OcTree.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>

#include "detail/occupancy_octree_impl.hpp"

namespace scantling::mapping {
namespace {

using detail::kHalfKeyRange;
using detail::kKeyOffset;
using detail::to_point3d;

void require_below(double value, double bound, std::string_view prefix, std::string_view field,
                   std::string_view bound_name) {
    config_checks::require(value < bound, prefix, field, value,
                           fmt::format("< {} = {}", bound_name, bound));
}

void require_above(double value, double bound, std::string_view prefix, std::string_view field,
                   std::string_view bound_name) {
    config_checks::require(value > bound, prefix, field, value,
                           fmt::format("> {} = {}", bound_name, bound));
}

struct LeafVolumes {
    double free_m3 = 0.0;
    double occupied_m3 = 0.0;
};

LeafVolumes leaf_volumes(const octomap::OcTree& tree) {
    LeafVolumes volumes;
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
        const double edge_m = it.getSize();
        (tree.isNodeOccupied(*it) ? volumes.occupied_m3 : volumes.free_m3) +=
            edge_m * edge_m * edge_m;
    }
    return volumes;
}

}  // namespace

void OccupancyOctreeConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(resolution_m, prefix, "resolution_m");
    require_positive(max_range_m, prefix, "max_range_m");
    // A sensor anywhere in the inner half of the map must reach no farther than its edge.
    require(max_range_m <= kHalfKeyRange / 2.0 * resolution_m, prefix, "max_range_m", max_range_m,
            fmt::format("<= 16384 · resolution_m = {} (half the map's half-extent)",
                        kHalfKeyRange / 2.0 * resolution_m));
    require(prob_hit > 0.5 && prob_hit < 1.0, prefix, "prob_hit", prob_hit, "in (0.5, 1)");
    require(prob_miss > 0.0 && prob_miss < 0.5, prefix, "prob_miss", prob_miss, "in (0, 0.5)");
    require_open_unit(occupied_threshold, prefix, "occupied_threshold");
    require(clamp_min > 0.0, prefix, "clamp_min", clamp_min, "> 0");
    require_below(clamp_min, occupied_threshold, prefix, "clamp_min", "occupied_threshold");
    require(clamp_max < 1.0, prefix, "clamp_max", clamp_max, "< 1");
    require_above(clamp_max, occupied_threshold, prefix, "clamp_max", "occupied_threshold");
}

OccupancyOctree::OccupancyOctree(const OccupancyOctreeConfig& config) {
    config.validate("occupancy_octree");
    impl_ = std::make_unique<Impl>(config);
}

OccupancyOctree::~OccupancyOctree() = default;
OccupancyOctree::OccupancyOctree(OccupancyOctree&&) noexcept = default;
OccupancyOctree& OccupancyOctree::operator=(OccupancyOctree&&) noexcept = default;

DepthInsertStats OccupancyOctree::insert_depth_frame(const PointCloud& points_sensor,
                                                     const Eigen::Isometry3d& T_world_sensor) {
    if (!T_world_sensor.matrix().allFinite())
        throw InputError("occupancy_octree: T_world_sensor is not finite");
    impl_->check_origin(T_world_sensor.translation());
    const OccupancyOctreeConfig& c = impl_->config;
    // A miss is cut (in double, before OctoMap's float maths) to a length that stays beyond
    // max_range_m even after discretisation moves it to its voxel centre (≤ 0.87 voxel), so
    // OctoMap clears up to max_range_m and never marks its end occupied; an enormous point
    // would otherwise overflow float.
    const double cut_m = c.max_range_m + 2.0 * c.resolution_m;
    DepthInsertStats stats;
    octomap::Pointcloud cloud_world;
    cloud_world.reserve(points_sensor.size());
    for (const Eigen::Vector3d& p_sensor : points_sensor.points) {
        if (!p_sensor.allFinite()) {
            ++stats.dropped_non_finite;
            continue;
        }
        const double range_m = p_sensor.norm();
        const bool miss = range_m > c.max_range_m;
        stats.misses += miss ? 1 : 0;
        cloud_world.push_back(to_point3d(
            T_world_sensor * (miss ? Eigen::Vector3d(p_sensor * (cut_m / range_m)) : p_sensor)));
    }
    stats.points = cloud_world.size();
    impl_->tree.insertPointCloud(cloud_world, to_point3d(T_world_sensor.translation()),
                                 c.max_range_m, /*lazy_eval=*/false, c.discretize);
    return stats;
}

Occupancy OccupancyOctree::query(const Eigen::Vector3d& p_world) const {
    if (!p_world.allFinite()) {
        throw InputError(fmt::format("occupancy_octree: query point ({}, {}, {}) is not finite",
                                     p_world.x(), p_world.y(), p_world.z()));
    }
    octomap::OcTreeKey key;
    if (!impl_->tree.coordToKeyChecked(p_world.x(), p_world.y(), p_world.z(), key))
        return Occupancy::kUnknown;
    const octomap::OcTreeNode* node = impl_->tree.search(key);
    if (node == nullptr) return Occupancy::kUnknown;
    return impl_->tree.isNodeOccupied(node) ? Occupancy::kOccupied : Occupancy::kFree;
}

double OccupancyOctree::explored_volume_m3() const {
    const LeafVolumes volumes = leaf_volumes(impl_->tree);
    return volumes.free_m3 + volumes.occupied_m3;
}

double OccupancyOctree::free_volume_m3() const { return leaf_volumes(impl_->tree).free_m3; }

double OccupancyOctree::occupied_volume_m3() const { return leaf_volumes(impl_->tree).occupied_m3; }

double OccupancyOctree::unknown_volume_in_m3(const Eigen::AlignedBox3d& box_world) const {
    if (!box_world.min().allFinite() || !box_world.max().allFinite())
        throw InputError("occupancy_octree: unknown_volume_in_m3 box is not finite");
    const double res_m = impl_->config.resolution_m;
    // Voxel i spans [i, i + 1) · res_m; its centre is in the box when i + 0.5 ∈ [min, max] / res.
    std::array<long long, 3> first{}, last{};
    for (int axis = 0; axis < 3; ++axis) {
        first[axis] = static_cast<long long>(std::ceil(box_world.min()[axis] / res_m - 0.5));
        last[axis] = static_cast<long long>(std::floor(box_world.max()[axis] / res_m - 0.5));
        if (first[axis] > last[axis]) return 0.0;
        if (first[axis] < -kKeyOffset || last[axis] >= kKeyOffset) {
            throw InputError(fmt::format(
                "occupancy_octree: unknown_volume_in_m3 box exceeds the map's extent (±{} m)",
                kHalfKeyRange * res_m));
        }
    }
    std::size_t unknown = 0;
    for (long long x = first[0]; x <= last[0]; ++x) {
        for (long long y = first[1]; y <= last[1]; ++y) {
            for (long long z = first[2]; z <= last[2]; ++z) {
                const octomap::OcTreeKey key(static_cast<octomap::key_type>(x + kKeyOffset),
                                             static_cast<octomap::key_type>(y + kKeyOffset),
                                             static_cast<octomap::key_type>(z + kKeyOffset));
                unknown += impl_->tree.search(key) == nullptr ? 1 : 0;
            }
        }
    }
    return static_cast<double>(unknown) * res_m * res_m * res_m;
}

std::size_t OccupancyOctree::num_leaves() const { return impl_->tree.getNumLeafNodes(); }

double OccupancyOctree::resolution_m() const { return impl_->config.resolution_m; }

const OccupancyOctreeConfig& OccupancyOctree::config() const { return impl_->config; }

void OccupancyOctree::write_binary(const std::string& path) const {
    io::write_file_atomically(path, [&](std::ostream& out) {
        if (!impl_->tree.writeBinaryConst(out))
            throw FileError(path, "OctoMap could not write the tree");
    });
}

}  // namespace scantling::mapping
