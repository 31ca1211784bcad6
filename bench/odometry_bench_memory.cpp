// LiODOM memory after a 1 km run (issue 4, item 6): the kitti preset over the simulated urban
// drive (scenarios/urban_drive_hdl64.yaml: an HDL-64E-like 64 × 1024 LiDAR, 2,011 sweeps,
// 1.18 km), one LidarOdometry fed sweep by sweep so that its map can be inspected at the end.
// Its own executable, so that the process's peak RSS (VmHWM) is this run's alone.
//
// The recording is too large to generate here (1.9 GB, minutes of simulation): point the
// environment variable SCANTLING_URBAN_RECORDING at it (`scantling sim
// scenarios/urban_drive_hdl64.yaml --out DIR`); without it the benchmark is skipped.
//
// Reported time = time inside LidarOdometry::process (reading the sweeps from disk is not
// timed). Extraction and registration use 2 threads; the stages run one after the other.
#include <malloc.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <scantling/io/sweep_source.hpp>
#include <scantling/odometry/liodom.hpp>

#include "bench_support.hpp"
#include "odometry_bench.hpp"

namespace scantling::bench {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kThreads = 2;
constexpr std::size_t kReportEvery = 500;  // frames between progress lines

/// A "VmHWM:" / "VmRSS:" line of /proc/self/status, in MB (0 when unavailable).
double proc_status_mb(const std::string& key) {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind(key, 0) == 0) return std::atof(line.c_str() + key.size()) * 1024.0 / 1e6;
    }
    return 0.0;
}

/// What the run leaves to report: the odometry (its map) and the per-frame results.
struct UrbanRun {
    std::unique_ptr<odometry::LidarOdometry> odometry;
    std::vector<Eigen::Isometry3d> poses;
    std::vector<double> extract_ms, register_ms, map_ms, edges;
    std::size_t not_registered = 0;  ///< frames carried by the motion model
    double seconds = 0.0;            ///< inside LidarOdometry::process
};

void print_progress(const UrbanRun& run) {
    const auto& odometry = *run.odometry;
    std::printf(
        "  frame %zu: %.0f m estimated; map %zu cells, %zu points; local map %zu points; "
        "memory_bytes %.1f MB; process RSS %.1f MB\n",
        run.poses.size(), path_length_m(run.poses), odometry.map().num_cells(),
        odometry.map().num_points(), odometry.local_map().size(),
        1e-6 * static_cast<double>(odometry.memory_bytes()), proc_status_mb("VmRSS:"));
    std::fflush(stdout);
}

UrbanRun run_urban(const io::SweepSource& source) {
    UrbanRun run;
    run.odometry = std::make_unique<odometry::LidarOdometry>(liodom_config("kitti", kThreads));
    for (std::size_t i = 0; i < source.size(); ++i) {
        const PointCloud sweep = source.read(i);
        const auto t0 = Clock::now();
        const odometry::FrameReport report = run.odometry->process(sweep);
        run.seconds += std::chrono::duration<double>(Clock::now() - t0).count();
        run.poses.push_back(report.T_odom_sensor);
        run.extract_ms.push_back(report.extract_ms);
        run.register_ms.push_back(report.register_ms);
        run.map_ms.push_back(report.map_ms);
        run.edges.push_back(static_cast<double>(report.num_edges));
        if (report.status == odometry::FrameStatus::kNoEdges ||
            report.status == odometry::FrameStatus::kNotRegistered) {
            ++run.not_registered;
        }
        if ((i + 1) % kReportEvery == 0) print_progress(run);
    }
    return run;
}

void set_memory_counters(benchmark::State& state, const odometry::LidarOdometry& odometry,
                         double rss_start_mb) {
    state.counters["memory_MB"] = 1e-6 * static_cast<double>(odometry.memory_bytes());
    state.counters["map_cells"] = static_cast<double>(odometry.map().num_cells());
    state.counters["map_points"] = static_cast<double>(odometry.map().num_points());
    state.counters["local_map_points"] = static_cast<double>(odometry.local_map().size());
    state.counters["rss_start_MB"] = rss_start_mb;
    state.counters["rss_end_MB"] = proc_status_mb("VmRSS:");
    state.counters["peak_rss_MB"] = proc_status_mb("VmHWM:");
    // Free pages glibc keeps in its arenas are returned first, so that this is close to the
    // live memory (pages holding any live block stay: fragmentation is still counted).
    malloc_trim(0);
    state.counters["rss_trimmed_MB"] = proc_status_mb("VmRSS:");
}

void urban_memory(benchmark::State& state, const std::string* path) {
    const auto source = io::open_sweep_source(*path);
    const double rss_start_mb = proc_status_mb("VmHWM:");
    UrbanRun run;
    for (auto _ : state) {
        run = run_urban(*source);
        state.SetIterationTime(run.seconds);
    }
    SweepSequence::Data truth;
    truth.ground_truth = source->ground_truth();
    set_trajectory_counters(state, truth, run.poses, run.seconds);
    if (state.counters.count("gt_path_m") != 0) {
        state.counters["end_err_pct"] =
            100.0 * state.counters["end_err_m"] / state.counters["gt_path_m"];
    }
    state.counters["extract_ms"] = median(run.extract_ms);
    state.counters["register_ms"] = median(run.register_ms);
    state.counters["map_ms"] = median(run.map_ms);
    state.counters["edges"] = median(run.edges);
    state.counters["not_registered"] = static_cast<double>(run.not_registered);
    set_memory_counters(state, *run.odometry, rss_start_mb);
    // Whatever the process still holds once the odometry is gone is not the odometry's.
    run.odometry.reset();
    malloc_trim(0);
    state.counters["rss_freed_MB"] = proc_status_mb("VmRSS:");
}

}  // namespace

}  // namespace scantling::bench

int main(int argc, char** argv) {
    const char* env = std::getenv("SCANTLING_URBAN_RECORDING");
    static std::string path = env != nullptr ? env : "";
    if (path.empty() || !std::filesystem::is_directory(path)) {
        std::printf(
            "SKIP: LiODOM memory after 1 km: set SCANTLING_URBAN_RECORDING to a recording of "
            "scenarios/urban_drive_hdl64.yaml (%s)\n",
            path.empty() ? "unset" : (path + " is absent").c_str());
    } else {
        benchmark::RegisterBenchmark("liodom_urban_1km_memory/ours/2thr",
                                     scantling::bench::urban_memory, &path)
            ->Unit(benchmark::kSecond)
            ->UseManualTime()
            ->Iterations(1)
            ->Repetitions(1);
    }
    return scantling::bench::run_all(argc, argv);
}
