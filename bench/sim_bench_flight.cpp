// Simulation speed: a 60 s flight of a drone with an OS1-64 (64 × 1024, 10 Hz) and a 200 Hz
// IMU sweeping a ship's side shell in its dry dock (a lawnmower at 3 m stand-off, 1 m/s), all
// in memory; reported as simulated seconds per wall-clock second ("x_realtime").
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <scantling/sim/imu.hpp>
#include <scantling/sim/lawnmower_trajectory.hpp>
#include <scantling/sim/spinning_lidar.hpp>
#include <scantling/sim/world_hull.hpp>

#include "bench_support.hpp"
#include "sim_bench.hpp"

namespace scantling::bench {
namespace {

constexpr double kFlightS = 60.0;
constexpr double kLidarRateHz = 10.0;
constexpr double kImuRateHz = 200.0;
constexpr double kStandoffM = 3.0;
constexpr double kSpeedMps = 1.0;
constexpr double kSweepHeightM = 5.0;  // lawnmower extent up the side shell
constexpr std::uint64_t kSeed = 7;

struct FlightCase {
    std::string name;
    const sim::World* world = nullptr;
    const sim::RayCaster* caster = nullptr;
    std::unique_ptr<sim::LawnmowerTrajectory> trajectory;
};

/// The parametric hull, built once and kept for the whole run.
struct ParametricHull {
    sim::World world = sim::build_ship_hull();
    sim::RayCaster caster{world.mesh, world.surface_tags};
};

std::vector<FlightCase>& cases() {
    static std::vector<FlightCase> all;
    return all;
}

/// Lawnmower over the +y side shell (the plane y = side_y_m), horizontal slices 1 m apart from
/// x_end_m back to x_end_m − width_m and from z_top_m down kSweepHeightM. Wall frame: x along
/// world −x, y up, so the wall normal is +y.
std::unique_ptr<sim::LawnmowerTrajectory> side_sweep(double x_end_m, double width_m,
                                                     double side_y_m, double z_top_m) {
    sim::LawnmowerTrajectoryConfig config;
    Eigen::Matrix3d R_world_wall;
    R_world_wall << -1, 0, 0, 0, 0, 1, 0, 1, 0;
    config.T_world_wall.linear() = R_world_wall;
    config.T_world_wall.translation() = Eigen::Vector3d(x_end_m, side_y_m, z_top_m - kSweepHeightM);
    config.width_m = width_m;
    config.height_m = kSweepHeightM;
    config.standoff_m = kStandoffM;
    config.slice_spacing_m = 1.0;
    config.max_speed_mps = kSpeedMps;
    return std::make_unique<sim::LawnmowerTrajectory>(config);
}

struct FlightTally {
    std::size_t points = 0;
    std::size_t imu_samples = 0;
};

/// The whole flight: 600 sweeps, each from the trajectory pose at its start, and the IMU
/// samples in between, in time order as a scenario runner interleaves them.
FlightTally fly(const FlightCase& flight, const ParallelConfig& parallel) {
    const sim::SceneView scene{*flight.caster, flight.world->metadata};
    const sim::SpinningLidar lidar(sim::ouster_os1_64(1024, kLidarRateHz));
    Rng rng(kSeed);
    sim::ImuSimulator imu(sim::consumer_mems_imu(), rng);
    const int sweeps = static_cast<int>(kFlightS * kLidarRateHz);
    const int imu_per_sweep = static_cast<int>(kImuRateHz / kLidarRateHz);
    FlightTally tally;
    for (int k = 0; k < sweeps; ++k) {
        const double t_s = k / kLidarRateHz;
        const PointCloud cloud =
            lidar.scan(scene, flight.trajectory->at(t_s).T_world_body, rng, t_s, parallel);
        tally.points += cloud.size();
        for (int i = 0; i < imu_per_sweep; ++i) {
            const double t_imu_s = t_s + i / kImuRateHz;
            benchmark::DoNotOptimize(imu.measure(flight.trajectory->at(t_imu_s), rng));
            ++tally.imu_samples;
        }
    }
    return tally;
}

void hull_flight(benchmark::State& state, const FlightCase* flight, int threads) {
    const ParallelConfig parallel{.num_threads = threads};
    FlightTally tally;
    double seconds = 0.0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        tally = fly(*flight, parallel);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    const double runs = static_cast<double>(state.iterations());
    state.counters["x_realtime"] = kFlightS * runs / seconds;
    state.counters["points_per_sweep"] =
        static_cast<double>(tally.points) / (kFlightS * kLidarRateHz);
    state.counters["imu_samples"] = static_cast<double>(tally.imu_samples);
}

void add_case(std::string name, const sim::World& world, const sim::RayCaster& caster,
              std::unique_ptr<sim::LawnmowerTrajectory> trajectory) {
    std::printf(
        "flight %s: %zu triangles; lawnmower of %.0f s (%d slices), first %.0f s flown: "
        "%d OS1-64 64 x 1024 sweeps + IMU at %.0f Hz\n",
        name.c_str(), world.mesh.num_triangles(), trajectory->duration_s(),
        trajectory->num_slices(), kFlightS, static_cast<int>(kFlightS * kLidarRateHz), kImuRateHz);
    cases().push_back({std::move(name), &world, &caster, std::move(trajectory)});
}

}  // namespace

void register_flight_benchmarks(const sim::World* dtc_world, const sim::RayCaster* dtc_caster) {
    static const ParametricHull parametric;
    const sim::ShipHullConfig hull;  // the defaults build_ship_hull() used
    add_case("hull_flight_60s", parametric.world, parametric.caster,
             side_sweep(hull.length_m - 1.0, hull.length_m - 2.0, hull.half_breadth_m, 7.0));
    if (dtc_world != nullptr && dtc_caster != nullptr) {
        // Mid-body, where the side is flat: 60 m of side centred on the middle, below the top.
        const Aabb box = surface_bounds(*dtc_world, "hull");
        const double mid_x = 0.5 * (box.min.x() + box.max.x());
        add_case("dtc_hull_flight_60s", *dtc_world, *dtc_caster,
                 side_sweep(mid_x + 30.0, 60.0, box.max.y(), 0.5 * (box.min.z() + box.max.z())));
    }
    for (const FlightCase& flight : cases()) {
        for (int threads : {1, 2}) {
            benchmark::RegisterBenchmark(fmt::format("{}/ours/{}thr", flight.name, threads).c_str(),
                                         hull_flight, &flight, threads)
                ->Unit(benchmark::kSecond)
                ->UseRealTime()
                ->Iterations(1);
        }
    }
}

}  // namespace scantling::bench
