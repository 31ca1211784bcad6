#pragma once
/// @file Deterministic voxel-grid downsampling (centroid per voxel).

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>

namespace scantling {

struct VoxelGridConfig {
    double voxel_size_m = 0.05;  ///< voxel edge, > 0
    ParallelConfig parallel;     ///< threads for key computation and sorting

    void validate(std::string_view prefix = "voxel_grid") const;
};

/// One point per occupied voxel at the centroid of its points; every present field is
/// averaged (normals re-normalised, colours rounded, rings take the most common value of the
/// voxel, covariances averaged). Output order is by voxel key, independent of the thread count
/// and of the input order's scheduling: the same input gives the same output.
/// Throws InputError on non-finite points, ConfigError on a bad voxel size.
PointCloud voxel_downsample(const PointCloud& cloud, const VoxelGridConfig& config);

/// Convenience: default config with the given voxel size.
PointCloud voxel_downsample(const PointCloud& cloud, double voxel_size_m);

}  // namespace scantling
