// `scantling mission SCENARIO.yaml --out DIR [--seed N] [--force]`: one closed-loop run.
#include <fmt/format.h>

#include <cstdio>
#include <ostream>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/mission/closed_loop.hpp>
#include <scantling/mission/mission_scenario.hpp>
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
    text += fmt::format("estimate_nees: {:.2f} (3 when consistent)\n", r.position_nees_mean);
    text += fmt::format("path_length: {:.1f} m\n", r.path_length_m);
    text += fmt::format("safety_interventions: {} ticks, nearest return {:.2f} m\n",
                        r.safety_interventions, r.min_obstacle_distance_m);
    text += fmt::format("events: {}\nsweeps: {}\n", r.events, r.lidar_sweeps);
    text += fmt::format(
        "fused: lidar increments {} (refused {}), heights {} (refused {}), uwb "
        "ranges {} (refused {})\n",
        r.increments_applied, r.increments_rejected, r.ranges_applied, r.ranges_rejected,
        r.uwb_applied, r.uwb_rejected);
    text += fmt::format("wall_time: {:.1f} s\nreal_time_factor: {:.1f}x\n", r.wall_time_s,
                        r.real_time_factor);
    return text;
}

}  // namespace

void run_mission(const MissionOptions& options, std::ostream& out) {
    if (options.out.empty()) throw ConfigError("--out is required");
    io::ensure_output_distinct(options.out, {options.scenario});
    mission::MissionScenario scenario = mission::load_mission_scenario(options.scenario);
    if (options.seed) scenario.simulation.seed = *options.seed;
    if (options.num_threads != 0) scenario.simulation.parallel.num_threads = options.num_threads;
    const InterruptScope interrupt;
    mission::MissionRunOptions run_options;
    run_options.overwrite = options.force;
    run_options.stop_requested = [&interrupt] { return interrupt.requested(); };
    if (options.progress) run_options.progress = draw_progress;
    mission::MissionResult result;
    try {
        result = mission::run_mission(scenario, options.out, run_options);
    } catch (const sim::ScenarioInterrupted& e) {
        if (options.progress) std::fputs("\n", stderr);
        exit_interrupted(e.what(), interrupt.signal_number());
    }
    if (options.progress) std::fputs("\n", stderr);
    out << summary_text(scenario, result);
}

}  // namespace scantling::app
