// `scantling mission SCENARIO.yaml --out DIR [--seed N] [--force] [--set KEY=VALUE]...`: one
// closed-loop run.
#include <fmt/format.h>

#include <algorithm>

#include <cstdio>
#include <ostream>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/mission/closed_loop.hpp>
#include <scantling/mission/crawler_mission.hpp>
#include <scantling/mission/exploration_mission.hpp>
#include <scantling/mission/mission_scenario.hpp>
#include <scantling/mission/rov_mission.hpp>
#include <scantling/sim/scenario_runner.hpp>

#include "scantling/commands.hpp"
#include "scantling/interrupt.hpp"

namespace scantling::app {
namespace {

void draw_progress(const mission::MissionProgress& p) {
    fmt::print(stderr, "\rmission: {:6.1f} / {:.1f} s, {:<10}", p.sim_time_s, p.duration_s,
               control::to_string(p.state));
    std::fflush(stderr);
}

std::string summary_text(const mission::MissionScenario& m, const mission::MissionResult& r) {
    std::string text = fmt::format("recording: {}\n", r.directory);
    text += fmt::format("scenario: {} (world {}, seed {})\n", m.name,
                        sim::to_string(m.simulation.world.type), m.simulation.seed);
    text += fmt::format("final_state: {}\n", control::to_string(r.final_state));
    text += fmt::format("waypoints_reached: {} / {}\n", r.waypoints_reached, r.waypoints);
    text += fmt::format("mission_time: {:.1f} s\n", r.mission_time_s);
    text += fmt::format("path_deviation: mean {:.3f} m, max {:.3f} m\n", r.path_deviation_mean_m,
                        r.path_deviation_max_m);
    text += fmt::format(
        "estimate_error: rms {:.3f} m, max {:.3f} m, final {:.3f} m, yaw rms "
        "{:.2f} deg\n",
        r.position_error_rms_m, r.position_error_max_m, r.final_position_error_m,
        r.yaw_error_rms_rad * 180.0 / M_PI);
    if (r.coverage) {
        const perception::CoverageResult& c = *r.coverage;
        text +=
            fmt::format("camera_coverage: {:.1f} % of the rectangle ({:.2f} m2 seen), {} holes{}\n",
                        100.0 * c.covered_fraction, c.covered_area_m2, c.holes.size(),
                        c.holes.empty() ? std::string()
                                        : fmt::format(", largest {:.2f} m2", c.holes[0].area_m2));
    }
    text += fmt::format("estimate_nees: {:.2f} (3 when consistent)\n", r.position_nees_mean);
    text += fmt::format("path_length: {:.1f} m\n", r.path_length_m);
    text += fmt::format("safety_interventions: {} ticks, nearest return {:.2f} m\n",
                        r.safety_interventions, r.min_obstacle_distance_m);
    text += fmt::format("events: {}\nsweeps: {}\n", r.events, r.lidar_sweeps);
    text += fmt::format(
        "fused: lidar increments {} (refused {}), heights {} (refused {}), uwb "
        "ranges {} (refused {}, re-acquired {} times)\n",
        r.increments_applied, r.increments_rejected, r.ranges_applied, r.ranges_rejected,
        r.uwb_applied, r.uwb_rejected, r.uwb_reacquisitions);
    const double iterations_per_sweep = r.odometry_registered > 0
                                            ? static_cast<double>(r.odometry_iterations) /
                                                  static_cast<double>(r.odometry_registered)
                                            : 0.0;
    text += fmt::format(
        "odometry: {} sweeps registered ({} degenerate, {:.1f} iterations each), {} not "
        "registered\n",
        r.odometry_registered, r.odometry_degenerate, iterations_per_sweep,
        r.odometry_unregistered);
    if (r.inputs_rejected > 0) text += fmt::format("inputs_rejected: {}\n", r.inputs_rejected);
    text += fmt::format("wall_time: {:.1f} s\nreal_time_factor: {:.1f}x\n", r.wall_time_s,
                        r.real_time_factor);
    const mission::LoopTiming& t = r.timing;
    const double total = std::max(r.wall_time_s, 1e-9);
    const auto share = [total](double s) { return 100.0 * s / total; };
    text += fmt::format(
        "loop_time: simulate {:.1f} s ({:.0f} %), record {:.1f} s ({:.0f} %), odometry {:.1f} s "
        "({:.0f} %), estimators {:.1f} s ({:.0f} %), command {:.1f} s ({:.0f} %), log {:.1f} s "
        "({:.0f} %)\n",
        t.simulate_s, share(t.simulate_s), t.record_s, share(t.record_s), t.odometry_s,
        share(t.odometry_s), t.estimators_s, share(t.estimators_s), t.command_s, share(t.command_s),
        t.log_s, share(t.log_s));
    return text;
}

std::string coverage_line(std::string_view what, const perception::CoverageResult& c) {
    return fmt::format(
        "{}: {:.1f} % ({:.2f} m2 seen), {} holes{}\n", what, 100.0 * c.covered_fraction,
        c.covered_area_m2, c.holes.size(),
        c.holes.empty() ? std::string() : fmt::format(", largest {:.3f} m2", c.holes[0].area_m2));
}

std::string rov_summary_text(const mission::RovMissionScenario& m,
                             const mission::RovMissionResult& r) {
    std::string text = fmt::format("recording: {}\n", r.directory);
    text += fmt::format(
        "scenario: {} (world {}, seed {}, rov hull survey, {} slices at {:.2f} m)\n", m.name,
        sim::to_string(m.simulation.world.type), m.simulation.seed,
        m.plan.orientation == planning::SliceOrientation::kHorizontal ? "horizontal" : "vertical",
        m.plan.stand_off_m);
    text += fmt::format("final_state: {}\nmission_time: {:.1f} s\n",
                        control::to_string(r.final_state), r.mission_time_s);
    text += fmt::format("stand_off_error: mean {:.3f} m, max {:.3f} m ({} samples)\n",
                        r.stand_off_error_mean_m, r.stand_off_error_max_m, r.stand_off_samples);
    text += fmt::format("heading_error: mean {:.2f} deg, max {:.2f} deg\n",
                        r.heading_error_mean_rad * 180.0 / M_PI,
                        r.heading_error_max_rad * 180.0 / M_PI);
    if (r.coverage_survey)
        text += coverage_line("camera_coverage_after_survey", *r.coverage_survey);
    if (r.coverage) text += coverage_line("camera_coverage_final", *r.coverage);
    text += fmt::format(
        "believed_coverage: {:.1f} % after the survey, {:.1f} % at the end; {} holes re-inspected "
        "in {} rounds\n",
        100.0 * r.believed_coverage_survey, 100.0 * r.believed_coverage_final, r.holes_found,
        r.reinspection_rounds);
    text += fmt::format("estimate_error: rms {:.3f} m, max {:.3f} m, yaw rms {:.2f} deg\n",
                        r.position_error_rms_m, r.position_error_max_m,
                        r.yaw_error_rms_rad * 180.0 / M_PI);
    text += fmt::format(
        "sonar: {} pings, {} hull lines, {} voxels (uncertainty {:.3f} m), {:.1f} % of the "
        "section\n",
        r.pings, r.hull_lines, r.sonar_voxels, r.sonar_voxel_uncertainty_mean_m,
        100.0 * r.sonar_coverage);
    text += fmt::format("lasers: {} of {} images, distance error {:.3f} m\n", r.laser_measurements,
                        r.images, r.laser_distance_error_mean_m);
    text += fmt::format(
        "guidance: paused {} ticks, backing off {} ticks, {} contacts; dvl without lock {}\n",
        r.guidance_paused_ticks, r.backing_off_ticks, r.contacts, r.dvl_invalid);
    if (r.inputs_rejected > 0) text += fmt::format("inputs_rejected: {}\n", r.inputs_rejected);
    text += fmt::format("path_length: {:.1f} m\nevents: {}\n", r.path_length_m, r.events);
    text += fmt::format("wall_time: {:.1f} s\nreal_time_factor: {:.1f}x\n", r.wall_time_s,
                        r.real_time_factor);
    return text;
}

template <class Run>
auto run_interruptible(const MissionOptions& options, Run run) {
    const InterruptScope interrupt;
    mission::MissionRunOptions run_options;
    run_options.overwrite = options.force;
    run_options.stop_requested = [&interrupt] { return interrupt.requested(); };
    if (options.progress) run_options.progress = draw_progress;
    try {
        auto result = run(run_options);
        if (options.progress) std::fputs("\n", stderr);
        return result;
    } catch (const sim::ScenarioInterrupted& e) {
        if (options.progress) std::fputs("\n", stderr);
        exit_interrupted(e.what(), interrupt.signal_number());
    }
}

void run_rov_mission(const MissionOptions& options, std::ostream& out) {
    mission::RovMissionScenario scenario =
        mission::load_rov_mission_scenario(options.scenario, options.overrides);
    if (options.seed) scenario.simulation.seed = *options.seed;
    if (options.num_threads != 0) scenario.simulation.parallel.num_threads = options.num_threads;
    const mission::RovMissionResult result =
        run_interruptible(options, [&](const mission::MissionRunOptions& run_options) {
            return mission::run_rov_mission(scenario, options.out, run_options);
        });
    out << rov_summary_text(scenario, result);
}

std::string crawler_summary_text(const mission::CrawlerMissionScenario& m,
                                 const mission::CrawlerMissionResult& r) {
    std::string text = fmt::format("recording: {}\n", r.directory);
    std::string tasks;
    for (const planning::SurfaceTask& t : m.tasks) {
        tasks += (tasks.empty() ? "" : ", ") + std::string(planning::to_string(t.type));
        if (t.type == planning::SurfaceTaskType::kRectangle) {
            tasks += fmt::format(" {:.2f} x {:.2f} m", t.rectangle.width_m, t.rectangle.height_m);
        }
    }
    text += fmt::format("scenario: {} (world {}, seed {}, crawler tasks: {})\n", m.name,
                        sim::to_string(m.simulation.world.type), m.simulation.seed, tasks);
    if (r.transects > 0) {
        text += fmt::format("rectangle: {} transects {:.3f} m apart\n", r.transects, r.step_m);
    }
    text += fmt::format(
        "final_state: {}\ntasks: {} done, {} failed of {}\nwaypoints_reached: {}\n"
        "mission_time: {:.1f} s\n",
        control::to_string(r.final_state), r.tasks_done, r.tasks_failed, r.tasks,
        r.waypoints_reached, r.mission_time_s);
    text += fmt::format("cross_track: mean {:.3f} m, max {:.3f} m ({} samples)\n",
                        r.cross_track_mean_m, r.cross_track_max_m, r.cross_track_samples);
    if (r.transects > 0) {
        text += fmt::format("coverage: {:.1f} % of the rectangle ({:.2f} m swath)\n",
                            100.0 * r.coverage, m.swath_width_m);
    }
    text += fmt::format("estimate_error: rms {:.3f} m, max {:.3f} m, heading rms {:.2f} deg\n",
                        r.position_error_rms_m, r.position_error_max_m,
                        r.yaw_error_rms_rad * 180.0 / M_PI);
    text += fmt::format("uwb: {} ranges applied, {} refused\n", r.uwb_applied, r.uwb_refused);
    if (r.inputs_rejected > 0) text += fmt::format("inputs_rejected: {}\n", r.inputs_rejected);
    text += fmt::format("path_length: {:.1f} m\nevents: {}\n", r.path_length_m, r.events);
    text += fmt::format("wall_time: {:.1f} s\nreal_time_factor: {:.1f}x\n", r.wall_time_s,
                        r.real_time_factor);
    return text;
}

void run_crawler_mission(const MissionOptions& options, std::ostream& out) {
    mission::CrawlerMissionScenario scenario =
        mission::load_crawler_mission_scenario(options.scenario, options.overrides);
    if (options.seed) scenario.simulation.seed = *options.seed;
    if (options.num_threads != 0) scenario.simulation.parallel.num_threads = options.num_threads;
    const mission::CrawlerMissionResult result =
        run_interruptible(options, [&](const mission::MissionRunOptions& run_options) {
            return mission::run_crawler_mission(scenario, options.out, run_options);
        });
    out << crawler_summary_text(scenario, result);
}

std::string exploration_summary_text(const mission::ExplorationMissionScenario& m,
                                     const mission::ExplorationMissionResult& r) {
    std::string text = fmt::format("recording: {}\n", r.directory);
    text +=
        fmt::format("scenario: {} (world {}, seed {}, explore, {} gain, map {:.2f} m, N_T {})\n",
                    m.name, sim::to_string(m.simulation.world.type), m.simulation.seed,
                    m.stack.nbv.defect_aware ? "defect-aware" : "vanilla", m.stack.map.resolution_m,
                    m.stack.nbv.max_nodes);
    text += fmt::format("final_state: {}{}\n", control::to_string(r.final_state),
                        r.completed ? " (no gain left)" : " (exploration not finished)");
    text += fmt::format("exploration_time: {:.1f} s\n", r.exploration_time_s);
    text += fmt::format("reachable_free_mapped: {:.1f} % of {:.1f} m3 (explored {:.1f} m3)\n",
                        100.0 * r.reachable_share, r.reachable_free_m3, r.explored_m3);
    text += fmt::format("plans: {} ({} failed), {:.3f} s mean, {:.3f} s max\n", r.plans,
                        r.plans_failed, r.plan_time_mean_s, r.plan_time_max_s);
    text += fmt::format("detections_per_image: {:.2f} ({} in {} images), defects mapped {} of {}\n",
                        r.detections_per_image, r.detections, r.images, r.defects_mapped,
                        r.defects_in_world);
    text += fmt::format("estimate_error: rms {:.3f} m, final {:.3f} m\n", r.position_error_rms_m,
                        r.position_error_final_m);
    text += fmt::format("nearest_wall: {:.2f} m\npath_length: {:.1f} m\nevents: {}\n",
                        r.min_wall_distance_m, r.path_length_m, r.events);
    text += fmt::format("wall_time: {:.1f} s\nreal_time_factor: {:.1f}x\n", r.wall_time_s,
                        r.real_time_factor);
    return text;
}

void run_exploration_mission(const MissionOptions& options, std::ostream& out) {
    mission::ExplorationMissionScenario scenario =
        mission::load_exploration_mission_scenario(options.scenario, options.overrides);
    if (options.seed) scenario.simulation.seed = *options.seed;
    if (options.num_threads != 0) scenario.simulation.parallel.num_threads = options.num_threads;
    const mission::ExplorationMissionResult result =
        run_interruptible(options, [&](const mission::MissionRunOptions& run_options) {
            return mission::run_exploration_mission(scenario, options.out, run_options);
        });
    out << exploration_summary_text(scenario, result);
}

}  // namespace

void run_mission(const MissionOptions& options, std::ostream& out) {
    if (options.out.empty()) throw ConfigError("--out is required");
    io::ensure_output_distinct(options.out, {options.scenario});
    if (mission::is_rov_mission_file(options.scenario)) return run_rov_mission(options, out);
    if (mission::is_crawler_mission_file(options.scenario)) {
        return run_crawler_mission(options, out);
    }
    if (mission::is_exploration_mission_file(options.scenario)) {
        return run_exploration_mission(options, out);
    }
    mission::MissionScenario scenario =
        mission::load_mission_scenario(options.scenario, options.overrides);
    if (options.seed) scenario.simulation.seed = *options.seed;
    if (options.num_threads != 0) scenario.simulation.parallel.num_threads = options.num_threads;
    const mission::MissionResult result =
        run_interruptible(options, [&](const mission::MissionRunOptions& run_options) {
            return mission::run_mission(scenario, options.out, run_options);
        });
    out << summary_text(scenario, result);
}

}  // namespace scantling::app
