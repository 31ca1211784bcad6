// Queries of OccupancyOctree for planning (SPEC §8): is a box all known free (collision
// checks), is a line of sight clear, and where are the frontiers between free and unknown.
// All walk OctoMap's leaves, which merge uniform space: a box or a face of free space costs
// per leaf, not per voxel.
#include <scantling/mapping/occupancy_octree.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include <scantling/core/error.hpp>

#include "detail/occupancy_octree_impl.hpp"

namespace scantling::mapping {
namespace {

using detail::kKeyOffset;
constexpr int kTreeDepth = 16;

/// Inclusive key range per axis.
struct KeyBox {
    std::array<long long, 3> lo{};
    std::array<long long, 3> hi{};
};

/// Keys of the voxels the closed box touches; nullopt when a voxel lies outside the map.
std::optional<KeyBox> key_box(const Eigen::AlignedBox3d& box, double res_m) {
    KeyBox keys;
    for (int axis = 0; axis < 3; ++axis) {
        keys.lo[axis] = static_cast<long long>(std::floor(box.min()[axis] / res_m)) + kKeyOffset;
        keys.hi[axis] = static_cast<long long>(std::floor(box.max()[axis] / res_m)) + kKeyOffset;
        if (keys.lo[axis] < 0 || keys.hi[axis] > 65535) return std::nullopt;
    }
    return keys;
}

octomap::OcTreeKey to_key(const std::array<long long, 3>& k) {
    return {static_cast<octomap::key_type>(k[0]), static_cast<octomap::key_type>(k[1]),
            static_cast<octomap::key_type>(k[2])};
}

void require_finite_box(const Eigen::AlignedBox3d& box, const char* what) {
    if (!box.min().allFinite() || !box.max().allFinite())
        throw InputError(fmt::format("occupancy_octree: {} box is not finite", what));
}

/// The key range of the leaf at `depth` whose centre key is `key`.
KeyBox leaf_keys(const octomap::OcTreeKey& key, unsigned depth) {
    const long long size = 1LL << (kTreeDepth - static_cast<int>(depth));
    KeyBox leaf;
    for (int axis = 0; axis < 3; ++axis) {
        leaf.lo[axis] = static_cast<long long>(key[axis]) - size / 2;
        leaf.hi[axis] = leaf.lo[axis] + size - 1;
    }
    return leaf;
}

/// Voxels of `a` ∩ `b` (0 when disjoint).
std::uint64_t overlap_voxels(const KeyBox& a, const KeyBox& b) {
    std::uint64_t count = 1;
    for (int axis = 0; axis < 3; ++axis) {
        const long long lo = std::max(a.lo[axis], b.lo[axis]);
        const long long hi = std::min(a.hi[axis], b.hi[axis]);
        if (hi < lo) return 0;
        count *= static_cast<std::uint64_t>(hi - lo + 1);
    }
    return count;
}

/// True when any voxel of the cube of `size` keys at `lo` next to a face (the layer
/// `axis` = lo[axis] when `near_low`, else the far layer) is unknown: descends only where the
/// cube is split into children.
bool face_layer_has_unknown(const octomap::OcTree& tree, std::array<long long, 3> lo,
                            long long size, long long cell, int axis, bool near_low) {
    const unsigned depth =
        static_cast<unsigned>(kTreeDepth - std::countr_zero(static_cast<unsigned long long>(size)));
    const octomap::OcTreeNode* node = tree.search(to_key(lo), depth);
    if (node == nullptr) return true;
    if (size <= cell || !tree.nodeHasChildren(node)) return false;
    const long long half = size / 2;
    if (!near_low) lo[axis] += half;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int i = 0; i < 4; ++i) {
        std::array<long long, 3> child = lo;
        child[u] += (i & 1) != 0 ? half : 0;
        child[v] += (i & 2) != 0 ? half : 0;
        if (face_layer_has_unknown(tree, child, half, cell, axis, near_low)) return true;
    }
    return false;
}

/// Centre of voxel key `k` along one axis, metres.
double key_centre_m(long long k, double res_m) {
    return (static_cast<double>(k - kKeyOffset) + 0.5) * res_m;
}

/// The frontier points of one free leaf (see frontier_points) appended to `out`.
void leaf_frontiers(const octomap::OcTree& tree, const KeyBox& leaf, long long cell,
                    const Eigen::AlignedBox3d& bounds, double res_m,
                    std::vector<Eigen::Vector3d>& out) {
    const long long size = leaf.hi[0] - leaf.lo[0] + 1;
    Eigen::Vector3d centre;
    for (int i = 0; i < 3; ++i)
        centre[i] = (static_cast<double>(leaf.lo[i] - kKeyOffset) + size / 2.0) * res_m;
    for (int axis = 0; axis < 3; ++axis) {
        for (const bool high : {false, true}) {
            std::array<long long, 3> lo = leaf.lo;
            lo[axis] = high ? leaf.hi[axis] + 1 : leaf.lo[axis] - size;
            const long long layer = high ? lo[axis] : leaf.lo[axis] - 1;
            const double layer_m = key_centre_m(layer, res_m);
            if (lo[axis] < 0 || lo[axis] + size - 1 > 65535) continue;
            if (layer_m < bounds.min()[axis] || layer_m > bounds.max()[axis]) continue;
            if (!face_layer_has_unknown(tree, lo, size, cell, axis, high)) continue;
            Eigen::Vector3d p = centre;
            p[axis] = key_centre_m(high ? leaf.hi[axis] : leaf.lo[axis], res_m);
            if (bounds.contains(p)) out.push_back(p);
        }
    }
}

}  // namespace

bool OccupancyOctree::box_is_free(const Eigen::AlignedBox3d& box_world) const {
    require_finite_box(box_world, "box_is_free");
    if (box_world.isEmpty()) return true;
    const std::optional<KeyBox> box = key_box(box_world, impl_->config.resolution_m);
    const octomap::OcTree& tree = impl_->tree;
    if (!box || tree.size() == 0) return false;
    const KeyBox all{{0, 0, 0},
                     {box->hi[0] - box->lo[0], box->hi[1] - box->lo[1], box->hi[2] - box->lo[2]}};
    const std::uint64_t needed = overlap_voxels(all, all);
    std::uint64_t free = 0;
    for (auto it = tree.begin_leafs_bbx(to_key(box->lo), to_key(box->hi)),
              end = tree.end_leafs_bbx();
         it != end; ++it) {
        const std::uint64_t inside = overlap_voxels(leaf_keys(it.getKey(), it.getDepth()), *box);
        if (inside == 0) continue;  // OctoMap's bbx test is one key generous
        if (tree.isNodeOccupied(*it)) return false;
        free += inside;
    }
    return free == needed;
}

bool OccupancyOctree::line_of_sight(const Eigen::Vector3d& from_world,
                                    const Eigen::Vector3d& to_world) const {
    if (!from_world.allFinite() || !to_world.allFinite())
        throw InputError("occupancy_octree: line_of_sight end point is not finite");
    octomap::KeyRay ray;
    if (!impl_->tree.computeRayKeys(detail::to_point3d(from_world), detail::to_point3d(to_world),
                                    ray))
        return false;
    for (const octomap::OcTreeKey& key : ray) {
        const octomap::OcTreeNode* node = impl_->tree.search(key);
        if (node != nullptr && impl_->tree.isNodeOccupied(node)) return false;
    }
    return true;
}

std::vector<Eigen::Vector3d> OccupancyOctree::frontier_points(
    const Eigen::AlignedBox3d& bounds_world, int coarse_levels) const {
    require_finite_box(bounds_world, "frontier_points");
    if (coarse_levels < 0 || coarse_levels > 8) {
        throw InputError(
            fmt::format("occupancy_octree: frontier_points coarse_levels = {}, expected in [0, 8]",
                        coarse_levels));
    }
    const long long cell = 1LL << coarse_levels;
    const auto max_depth = static_cast<unsigned char>(kTreeDepth - coarse_levels);
    std::vector<Eigen::Vector3d> points;
    const double res_m = impl_->config.resolution_m;
    const std::optional<KeyBox> box = key_box(bounds_world, res_m);
    const octomap::OcTree& tree = impl_->tree;
    if (bounds_world.isEmpty() || !box || tree.size() == 0) return points;
    // Cut at max_depth, a node stands for its cell; its occupancy is its children's maximum
    // (OctoMap keeps inner nodes updated), so a "free" coarse cell holds no occupied voxel.
    for (auto it = tree.begin_leafs_bbx(to_key(box->lo), to_key(box->hi), max_depth),
              end = tree.end_leafs_bbx();
         it != end; ++it) {
        if (tree.isNodeOccupied(*it)) continue;
        leaf_frontiers(tree, leaf_keys(it.getKey(), it.getDepth()), cell, bounds_world, res_m,
                       points);
    }
    return points;
}

}  // namespace scantling::mapping
