// LiODOM speed (issue 4, item 6): frames per second of the whole pipeline (run_odometry, edge
// extraction pipelined against registration + mapping) on the 16 real 64-beam sweeps and on
// simulated OS1-64 sweeps (64 × 1024, 10 Hz), 1 and 2 threads, with the median time of each
// stage; against scan-to-scan point-to-plane ICP odometry over the same sweeps, Open3D's
// (odometry_bench_open3d.cpp) and ours (run_icp_odometry).
// Every sweep is read or simulated once, before the timed loops; the reader hands the odometry
// a copy of the sweep held in memory (the copy is inside the timed loop: its cost is printed).
// The memory after a 1 km run is measured by its own executable (odometry_bench_memory.cpp), so
// that its peak RSS is that run's alone.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <scantling/io/sweep_source.hpp>
#include <scantling/odometry/icp_odometry.hpp>
#include <scantling/odometry/liodom.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/scenario_runner.hpp>

#include "bench_support.hpp"
#include "odometry_bench.hpp"

namespace scantling::bench {
namespace {

using Clock = std::chrono::steady_clock;

/// Simulated seconds per sequence: 100 sweeps at 10 Hz.
constexpr double kSimDurationS = 10.0;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

odometry::SweepReader reader_of(const std::vector<PointCloud>& sweeps) {
    return [&sweeps](std::size_t i) { return sweeps[i]; };
}

std::vector<Eigen::Isometry3d> poses_of(const std::vector<odometry::FrameReport>& reports) {
    std::vector<Eigen::Isometry3d> poses;
    poses.reserve(reports.size());
    for (const auto& r : reports) poses.push_back(r.T_odom_sensor);
    return poses;
}

/// Median stage times over every frame of every run; frames that were not registered
/// (motion model) in the last run.
void set_stage_counters(benchmark::State& state, const std::vector<odometry::FrameReport>& all,
                        const std::vector<odometry::FrameReport>& last, bool icp) {
    std::vector<double> extract, reg, map, edges, iterations, local_map;
    for (const auto& r : all) {
        extract.push_back(r.extract_ms);
        reg.push_back(r.register_ms);
        map.push_back(r.map_ms);
        edges.push_back(static_cast<double>(r.num_edges));
        iterations.push_back(r.iterations);
        local_map.push_back(static_cast<double>(r.local_map_points));
    }
    state.counters[icp ? "prepare_ms" : "extract_ms"] = median(extract);
    state.counters[icp ? "icp_ms" : "register_ms"] = median(reg);
    state.counters[icp ? "points" : "edges"] = median(edges);
    state.counters["iterations"] = median(iterations);
    if (!icp) {
        state.counters["map_ms"] = median(map);
        state.counters["local_map_pts"] = median(local_map);
    }
    const auto motion_model = std::count_if(last.begin(), last.end(), [](const auto& r) {
        return r.status == odometry::FrameStatus::kNoEdges ||
               r.status == odometry::FrameStatus::kNotRegistered ||
               r.status == odometry::FrameStatus::kUnreadable;
    });
    state.counters["not_registered"] = static_cast<double>(motion_model);
}

template <typename Run>
void odometry_case(benchmark::State& state, const SweepSequence& sequence, bool icp, Run run) {
    const auto& data = sequence.data();
    if (!sequence.error().empty()) {
        state.SkipWithError(sequence.error().c_str());
        return;
    }
    std::vector<odometry::FrameReport> reports, all;
    std::vector<Clock::time_point> done_at;
    const odometry::FrameCallback on_frame = [&](const odometry::FrameReport&) {
        done_at.push_back(Clock::now());
    };
    double seconds = 0.0;
    for (auto _ : state) {
        done_at.clear();
        const auto t0 = Clock::now();
        reports = run(data.sweeps.size(), reader_of(data.sweeps), on_frame);
        seconds += seconds_since(t0);
        benchmark::DoNotOptimize(reports.data());
        all.insert(all.end(), reports.begin(), reports.end());
    }
    set_trajectory_counters(state, data, poses_of(reports), seconds);
    state.counters["fps_steady"] = steady_fps(done_at);
    set_stage_counters(state, all, reports, icp);
}

void liodom(benchmark::State& state, const SweepSequence* sequence, int threads) {
    const auto config = liodom_config(sequence->preset(), threads);
    odometry_case(state, *sequence, false,
                  [&](std::size_t n, const odometry::SweepReader& read,
                      const odometry::FrameCallback& on_frame) {
                      return odometry::run_odometry(n, read, config, on_frame);
                  });
}

void scan_icp(benchmark::State& state, const SweepSequence* sequence, int threads) {
    const auto config =
        odometry::icp_odometry_config_like(liodom_config(sequence->preset(), threads));
    odometry_case(state, *sequence, true,
                  [&](std::size_t n, const odometry::SweepReader& read,
                      const odometry::FrameCallback& on_frame) {
                      return odometry::run_icp_odometry(n, read, config, on_frame);
                  });
}

void add(const std::string& name, void (*fn)(benchmark::State&, const SweepSequence*, int),
         const SweepSequence* sequence, int threads) {
    benchmark::RegisterBenchmark(name.c_str(), fn, sequence, threads)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(1);
}

void register_sequence(const SweepSequence* sequence) {
    for (int threads : kOdometryThreadCounts) {
        const std::string& name = sequence->name();
        add(fmt::format("{}/ours/{}thr", name, threads), liodom, sequence, threads);
        add(fmt::format("{}/scan_icp/{}thr", name, threads), scan_icp, sequence, threads);
    }
    register_open3d_icp_odometry(sequence);
}

SweepSequence::Data read_all(const io::SweepSource& source) {
    SweepSequence::Data data;
    data.sweeps.reserve(source.size());
    for (std::size_t i = 0; i < source.size(); ++i) data.sweeps.push_back(source.read(i));
    data.ground_truth = source.ground_truth();
    return data;
}

/// The scenario's first kSimDurationS seconds with its spinning LiDAR only, simulated into a
/// scratch recording that is read back and deleted.
SweepSequence::Data simulate(const std::string& scenario_file) {
    sim::Scenario scenario = sim::load_scenario(scenario_file);
    scenario.duration_s = kSimDurationS;
    std::erase_if(scenario.sensors, [](const sim::SensorSpec& s) {
        return s.type != sim::SensorType::kSpinningLidar;
    });
    scenario.export_world.world = false;
    const auto dir = std::filesystem::temp_directory_path() /
                     fmt::format("scantling_odometry_bench_{}_{}", scenario.name, ::getpid());
    std::filesystem::remove_all(dir);
    try {
        sim::run_scenario(scenario, dir.string());
        SweepSequence::Data data = read_all(*io::open_sweep_source(dir.string()));
        std::filesystem::remove_all(dir);
        return data;
    } catch (...) {
        std::filesystem::remove_all(dir);
        throw;
    }
}

std::vector<const SweepSequence*> make_sequences() {
    std::vector<const SweepSequence*> sequences;  // live until exit: the benchmarks point to them
    const std::string scans = std::string(SCANTLING_SHARED_DATA_DIR) + "/lidar-scans";
    if (std::filesystem::is_directory(scans)) {
        sequences.push_back(new SweepSequence("liodom_kitti16", "kitti", [scans] {
            return read_all(*io::open_sweep_source(scans));
        }));
    } else {
        std::printf("SKIP: odometry benchmark on real sweeps: %s is absent\n", scans.c_str());
    }
    const std::string dir = SCANTLING_SCENARIO_DIR;
    sequences.push_back(new SweepSequence("liodom_sim_hull_os1", "os1_drone", [dir] {
        return simulate(dir + "/hull_sweep_os1.yaml");
    }));
    sequences.push_back(new SweepSequence("liodom_sim_tank_os1", "os1_drone", [dir] {
        return simulate(dir + "/storage_tank_orbit_os1.yaml");
    }));
    return sequences;
}

}  // namespace
}  // namespace scantling::bench

int main(int argc, char** argv) {
    double load[3] = {0, 0, 0};
    getloadavg(load, 3);
    std::printf("odometry benchmark: %ld cores online, load average at start %.2f %.2f %.2f\n",
                sysconf(_SC_NPROCESSORS_ONLN), load[0], load[1], load[2]);
    for (const auto* sequence : scantling::bench::make_sequences()) {
        scantling::bench::register_sequence(sequence);
    }
    return scantling::bench::run_all(argc, argv);
}
