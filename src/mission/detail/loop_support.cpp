// What the vehicles' closed loops share (loop_support.hpp).
#include "loop_support.hpp"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <scantling/sim/scenario_runner.hpp>

#include <scantling/core/random.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/tum.hpp>

namespace scantling::mission::detail {
namespace {

namespace layout = io::recording_layout;

std::vector<io::PathPointRecord> path_records(const planning::WaypointPath& path) {
    std::vector<io::PathPointRecord> records;
    for (const planning::Waypoint& wp : path.waypoints) {
        records.push_back({wp.p_world_m, wp.tolerance_m});
    }
    return records;
}

}  // namespace

void write_text(const std::string& path, const std::string& text) {
    io::write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

io::ImuRecord imu_record(const sim::ImuSample& sample) {
    return {sample.stamp_s, sample.specific_force_mps2, sample.angular_rate_radps};
}

std::vector<io::UwbRecord> uwb_records(const sim::UwbMeasurement& round) {
    std::vector<io::UwbRecord> records;
    records.reserve(round.ranges.size());
    for (const sim::UwbRange& r : round.ranges) {
        records.push_back({round.stamp_s, r.anchor_id, r.range_m, r.valid, r.line_of_sight});
    }
    return records;
}

io::EstimateRecord estimate_record(const localization::DroneState& estimate, double t_s,
                                   bool valid) {
    const auto& P = estimate.covariance;
    return {.stamp_s = t_s,
            .T_world_body = estimate.T_odom_body,
            .v_world_mps = estimate.v_odom_mps,
            .position_sigma_m =
                Eigen::Vector3d(std::sqrt(P(0, 0)), std::sqrt(P(1, 1)), std::sqrt(P(2, 2))),
            .yaw_sigma_rad = std::sqrt(P(5, 5)),
            .valid = valid};
}

void throw_if_stop_requested(const MissionRunOptions& options, const sim::Simulator& sim,
                             const std::string& directory) {
    if (!options.stop_requested || !options.stop_requested()) return;
    throw sim::ScenarioInterrupted(
        fmt::format("interrupted at simulated t = {:.3f} s; nothing was written to {}", sim.now_s(),
                    directory));
}

std::vector<control::OperatorCommand> operator_commands_due(control::OperatorScript& script,
                                                            const sim::Simulator& sim) {
    std::vector<control::OperatorCommand> commands = script.due(sim.now_s());
    if (sim.tick() == 0) commands.insert(commands.begin(), {control::OperatorCommandType::kStart});
    return commands;
}

void log_operator(MissionFiles& files, std::span<const control::OperatorCommand> commands,
                  double t_s) {
    for (const control::OperatorCommand& c : commands) {
        nlohmann::ordered_json j{{"command", std::string(control::to_string(c.type))}};
        if (c.type == control::OperatorCommandType::kTakeOver) {
            j["v_world_mps"] = {c.v_world_mps.x(), c.v_world_mps.y(), c.v_world_mps.z()};
            j["yaw_rate_radps"] = c.yaw_rate_radps;
        }
        files.add_event(t_s, "operator", j.dump());
    }
}

void log_faults(MissionFiles& files, FaultInjector& faults, double t_s) {
    for (const FaultChange& change : faults.changes(t_s)) {
        const SensorFault& f = faults.faults()[change.fault];
        nlohmann::ordered_json j{{"fault", change.fault},
                                 {"sensor", std::string(sim::to_string(f.sensor))},
                                 {"kind", std::string(to_string(f.kind))}};
        if (change.started) j["duration_s"] = f.duration_s;
        files.add_event(t_s, change.started ? "fault_started" : "fault_ended", j.dump());
    }
}

std::vector<sim::SensorType> sensor_types(const sim::Scenario& simulation) {
    std::vector<sim::SensorType> types;
    for (const sim::SensorSpec& sensor : simulation.sensors) types.push_back(sensor.type);
    return types;
}

sim::RecordingSummary recording_summary(const std::string& name, const std::string& description,
                                        const sim::Scenario& simulation,
                                        const sim::Simulator& sim) {
    sim::RecordingSummary summary{.scenario = name,
                                  .description = description,
                                  .world = std::string(sim::to_string(simulation.world.type)),
                                  .duration_s = sim.now_s(),
                                  .dt_s = simulation.dt_s,
                                  .seed = simulation.seed,
                                  .sensors = {}};
    for (std::size_t i = 0; i < simulation.sensors.size(); ++i) {
        summary.sensors.emplace_back(std::string(sim::to_string(simulation.sensors[i].type)),
                                     sim.sensor_rate_hz(i));
    }
    return summary;
}

void write_mission_files(const sim::RecordingWriter& writer, const MissionFiles& files,
                         const planning::WaypointPath& path, const std::string& summary) {
    const std::filesystem::path dir =
        std::filesystem::path(writer.staging_directory()) / layout::kMissionDir;
    std::filesystem::create_directories(dir);
    const auto file = [&dir](const char* name) { return (dir / name).string(); };
    write_text(file(layout::kMissionEstimates), io::estimates_csv(files.estimates));
    std::vector<io::StampedPose> poses;
    for (const io::EstimateRecord& e : files.estimates)
        poses.push_back({e.stamp_s, e.T_world_body});
    io::write_tum(file(layout::kMissionEstimatesTum), poses);
    write_text(file(layout::kMissionCommands), io::commands_csv(files.commands));
    write_text(file(layout::kMissionEvents), files.events);
    write_text(file(layout::kMissionPath), io::intended_path_csv(path_records(path)));
    write_text(file(layout::kMissionSummary), summary);
}

void write_world_if_exported(sim::RecordingWriter& writer, const sim::Scenario& simulation,
                             const sim::Simulator& sim) {
    if (!simulation.export_world.world) return;
    writer.write_world(sim.world(), {.map_spacing_m = simulation.export_world.map_spacing_m,
                                     .seed = Rng(simulation.seed).split(100).next_u64()});
}

}  // namespace scantling::mission::detail
