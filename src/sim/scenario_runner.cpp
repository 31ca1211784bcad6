// The scenario loop (scenario_runner.hpp).
#include <scantling/sim/scenario_runner.hpp>

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/sim_clock.hpp>

#include "detail/scenario_parts.hpp"

namespace scantling::sim {
namespace {

using detail::kMapStream;
using detail::kVehicleStream;
using Sensors = detail::ScenarioSensors;
constexpr double kStampTolerance_s = 1e-9;

RecordingSummary summary_of(const Scenario& scenario, const Sensors& sensors, double duration_s) {
    RecordingSummary summary{.scenario = scenario.name,
                             .description = scenario.description,
                             .world = std::string(to_string(scenario.world.type)),
                             .duration_s = duration_s,
                             .dt_s = scenario.dt_s,
                             .seed = scenario.seed,
                             .sensors = {}};
    for (std::size_t i = 0; i < sensors.size(); ++i) {
        summary.sensors.emplace_back(std::string(to_string(scenario.sensors[i].type)),
                                     sensors[i]->rate_hz());
    }
    return summary;
}

struct Loop {
    const Scenario& scenario;
    const SceneView& scene;
    const detail::VehicleHistory& vehicle;
    Sensors& sensors;
    RecordingWriter& writer;
    const ScenarioRunOptions& options;
    double duration_s;
};

void report(const Loop& loop, double t_s) {
    if (loop.options.progress) {
        loop.options.progress({t_s, loop.duration_s, loop.writer.counts().lidar_sweeps});
    }
}

void stop_if_requested(const ScenarioRunOptions& options, double t_s, double duration_s,
                       const std::string& directory) {
    if (options.stop_requested && options.stop_requested()) {
        throw ScenarioInterrupted(fmt::format(
            "interrupted at simulated t = {:.3f} s of {:.3f} s; nothing was written to {}", t_s,
            duration_s, directory));
    }
}

void stop_if_requested(const Loop& loop, double t_s) {
    stop_if_requested(loop.options, t_s, loop.duration_s, loop.writer.directory());
}

void run_loop(const Loop& loop) {
    SimClock clock(loop.scenario.dt_s);
    for (const auto& sensor : loop.sensors)
        clock.add(RateSchedule{.rate_hz = sensor->rate_hz(), .phase_s = 0.0});
    double next_report_s = 1.0;
    for (std::int64_t k = 0; k < loop.vehicle.num_ticks(); ++k, clock.advance()) {
        stop_if_requested(loop, clock.now_s());
        const MotionState& state = loop.vehicle.at_tick(k);
        loop.writer.add_ground_truth(clock.now_s(), state.T_world_body);
        for (const std::size_t i : clock.due_now()) {
            const double stamp_s = clock.last_fire_time_s(i);
            // Measurements start in [0, duration): a sweep at the end would see no motion.
            if (stamp_s >= loop.duration_s - kStampTolerance_s) continue;
            // Obstacles frozen at the stamp for the whole firing (sensor_mount.hpp, SceneView).
            const SceneView scene = loop.scene.at_time(stamp_s);
            const detail::FireContext context{scene, loop.vehicle, k, stamp_s,
                                              loop.scenario.parallel};
            loop.writer.add(
                {.sensor_index = i, .stamp_s = stamp_s, .data = loop.sensors[i]->fire(context)});
        }
        if (clock.now_s() >= next_report_s) {
            report(loop, clock.now_s());
            next_report_s += 1.0;
        }
    }
}

}  // namespace

namespace detail {

ScenarioSensors make_scenario_sensors(const Scenario& scenario, const Rng& root) {
    ScenarioSensors sensors;
    for (std::size_t i = 0; i < scenario.sensors.size(); ++i) {
        const std::string prefix = "sensors[" + std::to_string(i) + "]";
        sensors.push_back(
            make_sensor(scenario.sensors[i], root.split(kFirstSensorStream + i), prefix));
        const SensorType type = scenario.sensors[i].type;
        const bool motion = type == SensorType::kImu || type == SensorType::kVio ||
                            type == SensorType::kDvl || type == SensorType::kWheelOdometry;
        // Motion sensors sample the tick state: at most one sample per tick.
        if (motion && sensors.back()->rate_hz() * scenario.dt_s > 1.0 + 1e-9) {
            throw ConfigError(prefix + ".rate_hz = " + std::to_string(sensors.back()->rate_hz()) +
                              ", expected <= 1 / dt_s = " + std::to_string(1.0 / scenario.dt_s));
        }
    }
    return sensors;
}

}  // namespace detail

double scenario_duration_s(const Scenario& scenario) {
    if (scenario.duration_s > 0.0) return scenario.duration_s;
    return make_trajectory(scenario.vehicle.trajectory)->duration_s();
}

ScenarioRunResult run_scenario(const Scenario& scenario, const std::string& directory,
                               const ScenarioRunOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    scenario.validate();
    const double duration_s = scenario_duration_s(scenario);
    // Ticks cover [0, duration] (the tolerance absorbs 10 / 0.005 = 1999.9999...).
    const auto num_ticks =
        static_cast<std::int64_t>(std::floor(duration_s / scenario.dt_s + 1e-6)) + 1;
    const Rng root(scenario.seed);
    Sensors sensors = detail::make_scenario_sensors(scenario, root);
    const World world = build_world(scenario.world, scenario.base_directory);
    Rng vehicle_rng = root.split(kVehicleStream);
    const detail::VehicleHistory vehicle = detail::simulate_vehicle(
        scenario.vehicle, scenario.world, world, scenario.dt_s, num_ticks, vehicle_rng);
    const RayCaster caster(world.mesh, world.surface_tags);
    const MovingObstacles obstacles(scenario.moving_obstacles);
    const SceneView scene{caster, world.metadata, &obstacles, 0.0};

    stop_if_requested(options, 0.0, duration_s, directory);  // the world may take a while
    RecordingWriter writer(directory, options.overwrite);
    if (scenario.export_world.world) {
        writer.write_world(world,
                           WorldExportConfig{.map_spacing_m = scenario.export_world.map_spacing_m,
                                             .seed = root.split(kMapStream).next_u64()});
    }
    const Loop loop{scenario, scene, vehicle, sensors, writer, options, duration_s};
    report(loop, 0.0);
    run_loop(loop);
    writer.finish(summary_of(scenario, sensors, duration_s));
    report(loop, duration_s);

    ScenarioRunResult result{.directory = directory,
                             .counts = writer.counts(),
                             .duration_s = duration_s,
                             .wall_time_s = 0.0,
                             .world_triangles = world.mesh.num_triangles()};
    result.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writer.write_timing(result.wall_time_s, duration_s / std::max(result.wall_time_s, 1e-9));
    stop_if_requested(loop, duration_s);
    writer.commit();
    return result;
}

}  // namespace scantling::sim
