#pragma once
/// @file Private to scantling_core: groups a cloud's points by voxel (used by voxel_grid.cpp).

#include <cstddef>
#include <span>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>

namespace scantling::detail {

/// Point indices sorted by voxel (lexicographic voxel index x, y, z; ascending point index
/// within a voxel) and where each voxel's run starts in `order`, plus a final end marker.
struct VoxelRuns {
    std::vector<std::size_t> order;
    std::vector<std::size_t> starts;

    std::size_t count() const { return starts.empty() ? 0 : starts.size() - 1; }
    std::span<const std::size_t> members(std::size_t v) const {
        return {order.data() + starts[v], starts[v + 1] - starts[v]};
    }
};

/// Voxel of a point: floor(p / voxel_size_m) per axis (grid anchored at the origin).
/// Throws InputError on a non-finite point or on voxel indices beyond the 64-bit range.
/// Deterministic and independent of the thread count. `cloud` must be non-empty.
VoxelRuns sort_into_voxels(const PointCloud& cloud, double voxel_size_m,
                           const ParallelConfig& parallel);

}  // namespace scantling::detail
