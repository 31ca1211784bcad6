// Registration against Open3D 0.16: point-to-point, point-to-plane and generalized ICP on the
// real LiDAR pair; FPFH and global registration on the RGB-D pair (registration_bench_global);
// all of them on simulated tank scans (registration_bench_tanks).
// Both sides get the same downsampled points, normals and covariances (computed once by us,
// copied into the Open3D clouds, outside the timed loop), the same correspondence distance and
// iteration cap, and the same thread count: ours via ParallelConfig, Open3D via
// omp_set_num_threads. Each case reports its error against the reference transform.
#include <cstdio>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <omp.h>
#include <open3d/pipelines/registration/GeneralizedICP.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>

#include <scantling/core/normals.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/registration/icp.hpp>

#include "bench_support.hpp"
#include "registration_bench.hpp"

namespace scantling::bench {

namespace o3reg = open3d::pipelines::registration;

Eigen::Isometry3d read_matrix_file(const std::string& path) {
    std::ifstream in(path);
    Eigen::Matrix4d M;
    for (int i = 0; i < 16; ++i) in >> M(i / 4, i % 4);
    Eigen::Isometry3d T;
    T.matrix() = M;
    return T;
}

std::shared_ptr<open3d::geometry::PointCloud> to_open3d(const PointCloud& cloud) {
    auto o3d = std::make_shared<open3d::geometry::PointCloud>(cloud.points);
    o3d->normals_ = cloud.normals;
    o3d->covariances_ = cloud.covariances;
    return o3d;
}

void set_error_counters(benchmark::State& state, const Eigen::Isometry3d& T,
                        const Eigen::Isometry3d& T_ref) {
    const Eigen::Isometry3d E = T_ref.inverse() * T;
    state.counters["rot_err_deg"] = Eigen::AngleAxisd(E.linear()).angle() * 180.0 / M_PI;
    state.counters["trans_err_cm"] = E.translation().norm() * 100.0;
}

bool is_3dmatch_success(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T_ref) {
    const Eigen::Isometry3d E = T_ref.inverse() * T;
    return Eigen::AngleAxisd(E.linear()).angle() < 15.0 * M_PI / 180.0 &&
           E.translation().norm() < 0.3;
}

namespace {

constexpr double kIcpMaxDistanceM = 1.0;  // both: max correspondence distance
constexpr int kIcpMaxIterations = 30;     // both: Open3D's ICPConvergenceCriteria default
/// Neighbours for the normals and GICP covariances given to both (our IcpConfig default).
constexpr int kIcpNeighbors = 10;

registration::IcpMethod our_method(int m) { return static_cast<registration::IcpMethod>(m); }

void icp_ours(benchmark::State& state, const RegistrationPair* pair, int method, int threads) {
    registration::IcpConfig config;
    config.method = our_method(method);
    config.max_correspondence_distance_m = kIcpMaxDistanceM;
    config.max_iterations = kIcpMaxIterations;
    config.num_neighbors = kIcpNeighbors;
    config.parallel = threads_config(threads);
    registration::RegistrationResult result;
    for (auto _ : state) {
        result =
            registration::align(pair->source, pair->target, Eigen::Isometry3d::Identity(), config);
        benchmark::DoNotOptimize(result.T_target_source);
    }
    set_error_counters(state, result.T_target_source, pair->T_target_source_ref);
    state.counters["iterations"] = result.iterations;
}

o3reg::RegistrationResult open3d_icp(const RegistrationPair& pair, int method) {
    const o3reg::ICPConvergenceCriteria criteria(1e-6, 1e-6, kIcpMaxIterations);
    const Eigen::Matrix4d init = Eigen::Matrix4d::Identity();
    if (method == 2) {
        return o3reg::RegistrationGeneralizedICP(
            *pair.o3d_source, *pair.o3d_target, kIcpMaxDistanceM, init,
            o3reg::TransformationEstimationForGeneralizedICP(), criteria);
    }
    if (method == 1) {
        return o3reg::RegistrationICP(*pair.o3d_source, *pair.o3d_target, kIcpMaxDistanceM, init,
                                      o3reg::TransformationEstimationPointToPlane(), criteria);
    }
    return o3reg::RegistrationICP(*pair.o3d_source, *pair.o3d_target, kIcpMaxDistanceM, init,
                                  o3reg::TransformationEstimationPointToPoint(), criteria);
}

void icp_open3d(benchmark::State& state, const RegistrationPair* pair, int method, int threads) {
    omp_set_num_threads(threads);
    o3reg::RegistrationResult result;
    for (auto _ : state) {
        result = open3d_icp(*pair, method);
        benchmark::DoNotOptimize(result.transformation_);
    }
    Eigen::Isometry3d T;
    T.matrix() = result.transformation_;
    set_error_counters(state, T, pair->T_target_source_ref);
}

/// Downsampled lidar pair with our normals (k = 10) and GICP covariances on both clouds.
RegistrationPair* make_lidar_pair(const PointCloud& source, const PointCloud& target,
                                  const Eigen::Isometry3d& T_ref, double voxel_m) {
    auto* pair = new RegistrationPair;  // lives until exit: the benchmarks point to it
    pair->T_target_source_ref = T_ref;
    pair->source = voxel_downsample(remove_non_finite(source), voxel_m);
    pair->target = voxel_downsample(remove_non_finite(target), voxel_m);
    for (PointCloud* cloud : {&pair->source, &pair->target}) {
        cloud->normals.clear();
        cloud->covariances.clear();
        NormalEstimationConfig normals;
        normals.num_neighbors = kIcpNeighbors;
        CovarianceConfig covariances;
        covariances.num_neighbors = kIcpNeighbors;
        estimate_normals_and_covariances(*cloud, normals, covariances);
    }
    pair->o3d_source = to_open3d(pair->source);
    pair->o3d_target = to_open3d(pair->target);
    return pair;
}

const char* const kIcpNames[] = {"icp_p2point", "icp_p2plane", "gicp"};

}  // namespace

void register_icp_benchmarks(const RegistrationPair& pair, double voxel_m) {
    std::printf("lidar pair at %.2f m voxels: %zu source, %zu target points\n", voxel_m,
                pair.source.size(), pair.target.size());
    for (int t : kRegThreadCounts) {
        for (int m = 0; m < 3; ++m) {
            const std::string name =
                fmt::format("registration_lidar_{:.2f}m_{}", voxel_m, kIcpNames[m]);
            add_benchmark(fmt::format("{}/ours/{}thr", name, t), icp_ours, &pair, m, t);
            add_benchmark(fmt::format("{}/open3d/{}thr", name, t), icp_open3d, &pair, m, t);
        }
    }
}

}  // namespace scantling::bench

namespace {

/// The real pairs of the shared data; nothing when it is absent (a message says so).
void register_real_pair_benchmarks() {
    using namespace scantling::bench;
    const std::string dir = SCANTLING_SHARED_DATA_DIR;
    const auto source = load_shared_cloud(dir, "lidar-pair/source.ply");
    const auto target = load_shared_cloud(dir, "lidar-pair/target.ply");
    const auto src = load_shared_cloud(dir, "rgbd-pair/src.ply");
    const auto ref = load_shared_cloud(dir, "rgbd-pair/ref.ply");
    if (!source || !target || !src || !ref) return;
    const auto T_lidar = read_matrix_file(dir + "/lidar-pair/T_target_source.txt");
    for (double voxel_m : {0.25, 0.1}) {
        register_icp_benchmarks(*make_lidar_pair(*source, *target, T_lidar, voxel_m), voxel_m);
    }
    auto* rgbd = new RegistrationPair;
    rgbd->source = *src;
    rgbd->target = *ref;
    rgbd->T_target_source_ref = read_matrix_file(dir + "/rgbd-pair/T_ref_src.txt");
    register_global_benchmarks(*rgbd);
}

}  // namespace

int main(int argc, char** argv) {
    register_real_pair_benchmarks();
    scantling::bench::register_tank_benchmarks();  // simulated: no shared data needed
    return scantling::bench::run_all(argc, argv);
}
