#pragma once
/// @file Inputs, error metrics and registration helpers shared by the registration benchmarks.

#include <Eigen/Geometry>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>
#include <open3d/geometry/KDTreeSearchParam.h>
#include <open3d/geometry/PointCloud.h>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/registration/fpfh.hpp>

namespace scantling::bench {

inline constexpr int kRegThreadCounts[] = {1, 2};

/// Two clouds to register, the reference T_target_source, and the same positions, normals and
/// covariances as Open3D clouds.
struct RegistrationPair {
    PointCloud source;
    PointCloud target;
    Eigen::Isometry3d T_target_source_ref = Eigen::Isometry3d::Identity();
    std::shared_ptr<open3d::geometry::PointCloud> o3d_source;
    std::shared_ptr<open3d::geometry::PointCloud> o3d_target;
};

/// Reads a 4×4 matrix text file (4 lines of 4 numbers).
Eigen::Isometry3d read_matrix_file(const std::string& path);

/// An Open3D cloud with the same points and (when present) normals and covariances.
std::shared_ptr<open3d::geometry::PointCloud> to_open3d(const PointCloud& cloud);

/// Rotation error (degrees) and translation error (metres) of `T` against `T_ref`, written as
/// the counters rot_err_deg and trans_err_cm of `state`.
void set_error_counters(benchmark::State& state, const Eigen::Isometry3d& T,
                        const Eigen::Isometry3d& T_ref);

/// 3DMatch's success criterion: rotation error < 15°, translation error < 0.3 m.
bool is_3dmatch_success(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T_ref);

inline ParallelConfig threads_config(int threads) {
    ParallelConfig config;
    config.num_threads = threads;
    return config;
}

/// Global registration settings of every FPFH case (real and simulated): 0.05 m voxels, FPFH
/// radius 5 voxels (Open3D's and TEASER++'s examples) over at most 100 neighbours, RANSAC's
/// inlier distance 1.5 voxels (Open3D's example: 0.075 m).
inline constexpr double kGlobalVoxelM = 0.05;
inline constexpr double kFpfhRadiusM = 5.0 * kGlobalVoxelM;
inline constexpr int kFpfhMaxNeighbors = 100;
inline constexpr double kRansacDistanceM = 1.5 * kGlobalVoxelM;

/// Our FPFH with the settings above on `threads` threads.
inline registration::FpfhConfig fpfh_config(int threads) {
    registration::FpfhConfig config;
    config.radius_m = kFpfhRadiusM;
    config.max_neighbors = kFpfhMaxNeighbors;
    config.parallel = threads_config(threads);
    return config;
}

/// Open3D's FPFH search with the same settings.
inline open3d::geometry::KDTreeSearchParamHybrid open3d_fpfh_param() {
    return open3d::geometry::KDTreeSearchParamHybrid(kFpfhRadiusM, kFpfhMaxNeighbors);
}

/// Registers a wall-clock, millisecond benchmark.
template <typename Fn, typename... Args>
void add_benchmark(const std::string& name, Fn fn, Args... args) {
    benchmark::RegisterBenchmark(name.c_str(), fn, args...)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}

/// Registers the ICP cases (lidar pair at `voxel_m`) and the FPFH/global ones (RGB-D pair).
void register_icp_benchmarks(const RegistrationPair& pair, double voxel_m);
void register_global_benchmarks(const RegistrationPair& pair);
/// Simulated tank scans against their CAD maps, many pairs per case (registration_bench_tanks).
void register_tank_benchmarks();

}  // namespace scantling::bench
