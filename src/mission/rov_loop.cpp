// The ROV hull survey's closed loop (rov_mission.hpp).
#include <scantling/mission/rov_mission.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <variant>

#include <scantling/core/error.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/mapping/hull_coverage.hpp>
#include <scantling/sim/recording_writer.hpp>
#include <scantling/sim/scenario_runner.hpp>
#include <scantling/sim/simulator.hpp>

#include "detail/coverage_monitor.hpp"
#include "detail/loop_support.hpp"
#include "detail/rov_metrics.hpp"

namespace scantling::mission {
namespace {

using detail::MissionFiles;
using detail::StageClock;

/// Sonar pings and images after the motion and ranging samples of their tick.
bool is_perception(const sim::SensorReading& r) {
    return std::holds_alternative<sim::SonarReading>(r.data) ||
           std::holds_alternative<sim::ImageReading>(r.data);
}

/// The loop's per-run state besides the stack.
struct RovLoop {
    sim::Simulator& sim;
    RovStack& stack;
    detail::RovMetrics& metrics;
    LoopTiming& timing;
};

void feed_image(RovLoop& loop, const sim::ImageReading& image) {
    const auto lasers = loop.stack.add_image(image.image, image.stamp_s);
    if (lasers && lasers->ok()) {
        loop.metrics.add_laser(loop.sim.scene(), image.T_world_sensor, lasers->distance_m);
    }
}

/// One reading to the stack, as the io type a recording gives.
void feed(RovLoop& loop, const sim::SensorReading& reading) {
    StageClock clock(is_perception(reading) ? loop.timing.odometry_s : loop.timing.estimators_s);
    RovStack& stack = loop.stack;
    if (const auto* imu = std::get_if<sim::ImuSample>(&reading.data)) {
        stack.add_imu(detail::imu_record(*imu));
    } else if (const auto* dvl = std::get_if<sim::DvlSample>(&reading.data)) {
        stack.add_dvl({dvl->stamp_s, dvl->valid, dvl->v_body_mps, dvl->altitude_m});
    } else if (const auto* p = std::get_if<sim::PressureSample>(&reading.data)) {
        stack.add_pressure({p->stamp_s, p->pressure_pa, p->depth_m});
    } else if (const auto* sonar = std::get_if<sim::SonarReading>(&reading.data)) {
        stack.add_sonar(sim::to_sonar_ping(sonar->image));
    } else if (const auto* image = std::get_if<sim::ImageReading>(&reading.data)) {
        feed_image(loop, *image);
    }
}

void log_command(MissionFiles& files, const RovStackCommand& c, double t_s) {
    files.commands.push_back({.stamp_s = t_s,
                              .v_world_mps = c.v_world_mps,
                              .yaw_rate_radps = c.yaw_rate_radps,
                              .v_requested_world_mps = c.v_world_mps,
                              .limited = c.backing_off});
    for (const StackEvent& e : c.events) files.add_event(e.t_s, e.type, e.json);
}

/// The sonar map's voxels for the operator: mean, normal, points and uncertainty.
std::string sonar_map_csv(const mapping::SonarInspectionMap& map) {
    std::string text = "# x_m y_m z_m nx ny nz points uncertainty_m first_s last_s\n";
    for (const mapping::SonarVoxel& v : map.voxels()) {
        text += fmt::format("{:.4f} {:.4f} {:.4f} {:.4f} {:.4f} {:.4f} {} {:.4f} {:.3f} {:.3f}\n",
                            v.mean_world_m.x(), v.mean_world_m.y(), v.mean_world_m.z(),
                            v.normal_world.x(), v.normal_world.y(), v.normal_world.z(),
                            v.num_points, v.uncertainty_m, v.first_stamp_s, v.last_stamp_s);
    }
    return text;
}

/// The sonar map's share of the section (hull_coverage.hpp), its plane as planned.
double sonar_coverage(const mapping::SonarInspectionMap& map,
                      const perception::InspectionRectangle& section) {
    const mapping::InspectedSurface surface{.origin_world_m = section.corner_world,
                                            .axis_u_world = section.u_world,
                                            .axis_v_world = section.v_world,
                                            .extent_u_m = section.width_m,
                                            .extent_v_m = section.height_m};
    return mapping::coverage_of(map, surface).covered_fraction;
}

/// The stack's counters and maps into the result.
void add_stack_figures(const RovStack& stack, RovMissionResult& r) {
    const RovStack::Counters& c = stack.counters();
    r.contacts = stack.contacts().num_contacts();
    r.pings = c.pings;
    r.hull_lines = c.hull_lines;
    r.images = c.images;
    r.laser_measurements = c.laser_measurements;
    r.dvl_invalid = c.dvl_invalid;
    r.inputs_rejected = c.inputs_rejected;
    r.holes_found = c.holes_found;
    r.reinspection_rounds = c.reinspection_rounds;
    r.believed_coverage_final = stack.believed_coverage().result().covered_fraction;
    const std::vector<mapping::SonarVoxel> voxels = stack.sonar_map().voxels();
    r.sonar_voxels = voxels.size();
    double sum = 0.0;
    for (const mapping::SonarVoxel& v : voxels) sum += v.uncertainty_m;
    r.sonar_voxel_uncertainty_mean_m = voxels.empty() ? 0.0 : sum / voxels.size();
    r.sonar_coverage = sonar_coverage(stack.sonar_map(), stack.inspected());
}

/// One tick's readings to the recording and the stack (motion and ranging first, then the
/// pings and images, which need the estimate at their stamp), with the fault windows logged.
void deliver_tick(RovLoop& loop, sim::SimStep& step, FaultInjector& faults,
                  sim::RecordingWriter& writer, MissionFiles& files, double t_s) {
    {
        StageClock clock(loop.timing.record_s);
        writer.add_ground_truth(t_s, step.truth.T_world_body);
    }
    std::stable_partition(step.readings.begin(), step.readings.end(),
                          [](const sim::SensorReading& r) { return !is_perception(r); });
    detail::log_faults(files, faults, t_s);
    for (const sim::SensorReading& reading : step.readings) {
        detail::deliver(reading, faults, writer, loop.timing.record_s,
                        [&](const sim::SensorReading& r) { feed(loop, r); });
    }
}

/// The survey's own figures, kept when the slices are done (before any re-inspection).
struct SurveyFigures {
    std::optional<perception::CoverageResult> coverage;
    double believed = 0.0;
    bool taken = false;
};

void take_survey_figures(const RovStack& stack, const std::optional<detail::CoverageMonitor>& truth,
                         SurveyFigures& survey) {
    if (survey.taken || stack.phase() == SurveyPhase::kSurvey) return;
    if (truth) survey.coverage = truth->result();
    survey.believed = stack.believed_coverage().result().covered_fraction;
    survey.taken = true;
}

void write_recording(sim::RecordingWriter& writer, const RovMissionScenario& scenario,
                     const sim::Simulator& sim, const RovStack& stack, const MissionFiles& files,
                     const planning::WaypointPath& survey, RovMissionResult& result) {
    writer.finish(
        detail::recording_summary(scenario.name, scenario.description, scenario.simulation, sim));
    detail::write_mission_files(writer, files, survey, detail::rov_summary_json(scenario, result));
    detail::write_text((std::filesystem::path(writer.staging_directory()) /
                        io::recording_layout::kMissionDir / io::recording_layout::kMissionSonarMap)
                           .string(),
                       sonar_map_csv(stack.sonar_map()));
    writer.write_timing(result.wall_time_s, result.real_time_factor);
    writer.commit();
}

}  // namespace

RovMissionResult run_rov_mission(const RovMissionScenario& scenario, const std::string& directory,
                                 const MissionRunOptions& options) {
    const auto wall_start = std::chrono::steady_clock::now();
    scenario.validate();
    const sim::Scenario& simulation = scenario.simulation;
    sim::Simulator sim(simulation, scenario.T_world_body_start());
    sim::RecordingWriter writer(directory, options.overwrite);
    detail::write_world_if_exported(writer, simulation, sim);
    const planning::WaypointPath survey = planning::hull_survey_in_world(
        planning::plan_hull_survey(scenario.flown_plan()), scenario.T_world_flown_hull());
    CoverageSpec section;
    section.rectangle = scenario.section();
    RovStack stack(scenario.stack, survey, section.inspection_rectangle(),
                   scenario.T_world_body_start(), 0.0);
    detail::RovMetrics metrics(scenario.plan.stand_off_m, scenario.stack.T_body_camera,
                               detail::appendage_tags(sim.scene()));
    control::OperatorScript script(scenario.operator_script);
    MissionFiles files;
    LoopTiming timing;
    RovLoop loop{sim, stack, metrics, timing};
    std::optional<detail::CoverageMonitor> truth_coverage;
    if (scenario.coverage) truth_coverage.emplace(*scenario.coverage, sim.scene());
    SurveyFigures survey_figures;
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
        const RovStackCommand command = [&] {
            StageClock clock(timing.command_s);
            return stack.command(t_s, commands);
        }();
        take_survey_figures(stack, truth_coverage, survey_figures);
        {
            StageClock clock(timing.log_s);
            log_command(files, command, t_s);
            const localization::DroneState estimate = stack.estimate();
            files.estimates.push_back(
                detail::estimate_record(estimate, t_s, stack.estimate_valid(t_s)));
            metrics.add_tick(sim.scene(), step.truth, estimate, command, t_s);
            if (truth_coverage && command.state == control::MissionState::kRunning) {
                truth_coverage->add(t_s, step.truth.T_world_body);
            }
        }
        if (options.progress && t_s >= next_progress_s) {
            options.progress({t_s, simulation.duration_s, command.state});
            next_progress_s += 1.0;
        }
        if (detail::mission_ended(command.state) && !ended_at_s) ended_at_s = t_s;
        if (ended_at_s && t_s >= *ended_at_s + scenario.linger_s) break;
        if (t_s >= simulation.duration_s - 1e-9) {
            files.add_event(
                t_s, "timeout",
                fmt::format(R"({{"state":"{}","phase":"{}"}})", control::to_string(command.state),
                            to_string(stack.phase())));
            break;
        }
        StageClock clock(timing.simulate_s);
        step = sim.step(
            {.v_world_mps = command.v_world_mps, .yaw_rate_radps = command.yaw_rate_radps});
    }
    RovMissionResult result = metrics.result(stack.state());
    add_stack_figures(stack, result);
    result.waypoints_survey = survey.waypoints.size();
    result.believed_coverage_survey =
        survey_figures.taken ? survey_figures.believed : result.believed_coverage_final;
    if (truth_coverage) {
        result.coverage = truth_coverage->result();
        result.coverage_survey = survey_figures.taken ? survey_figures.coverage : result.coverage;
    }
    result.timing = timing;
    result.directory = directory;
    result.sim_time_s = sim.now_s();
    result.events = files.num_events;
    detail::stamp_wall_time(result, wall_start);
    write_recording(writer, scenario, sim, stack, files, survey, result);
    return result;
}

}  // namespace scantling::mission
