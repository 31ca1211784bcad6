#pragma once
/// @file
/// Voxel thinning of one cell of the hashed map (SPEC §2: "cells over a point budget are
/// thinned with a voxel-grid filter"), through core's voxel_downsample: with the conversions it
/// was still faster than a per-cell std::sort routine (docs/benchmarks.md, "Hashed cell map").

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace scantling::mapping {

/// Replaces `offsets` (points relative to the cell centre, inside the box ±cell_size_m / 2) by
/// one centroid per occupied voxel of edge `voxel_m`, the grid anchored at the cell's minimum
/// corner so voxels never straddle cells. Output ordered by voxel (x, then y, then z), each
/// centroid summed in input order in double (core::voxel_downsample). When more than `budget`
/// voxels are occupied the voxel edge doubles until at most `budget` are (at the latest when one
/// voxel covers the cell), so the result never exceeds `budget` (>= 1). Returns the voxel edge
/// used. Preconditions (checked by CellMapConfig::validate): voxel_m > 0, at most 2²⁰ voxels per
/// cell edge. O(m) per voxel size tried (radix sort).
double thin_cell(std::vector<Eigen::Vector3f>& offsets, const Eigen::Vector3d& cell_size_m,
                 double voxel_m, std::size_t budget);

}  // namespace scantling::mapping
