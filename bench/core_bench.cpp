// Core geometry against Open3D 0.16: voxel downsampling, normal estimation, k-d tree + kNN.
// Both sides get the same positions (double precision) and the same thread count: ours through
// ParallelConfig, Open3D (OpenMP) through omp_set_num_threads.
#include <cstdio>
#include <string>

#include <fmt/format.h>
#include <omp.h>
#include <open3d/geometry/KDTreeFlann.h>
#include <open3d/geometry/KDTreeSearchParam.h>
#include <open3d/geometry/PointCloud.h>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/normals.hpp>
#include <scantling/core/voxel_grid.hpp>

#include "bench_support.hpp"
#include "core_bench.hpp"

namespace scantling::bench {
namespace {

const char* const kInput = "lidar-scans/000000.pcd";

CoreInputs& inputs() {
    static CoreInputs in;
    return in;
}

ParallelConfig threads_config(int threads) {
    ParallelConfig config;
    config.num_threads = threads;
    return config;
}

void voxel_ours(benchmark::State& state, double voxel_m, int threads) {
    VoxelGridConfig config;
    config.voxel_size_m = voxel_m;
    config.parallel = threads_config(threads);
    std::size_t out_size = 0;
    for (auto _ : state) {
        const PointCloud out = voxel_downsample(inputs().cloud, config);
        out_size = out.size();
        benchmark::DoNotOptimize(out.points.data());
    }
    state.counters["points_out"] = static_cast<double>(out_size);
}

void voxel_open3d(benchmark::State& state, double voxel_m, int threads) {
    omp_set_num_threads(threads);
    std::size_t out_size = 0;
    for (auto _ : state) {
        const auto out = inputs().o3d->VoxelDownSample(voxel_m);
        out_size = out->points_.size();
        benchmark::DoNotOptimize(out->points_.data());
    }
    state.counters["points_out"] = static_cast<double>(out_size);
}

void normals_ours(benchmark::State& state, int threads) {
    PointCloud cloud = inputs().cloud;
    NormalEstimationConfig config;
    config.num_neighbors = kNormalNeighbors;
    config.parallel = threads_config(threads);
    for (auto _ : state) {
        cloud.normals.clear();
        estimate_normals(cloud, config);
        benchmark::DoNotOptimize(cloud.normals.data());
    }
}

void normals_open3d(benchmark::State& state, int threads) {
    omp_set_num_threads(threads);
    open3d::geometry::PointCloud cloud = *inputs().o3d;
    for (auto _ : state) {
        cloud.normals_.clear();  // else Open3D orients towards the previous run's normals
        cloud.EstimateNormals(open3d::geometry::KDTreeSearchParamKNN(kNormalNeighbors));
        benchmark::DoNotOptimize(cloud.normals_.data());
    }
}

void knn_ours(benchmark::State& state, int threads) {
    const auto& points = inputs().cloud.points;
    for (auto _ : state) {
        const KdTree tree(points);
        const KnnBatchResult result =
            tree.knn_batch(points, kKnnNeighbors, threads_config(threads));
        benchmark::DoNotOptimize(result.indices.data());
    }
}

void knn_open3d(benchmark::State& state, int threads) {
    omp_set_num_threads(threads);
    const auto& points = inputs().o3d->points_;
    const int n = static_cast<int>(points.size());
    for (auto _ : state) {
        const open3d::geometry::KDTreeFlann tree(*inputs().o3d);
        std::vector<int> indices(points.size() * kKnnNeighbors);
        std::vector<double> distances_sq(points.size() * kKnnNeighbors);
#pragma omp parallel
        {
            std::vector<int> idx;
            std::vector<double> d2;
#pragma omp for schedule(static)
            for (int q = 0; q < n; ++q) {
                tree.SearchKNN(points[q], kKnnNeighbors, idx, d2);
                const std::ptrdiff_t row = std::ptrdiff_t{q} * kKnnNeighbors;
                std::copy(idx.begin(), idx.end(), indices.begin() + row);
                std::copy(d2.begin(), d2.end(), distances_sq.begin() + row);
            }
        }
        benchmark::DoNotOptimize(indices.data());
    }
}

template <typename Fn, typename... Args>
void add(const std::string& name, Fn fn, Args... args) {
    benchmark::RegisterBenchmark(name.c_str(), fn, args...)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}

void register_all() {
    for (int t : kThreadCounts) {
        for (double v : kVoxelSizesM) {
            add(fmt::format("voxel_downsample_{:.2f}m/ours/{}thr", v, t), voxel_ours, v, t);
            add(fmt::format("voxel_downsample_{:.2f}m/open3d/{}thr", v, t), voxel_open3d, v, t);
        }
        add(fmt::format("normals_knn{}/ours/{}thr", kNormalNeighbors, t), normals_ours, t);
        add(fmt::format("normals_knn{}/open3d/{}thr", kNormalNeighbors, t), normals_open3d, t);
        add(fmt::format("kdtree_build_knn{}/ours/{}thr", kKnnNeighbors, t), knn_ours, t);
        add(fmt::format("kdtree_build_knn{}/open3d/{}thr", kKnnNeighbors, t), knn_open3d, t);
    }
}

}  // namespace
}  // namespace scantling::bench

int main(int argc, char** argv) {
    using namespace scantling::bench;
    auto cloud = load_shared_cloud(SCANTLING_SHARED_DATA_DIR, kInput);
    if (!cloud) return 0;
    inputs().cloud.points = std::move(cloud->points);
    inputs().o3d = std::make_shared<open3d::geometry::PointCloud>(inputs().cloud.points);
    std::printf("input: %s/%s, %zu points\n", SCANTLING_SHARED_DATA_DIR, kInput,
                inputs().cloud.size());
    print_agreement(inputs());
    register_all();
    return run_all(argc, argv);
}
