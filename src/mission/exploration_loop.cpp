// The exploration's closed loop (exploration_mission.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <variant>

#include <scantling/core/error.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/mission/exploration_mission.hpp>
#include <scantling/sim/recording_writer.hpp>
#include <scantling/sim/scenario_runner.hpp>
#include <scantling/sim/simulator.hpp>

#include "detail/exploration_figures.hpp"
#include "detail/loop_support.hpp"

namespace scantling::mission {
namespace {

using detail::MissionFiles;
using detail::StageClock;

/// Depth frames and images after the motion samples of their tick.
bool is_perception(const sim::SensorReading& r) {
    return std::holds_alternative<sim::DepthReading>(r.data) ||
           std::holds_alternative<sim::ImageReading>(r.data);
}

io::VioRecord vio_record(const sim::VioSample& s) {
    return {.stamp_s = s.stamp_s,
            .valid = s.valid,
            .T_odom_body = s.T_odom_body,
            .v_body_mps = s.v_body_mps,
            .variances = s.covariance.diagonal(),
            .feature_quality = std::nullopt};
}

struct ExplorationLoop {
    ExplorationStack& stack;
    detail::ExplorationFigures& figures;
    LoopTiming& timing;
    int record_depth_every = 25;
    std::size_t depth_frames = 0;
};

void feed(ExplorationLoop& loop, const sim::SensorReading& reading) {
    StageClock clock(is_perception(reading) ? loop.timing.odometry_s : loop.timing.estimators_s);
    ExplorationStack& stack = loop.stack;
    if (const auto* imu = std::get_if<sim::ImuSample>(&reading.data)) {
        stack.add_imu(detail::imu_record(*imu));
    } else if (const auto* vio = std::get_if<sim::VioSample>(&reading.data)) {
        stack.add_vio(vio_record(*vio));
    } else if (const auto* baro = std::get_if<sim::BarometerSample>(&reading.data)) {
        stack.add_barometer({.stamp_s = baro->stamp_s, .altitude_m = baro->altitude_m});
    } else if (const auto* depth = std::get_if<sim::DepthReading>(&reading.data)) {
        stack.add_depth(depth->frame, reading.stamp_s);
    } else if (const auto* image = std::get_if<sim::ImageReading>(&reading.data)) {
        stack.add_sightings(image->sightings, image->stamp_s);
        loop.figures.add_image(image->sightings.size());
    }
}

/// Depth frames are recorded one in `record_depth_every` (the map is built from all).
bool recorded(ExplorationLoop& loop, const sim::SensorReading& reading) {
    if (!std::holds_alternative<sim::DepthReading>(reading.data)) return true;
    const std::size_t n = loop.depth_frames++;
    return loop.record_depth_every > 0 &&
           n % static_cast<std::size_t>(loop.record_depth_every) == 0;
}

void deliver_tick(ExplorationLoop& loop, sim::SimStep& step, FaultInjector& faults,
                  sim::RecordingWriter& writer, MissionFiles& files, double t_s) {
    {
        StageClock clock(loop.timing.record_s);
        writer.add_ground_truth(t_s, step.truth.T_world_body);
    }
    std::stable_partition(step.readings.begin(), step.readings.end(),
                          [](const sim::SensorReading& r) { return !is_perception(r); });
    detail::log_faults(files, faults, t_s);
    for (const sim::SensorReading& reading : step.readings) {
        detail::deliver(
            reading, faults, writer, loop.timing.record_s,
            [&](const sim::SensorReading& r) { feed(loop, r); }, recorded(loop, reading));
    }
}

void log_command(MissionFiles& files, const ExplorationCommand& c, double t_s) {
    files.commands.push_back({.stamp_s = t_s,
                              .v_world_mps = c.v_world_mps,
                              .yaw_rate_radps = c.yaw_rate_radps,
                              .v_requested_world_mps = c.v_requested_world_mps,
                              .limited = c.limited});
    for (const StackEvent& e : c.events) files.add_event(e.t_s, e.type, e.json);
}

/// The goals flown as the mission's intended path.
planning::WaypointPath flown_goals(const ExplorationStack& stack) {
    planning::WaypointPath path;
    for (const Eigen::Vector3d& g : stack.goals()) {
        path.waypoints.push_back({.p_world_m = g, .yaw_rad = std::nullopt});
    }
    return path;
}

void write_recording(sim::RecordingWriter& writer, const ExplorationMissionScenario& scenario,
                     const sim::Simulator& sim, const ExplorationStack& stack,
                     const MissionFiles& files, const ExplorationMissionResult& result) {
    writer.finish(
        detail::recording_summary(scenario.name, scenario.description, scenario.simulation, sim));
    detail::write_mission_files(writer, files, flown_goals(stack),
                                detail::exploration_summary_json(scenario, result));
    const std::filesystem::path mission_dir =
        std::filesystem::path(writer.staging_directory()) / io::recording_layout::kMissionDir;
    namespace layout = io::recording_layout;
    detail::write_text((mission_dir / layout::kMissionExplorationCurve).string(),
                       detail::exploration_curve_csv(result));
    detail::write_text((mission_dir / layout::kMissionPlans).string(),
                       detail::exploration_plans_csv(stack));
    stack.map().write_binary((mission_dir / layout::kMissionOccupancyMap).string());
    writer.write_timing(result.wall_time_s, result.real_time_factor);
    writer.commit();
}

/// The ground truth the share is measured against: the free space connected to the start.
detail::ReachableVolume reachable_of(const ExplorationMissionScenario& scenario,
                                     const sim::Simulator& sim) {
    const Eigen::Vector3d start = scenario.T_world_body_start().translation();
    detail::ReachableVolume reachable = detail::reachable_free_volume(
        sim.scene().caster, scenario.bounds_world, scenario.stack.map.resolution_m, start);
    // A vehicle placed in a wall (or a space smaller than itself) has nothing to explore: a
    // simulation user's mistake, refused before anything is written.
    const double box_m3 = scenario.stack.nbv.vehicle_box_m.prod();
    if (reachable.volume_m3() < box_m3) {
        throw InputError(fmt::format(
            "start: the vehicle at ({:.3f}, {:.3f}, {:.3f}) m lies inside the world's surfaces "
            "or in a free space of {:.3f} m3, smaller than the vehicle box ({:.3f} m3)",
            start.x(), start.y(), start.z(), reachable.volume_m3(), box_m3));
    }
    return reachable;
}

}  // namespace

ExplorationMissionResult run_exploration_mission(const ExplorationMissionScenario& scenario,
                                                 const std::string& directory,
                                                 const MissionRunOptions& options) {
    const auto wall_start = std::chrono::steady_clock::now();
    scenario.validate();
    const sim::Scenario& simulation = scenario.simulation;
    sim::Simulator sim(simulation, scenario.T_world_body_start());
    detail::ReachableVolume reachable = reachable_of(scenario, sim);
    sim::RecordingWriter writer(directory, options.overwrite);
    detail::write_world_if_exported(writer, simulation, sim);
    ExplorationStack stack(scenario.stack, scenario.T_world_body_start(), 0.0);
    detail::ExplorationFigures figures(scenario, std::move(reachable));
    control::OperatorScript script(scenario.operator_script);
    MissionFiles files;
    LoopTiming timing;
    ExplorationLoop loop{stack, figures, timing, scenario.record_depth_every};
    FaultInjector faults(scenario.faults, detail::sensor_types(simulation));
    std::optional<double> ended_at_s;
    double next_progress_s = 0.0;

    sim::SimStep step = sim.start();
    while (true) {
        detail::throw_if_stop_requested(options, sim, directory);
        const double t_s = sim.now_s();
        deliver_tick(loop, step, faults, writer, files, t_s);
        std::vector<control::OperatorCommand> commands = detail::operator_commands_due(script, sim);
        detail::log_operator(files, commands, t_s);
        const ExplorationCommand command = [&] {
            StageClock clock(timing.command_s);
            return stack.command(t_s, commands);
        }();
        {
            StageClock clock(timing.log_s);
            log_command(files, command, t_s);
            const localization::DroneState estimate = stack.estimate();
            files.estimates.push_back(
                detail::estimate_record(estimate, t_s, stack.estimate_valid()));
            figures.add_tick(sim.scene(), step.truth, estimate, command.state, t_s);
            figures.sample_volume(stack, t_s);
        }
        if (options.progress && t_s >= next_progress_s) {
            options.progress({t_s, simulation.duration_s, command.state});
            next_progress_s += 1.0;
        }
        if (detail::mission_ended(command.state) && !ended_at_s) {
            ended_at_s = t_s;
            figures.mark_ended(t_s);
            figures.sample_volume(stack, t_s, true);
        }
        if (ended_at_s && t_s >= *ended_at_s + scenario.linger_s) break;
        if (t_s >= simulation.duration_s - 1e-9) {
            files.add_event(
                t_s, "timeout",
                fmt::format(R"({{"state":"{}","phase":"{}"}})", control::to_string(command.state),
                            to_string(stack.phase())));
            figures.sample_volume(stack, t_s, true);
            break;
        }
        StageClock clock(timing.simulate_s);
        step = sim.step(
            {.v_world_mps = command.v_world_mps, .yaw_rate_radps = command.yaw_rate_radps});
    }
    ExplorationMissionResult result = figures.result(stack);
    result.defects_in_world = sim.world().metadata.defects.size();
    result.timing = timing;
    result.directory = directory;
    result.sim_time_s = sim.now_s();
    result.events = files.num_events;
    detail::stamp_wall_time(result, wall_start);
    write_recording(writer, scenario, sim, stack, files, result);
    return result;
}

}  // namespace scantling::mission
