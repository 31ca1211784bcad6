#pragma once
/// @file Inputs and settings shared by the core benchmarks and their agreement checks.

#include <memory>

#include <open3d/geometry/PointCloud.h>

#include <scantling/core/point_cloud.hpp>

namespace scantling::bench {

inline constexpr double kVoxelSizesM[] = {0.1, 0.5};  // mapping-scale and odometry-scale grids
inline constexpr int kNormalNeighbors = 30;           // both libraries: k = 30 nearest
inline constexpr int kKnnNeighbors = 10;              // kNN of every point
inline constexpr int kThreadCounts[] = {1, 2};

struct CoreInputs {
    PointCloud cloud;                                   ///< positions only
    std::shared_ptr<open3d::geometry::PointCloud> o3d;  ///< the same positions
};

/// Prints how far the two libraries' outputs agree (voxel counts, normal angles, kNN).
void print_agreement(const CoreInputs& inputs);

}  // namespace scantling::bench
