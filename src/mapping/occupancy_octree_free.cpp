// OccupancyOctree::mark_free (occupancy_octree.hpp): the space a vehicle occupies.
#include <array>
#include <cmath>

#include "detail/occupancy_octree_impl.hpp"

namespace scantling::mapping {

std::size_t OccupancyOctree::mark_free(const Eigen::AlignedBox3d& box_world) {
    if (!box_world.min().allFinite() || !box_world.max().allFinite())
        throw InputError("occupancy_octree: mark_free box is not finite");
    if (box_world.isEmpty()) return 0;
    const double res_m = impl_->config.resolution_m;
    // Every voxel the closed box touches (box_is_free's set): voxel i spans [i, i + 1) · res_m.
    std::array<long long, 3> first{}, last{};
    for (int axis = 0; axis < 3; ++axis) {
        first[axis] = static_cast<long long>(std::floor(box_world.min()[axis] / res_m));
        last[axis] = static_cast<long long>(std::floor(box_world.max()[axis] / res_m));
        if (first[axis] < -detail::kKeyOffset || last[axis] >= detail::kKeyOffset) {
            throw InputError(
                fmt::format("occupancy_octree: mark_free box exceeds the map's extent (±{} m)",
                            detail::kHalfKeyRange * res_m));
        }
    }
    std::size_t marked = 0;
    for (long long x = first[0]; x <= last[0]; ++x) {
        for (long long y = first[1]; y <= last[1]; ++y) {
            for (long long z = first[2]; z <= last[2]; ++z) {
                const octomap::OcTreeKey key(
                    static_cast<octomap::key_type>(x + detail::kKeyOffset),
                    static_cast<octomap::key_type>(y + detail::kKeyOffset),
                    static_cast<octomap::key_type>(z + detail::kKeyOffset));
                if (impl_->tree.search(key) != nullptr) continue;  // known: left as seen
                impl_->tree.updateNode(key, false);
                ++marked;
            }
        }
    }
    return marked;
}

}  // namespace scantling::mapping
