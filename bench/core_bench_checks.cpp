// Agreement between scantling and Open3D on the benchmark input, printed before the timings so
// that a fast but wrong implementation cannot pass unnoticed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <open3d/geometry/KDTreeFlann.h>
#include <open3d/geometry/KDTreeSearchParam.h>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/normals.hpp>
#include <scantling/core/voxel_grid.hpp>

#include "core_bench.hpp"

namespace scantling::bench {
namespace {

// Both sides compute the same squared distances from the same doubles, up to summation order.
constexpr double kDistanceRelTol = 1e-12;

void print_voxel_agreement(const CoreInputs& in) {
    for (double v : kVoxelSizesM) {
        const std::size_t ours = voxel_downsample(in.cloud, v).size();
        const std::size_t theirs = in.o3d->VoxelDownSample(v)->points_.size();
        std::printf(
            "check voxel %.2f m: ours %zu voxels, open3d %zu (%+.2f %%; the grids differ: ours "
            "is anchored at the origin, Open3D's at the min corner - voxel/2)\n",
            v, ours, theirs,
            100.0 * (static_cast<double>(ours) - static_cast<double>(theirs)) /
                static_cast<double>(theirs));
    }
}

void print_normal_agreement(const CoreInputs& in) {
    PointCloud ours = in.cloud;
    NormalEstimationConfig config;
    config.num_neighbors = kNormalNeighbors;
    estimate_normals(ours, config);
    open3d::geometry::PointCloud theirs = *in.o3d;
    theirs.EstimateNormals(open3d::geometry::KDTreeSearchParamKNN(kNormalNeighbors));
    std::vector<double> angles_deg(ours.size());
    for (std::size_t i = 0; i < ours.size(); ++i) {
        const double c = std::min(1.0, std::abs(ours.normals[i].dot(theirs.normals_[i])));
        angles_deg[i] = std::acos(c) * 180.0 / std::numbers::pi;  // sign: Open3D does not orient
    }
    std::sort(angles_deg.begin(), angles_deg.end());
    const auto within = std::lower_bound(angles_deg.begin(), angles_deg.end(), 1.0);
    std::printf(
        "check normals k=%d: angle to Open3D's (unsigned) median %.2e deg, p99 %.2e deg, max "
        "%.2e deg; %.3f %% within 1 deg\n",
        kNormalNeighbors, angles_deg[angles_deg.size() / 2],
        angles_deg[angles_deg.size() * 99 / 100], angles_deg.back(),
        100.0 * static_cast<double>(within - angles_deg.begin()) /
            static_cast<double>(angles_deg.size()));
}

void print_knn_agreement(const CoreInputs& in) {
    const KdTree tree(in.cloud.points);
    const KnnBatchResult ours = tree.knn_batch(in.cloud.points, kKnnNeighbors);
    const open3d::geometry::KDTreeFlann theirs(*in.o3d);
    std::vector<int> idx;
    std::vector<double> d2;
    std::size_t same_distances = 0;
    std::size_t same_indices = 0;
    for (std::size_t q = 0; q < in.cloud.size(); ++q) {
        theirs.SearchKNN(in.cloud.points[q], kKnnNeighbors, idx, d2);
        bool dist_ok = d2.size() == ours.k;
        bool idx_ok = dist_ok;
        for (std::size_t j = 0; dist_ok && j < ours.k; ++j) {
            const double a = ours.distances_sq_m2[q * ours.k + j];
            dist_ok = std::abs(a - d2[j]) <= kDistanceRelTol * std::max(a, 1.0);
            idx_ok = idx_ok && ours.indices[q * ours.k + j] == static_cast<std::size_t>(idx[j]);
        }
        same_distances += dist_ok ? 1 : 0;
        same_indices += dist_ok && idx_ok ? 1 : 0;
    }
    std::printf(
        "check kNN k=%d: %zu / %zu queries with the same distances as Open3D, %zu with the same "
        "indices in the same order (the rest differ only among equidistant points)\n",
        kKnnNeighbors, same_distances, in.cloud.size(), same_indices);
}

}  // namespace

void print_agreement(const CoreInputs& inputs) {
    print_voxel_agreement(inputs);
    print_normal_agreement(inputs);
    print_knn_agreement(inputs);
}

}  // namespace scantling::bench
