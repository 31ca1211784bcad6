// The closed loop (closed_loop.hpp).
#include <scantling/mission/closed_loop.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <variant>

#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/mission_log.hpp>
#include <scantling/io/tum.hpp>
#include <scantling/sim/recording_writer.hpp>
#include <scantling/sim/scenario_runner.hpp>
#include <scantling/sim/simulator.hpp>

#include "detail/coverage_monitor.hpp"
#include "detail/loop_metrics.hpp"
#include "detail/loop_support.hpp"

namespace scantling::mission {
namespace {

using detail::log_faults;
using detail::log_operator;
using detail::MissionFiles;
using detail::recording_summary;
using detail::sensor_types;
using detail::StageClock;
using detail::write_mission_files;

bool is_frame(const sim::SensorReading& r) {
    return std::holds_alternative<sim::LidarReading>(r.data);
}

/// One reading to the stack, as the io type a recording gives.
void feed(DroneStack& stack, const sim::SensorReading& reading, detail::LoopMetrics& metrics,
          LoopTiming& timing) {
    StageClock clock(is_frame(reading) ? timing.odometry_s : timing.estimators_s);
    if (const auto* imu = std::get_if<sim::ImuSample>(&reading.data)) {
        stack.add_imu(detail::imu_record(*imu));
    } else if (const auto* range = std::get_if<sim::RangeMeasurement>(&reading.data)) {
        stack.add_range({range->stamp_s, range->valid, range->range_m});
    } else if (const auto* baro = std::get_if<sim::BarometerSample>(&reading.data)) {
        stack.add_barometer({baro->stamp_s, baro->altitude_m});
    } else if (const auto* uwb = std::get_if<sim::UwbMeasurement>(&reading.data)) {
        for (const io::UwbRecord& record : detail::uwb_records(*uwb)) stack.add_uwb(record);
    } else if (const auto* lidar = std::get_if<sim::LidarReading>(&reading.data)) {
        metrics.add_odometry(stack.add_sweep(lidar->sweep, reading.stamp_s));
    }
}

std::string event_json(const control::MissionEvent& e) {
    nlohmann::ordered_json j;
    if (e.type == control::MissionEventType::kStateChanged) {
        j["from"] = std::string(control::to_string(e.from));
        j["to"] = std::string(control::to_string(e.to));
    }
    if (e.waypoint_index) j["waypoint"] = *e.waypoint_index;
    if (e.home_leg) j["home_leg"] = true;
    if (e.command) j["command"] = std::string(control::to_string(*e.command));
    if (!e.sensor.empty()) j["sensor"] = e.sensor;
    if (!e.reason.empty()) j["reason"] = e.reason;
    return j.empty() ? "{}" : j.dump();
}

void log_command(MissionFiles& files, const StackCommand& c, double t_s) {
    files.commands.push_back({.stamp_s = t_s,
                              .v_world_mps = c.v_world_mps,
                              .yaw_rate_radps = c.yaw_rate_radps,
                              .v_requested_world_mps = c.v_requested_world_mps,
                              .limited = c.limited});
    for (const control::MissionEvent& e : c.events) {
        files.add_event(e.t_s, std::string(control::to_string(e.type)), event_json(e));
    }
    if (c.limited != files.limited) {
        nlohmann::ordered_json j;
        if (c.collision) {
            j["status"] = std::string(safety::to_string(c.collision->status));
            if (c.collision->d_o_m) j["d_o_m"] = *c.collision->d_o_m;
        }
        files.add_event(t_s, c.limited ? "safety_limited" : "safety_released",
                        j.empty() ? "{}" : j.dump());
        files.limited = c.limited;
    }
}

/// To the recording and the stack, or, inside a fault window, to the stack as NaNs or not at
/// all (fault_injection.hpp).
void deliver(const sim::SensorReading& reading, const FaultInjector& faults,
             sim::RecordingWriter& writer, DroneStack& stack, detail::LoopMetrics& metrics,
             LoopTiming& timing) {
    const bool recorded =
        detail::deliver(reading, faults, writer, timing.record_s,
                        [&](const sim::SensorReading& r) { feed(stack, r, metrics, timing); });
    if (!recorded) return;
    if (const auto* lidar = std::get_if<sim::LidarReading>(&reading.data)) {
        metrics.add_sweep(lidar->sweep);
    }
}

}  // namespace

MissionResult run_mission(const MissionScenario& scenario, const std::string& directory,
                          const MissionRunOptions& options) {
    const auto wall_start = std::chrono::steady_clock::now();
    scenario.validate();
    sim::Scenario simulation = scenario.simulation;
    sim::Simulator sim(simulation, scenario.T_world_body_start());
    sim::RecordingWriter writer(directory, options.overwrite);
    detail::write_world_if_exported(writer, simulation, sim);
    DroneStackConfig stack_config = scenario.stack;
    // LiODOM parallelises its extraction and registration with results independent of the
    // thread count (odometry/liodom.hpp); the loop itself stays sequential.
    stack_config.odometry.set_num_threads(simulation.parallel.num_threads);
    DroneStack stack(stack_config, scenario.path, scenario.T_world_body_start(), 0.0);
    control::OperatorScript script(scenario.operator_script);
    detail::LoopMetrics metrics(scenario.path, scenario.T_world_body_start().translation());
    MissionFiles files;
    LoopTiming timing;
    std::optional<detail::CoverageMonitor> coverage;
    if (scenario.coverage) coverage.emplace(*scenario.coverage, sim.scene());
    FaultInjector faults(scenario.faults, sensor_types(simulation));
    std::optional<double> ended_at_s;
    double next_progress_s = 0.0;
    const double duration_s = simulation.duration_s;

    sim::SimStep step = sim.start();
    while (true) {
        detail::throw_if_stop_requested(options, sim, directory);
        const double t_s = sim.now_s();
        {
            StageClock clock(timing.record_s);
            writer.add_ground_truth(t_s, step.truth.T_world_body);
        }
        std::stable_partition(step.readings.begin(), step.readings.end(),
                              [](const sim::SensorReading& r) { return !is_frame(r); });
        log_faults(files, faults, t_s);
        for (const sim::SensorReading& reading : step.readings) {
            deliver(reading, faults, writer, stack, metrics, timing);
        }
        std::vector<control::OperatorCommand> commands = detail::operator_commands_due(script, sim);
        log_operator(files, commands, t_s);
        const StackCommand command = [&] {
            StageClock clock(timing.command_s);
            return stack.command(t_s, commands);
        }();
        {
            StageClock clock(timing.log_s);
            log_command(files, command, t_s);
            const localization::DroneState estimate = stack.estimate();
            files.estimates.push_back(
                detail::estimate_record(estimate, t_s, stack.estimate_valid()));
            metrics.add_tick(step.truth, estimate, command, t_s);
            if (coverage) coverage->add(t_s, step.truth.T_world_body);
        }
        if (options.progress && t_s >= next_progress_s) {
            options.progress({t_s, duration_s, command.state});
            next_progress_s += 1.0;
        }
        if (detail::mission_ended(command.state) && !ended_at_s) ended_at_s = t_s;
        if (ended_at_s && t_s >= *ended_at_s + scenario.linger_s) break;
        if (t_s >= duration_s - 1e-9) {
            files.add_event(t_s, "timeout",
                            fmt::format(R"({{"state":"{}"}})", control::to_string(command.state)));
            break;
        }
        StageClock clock(timing.simulate_s);
        step = sim.step(
            {.v_world_mps = command.v_world_mps, .yaw_rate_radps = command.yaw_rate_radps});
    }
    MissionResult result = metrics.result(stack.manager().state());
    const localization::LocalEkfCounters& local = stack.local_ekf().counters();
    result.increments_applied = local.increments_applied;
    result.increments_rejected = local.increments_rejected;
    result.ranges_applied = local.ranges_applied;
    result.ranges_rejected = local.ranges_rejected;
    result.uwb_applied = stack.global_ekf().counters().uwb_applied;
    result.uwb_rejected = stack.global_ekf().counters().uwb_rejected;
    result.uwb_reacquisitions = stack.global_ekf().counters().uwb_reacquisitions;
    result.inputs_rejected = stack.inputs_rejected();
    result.timing = timing;
    if (coverage) result.coverage = coverage->result();
    result.directory = directory;
    result.sim_time_s = sim.now_s();
    result.events = files.num_events;
    writer.finish(recording_summary(scenario.name, scenario.description, scenario.simulation, sim));
    detail::stamp_wall_time(result, wall_start);
    write_mission_files(writer, files, scenario.path, detail::summary_json(scenario, result));
    writer.write_timing(result.wall_time_s, result.real_time_factor);
    writer.commit();
    return result;
}

}  // namespace scantling::mission
