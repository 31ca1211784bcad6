// The Open3D baseline of the LiODOM speed benchmark: scan-to-scan point-to-plane ICP odometry
// with Open3D 0.16, set up as our run_icp_odometry (icp_odometry_config_like of the sequence's
// preset): range gate, voxel downsampling, normals from k nearest neighbours per sweep, each
// sweep aligned to the previous one from the constant-velocity guess (the last relative motion)
// with the same correspondence distance, Huber kernel scale and iteration cap, and the relative
// poses chained. Everything from the gate on is timed; the sweeps are converted to Open3D clouds
// before the timed loop. Threads: omp_set_num_threads (Open3D's loops are OpenMP).
#include <chrono>
#include <map>
#include <memory>
#include <vector>

#include <fmt/format.h>
#include <omp.h>
#include <open3d/geometry/KDTreeSearchParam.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/pipelines/registration/RobustKernel.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>

#include <scantling/odometry/icp_odometry.hpp>

#include "odometry_bench.hpp"

namespace scantling::bench {
namespace {

namespace o3reg = open3d::pipelines::registration;
using O3dCloud = open3d::geometry::PointCloud;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Range-gated, voxel-downsampled, with normals: as odometry::run_icp_odometry prepares a sweep.
std::shared_ptr<O3dCloud> prepare(const O3dCloud& sweep, const odometry::IcpOdometryConfig& c) {
    std::vector<std::size_t> keep;
    keep.reserve(sweep.points_.size());
    for (std::size_t i = 0; i < sweep.points_.size(); ++i) {
        const Eigen::Vector3d& p = sweep.points_[i];
        const double r = p.norm();
        if (p.allFinite() && r >= c.min_range_m && r <= c.max_range_m) keep.push_back(i);
    }
    auto down = sweep.SelectByIndex(keep)->VoxelDownSample(c.voxel_size_m);
    down->EstimateNormals(open3d::geometry::KDTreeSearchParamKNN(c.icp.num_neighbors));
    return down;
}

struct O3dFrame {
    Eigen::Isometry3d T_odom_sensor = Eigen::Isometry3d::Identity();
    Clock::time_point done_at;
    double prepare_ms = 0.0;
    double icp_ms = 0.0;
    double points = 0.0;
};

std::vector<O3dFrame> open3d_icp_odometry(const std::vector<std::shared_ptr<O3dCloud>>& sweeps,
                                          const odometry::IcpOdometryConfig& c) {
    const o3reg::TransformationEstimationPointToPlane estimation(
        std::make_shared<o3reg::HuberLoss>(c.icp.kernel_scale_m));
    const o3reg::ICPConvergenceCriteria criteria(1e-6, 1e-6, c.icp.max_iterations);
    std::vector<O3dFrame> frames(sweeps.size());
    std::shared_ptr<O3dCloud> previous;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    Eigen::Matrix4d delta = Eigen::Matrix4d::Identity();  // last T_prev_cur
    for (std::size_t i = 0; i < sweeps.size(); ++i) {
        const auto t0 = Clock::now();
        auto current = prepare(*sweeps[i], c);
        frames[i].prepare_ms = ms_since(t0);
        frames[i].points = static_cast<double>(current->points_.size());
        if (previous) {
            const auto t1 = Clock::now();
            const auto result =
                o3reg::RegistrationICP(*current, *previous, c.icp.max_correspondence_distance_m,
                                       delta, estimation, criteria);
            frames[i].icp_ms = ms_since(t1);
            delta = result.transformation_;
            T = T * Eigen::Isometry3d(delta);
        }
        frames[i].T_odom_sensor = T;
        frames[i].done_at = Clock::now();
        previous = std::move(current);
    }
    return frames;
}

/// The sequence's sweeps as Open3D clouds (positions only: all the baseline uses).
const std::vector<std::shared_ptr<O3dCloud>>& open3d_sweeps(const SweepSequence& sequence) {
    static std::map<const SweepSequence*, std::vector<std::shared_ptr<O3dCloud>>> converted;
    auto& clouds = converted[&sequence];
    if (clouds.empty()) {
        for (const PointCloud& sweep : sequence.data().sweeps) {
            clouds.push_back(std::make_shared<O3dCloud>(sweep.points));
        }
    }
    return clouds;
}

void open3d_icp(benchmark::State& state, const SweepSequence* sequence, int threads) {
    const auto config =
        odometry::icp_odometry_config_like(liodom_config(sequence->preset(), threads));
    const auto& sweeps = open3d_sweeps(*sequence);
    if (!sequence->error().empty()) {
        state.SkipWithError(sequence->error().c_str());
        return;
    }
    omp_set_num_threads(threads);
    std::vector<O3dFrame> frames;
    std::vector<double> prepare_ms, icp_ms, points;
    double seconds = 0.0;
    for (auto _ : state) {
        const auto t0 = Clock::now();
        frames = open3d_icp_odometry(sweeps, config);
        seconds += 1e-3 * ms_since(t0);
        benchmark::DoNotOptimize(frames.data());
        for (const O3dFrame& f : frames) {
            prepare_ms.push_back(f.prepare_ms);
            icp_ms.push_back(f.icp_ms);
            points.push_back(f.points);
        }
    }
    std::vector<Eigen::Isometry3d> poses;
    std::vector<Clock::time_point> done_at;
    for (const O3dFrame& f : frames) {
        poses.push_back(f.T_odom_sensor);
        done_at.push_back(f.done_at);
    }
    set_trajectory_counters(state, sequence->data(), poses, seconds);
    state.counters["fps_steady"] = steady_fps(done_at);
    state.counters["prepare_ms"] = median(prepare_ms);
    state.counters["icp_ms"] = median(icp_ms);
    state.counters["points"] = median(points);
}

}  // namespace

void register_open3d_icp_odometry(const SweepSequence* sequence) {
    for (int threads : kOdometryThreadCounts) {
        benchmark::RegisterBenchmark(
            fmt::format("{}/open3d_icp/{}thr", sequence->name(), threads).c_str(), open3d_icp,
            sequence, threads)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->Iterations(1);
    }
}

}  // namespace scantling::bench
