#pragma once
/// @file
/// OccupancyOctree's private state, shared by its source files (occupancy_octree.cpp: config,
/// insertion, volumes, file; occupancy_octree_view.cpp: view gains; occupancy_octree_query.cpp:
/// box, line-of-sight and frontier queries). Not installed: OctoMap stays private.

#include <Eigen/Core>
#include <string_view>

#include <fmt/format.h>
#include <octomap/OcTree.h>

#include <scantling/core/error.hpp>
#include <scantling/mapping/occupancy_octree.hpp>

namespace scantling::mapping {
namespace detail {

// OctoMap's 16-level tree: keys 0 … 65535 per axis, voxel index i ↔ key i + 32768.
constexpr double kHalfKeyRange = 32768.0;
constexpr int kKeyOffset = 32768;

inline octomap::point3d to_point3d(const Eigen::Vector3d& p) {
    return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

}  // namespace detail

struct OccupancyOctree::Impl {
    explicit Impl(const OccupancyOctreeConfig& c) : config(c), tree(c.resolution_m) {
        tree.setProbHit(c.prob_hit);
        tree.setProbMiss(c.prob_miss);
        tree.setClampingThresMin(c.clamp_min);
        tree.setClampingThresMax(c.clamp_max);
        tree.setOccupancyThres(c.occupied_threshold);
    }

    /// Rays must stay inside the map, or OctoMap drops them with a message on stderr.
    void check_origin(const Eigen::Vector3d& origin_world) const {
        const double reach_m = config.max_range_m + 2.0 * config.resolution_m;
        const double half_extent_m = detail::kHalfKeyRange * config.resolution_m;
        if (origin_world.cwiseAbs().maxCoeff() + reach_m >= half_extent_m) {
            throw InputError(fmt::format(
                "occupancy_octree: sensor at ({}, {}, {}) m is within max_range_m of the map's "
                "edge (±{} m at resolution_m = {})",
                origin_world.x(), origin_world.y(), origin_world.z(), half_extent_m,
                config.resolution_m));
        }
    }

    /// Walks one ray's voxels from its origin, collecting the unknown ones into `unknown`, up
    /// to the first occupied one; true when an occupied voxel stopped it.
    bool walk_ray(const octomap::point3d& origin, const octomap::point3d& end, octomap::KeyRay& ray,
                  octomap::KeySet& unknown) const {
        if (!tree.computeRayKeys(origin, end, ray)) return false;  // not after clipping
        for (const octomap::OcTreeKey& key : ray) {
            const octomap::OcTreeNode* node = tree.search(key);
            if (node == nullptr) {
                unknown.insert(key);
            } else if (tree.isNodeOccupied(node)) {
                return true;
            }
        }
        return false;
    }

    OccupancyOctreeConfig config;
    octomap::OcTree tree;
};

}  // namespace scantling::mapping
