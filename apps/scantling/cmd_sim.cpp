// `scantling sim SCENARIO.yaml --out DIR [--seed N] [--force]`.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/scenario_estimate.hpp>
#include <scantling/sim/scenario_runner.hpp>

#include "scantling/commands.hpp"
#include "scantling/interrupt.hpp"

namespace scantling::app {
namespace {

/// One progress line on stderr, redrawn in place.
void draw_progress(const sim::ScenarioProgress& p) {
    const double percent = p.duration_s > 0.0 ? 100.0 * p.sim_time_s / p.duration_s : 100.0;
    fmt::print(stderr, "\rsimulating: {:6.1f} / {:.1f} s ({:5.1f} %), {} sweeps", p.sim_time_s,
               p.duration_s, percent, p.lidar_sweeps);
    std::fflush(stderr);
}

std::string summary_text(const sim::Scenario& scenario, const sim::ScenarioRunResult& r) {
    const sim::RecordingCounts& c = r.counts;
    std::string text = fmt::format("recording: {}\n", r.directory);
    text += fmt::format("scenario: {} (world {}, seed {})\n", scenario.name,
                        sim::to_string(scenario.world.type), scenario.seed);
    text += fmt::format("simulated: {:.3f} s\n", r.duration_s);
    text += fmt::format("sweeps: {}\npoints: {}\n", c.lidar_sweeps, c.lidar_points);
    text += fmt::format("depth_frames: {}\nimages: {}\nimu: {}\nvio: {}\nground_truth: {}\n",
                        c.depth_frames, c.images, c.imu, c.vio, c.ground_truth);
    text += fmt::format("wall_time: {:.3f} s\nreal_time_factor: {:.2f}x\n", r.wall_time_s,
                        r.duration_s / std::max(r.wall_time_s, 1e-9));
    return text;
}

}  // namespace

void run_sim(const SimOptions& options, std::ostream& out) {
    if (options.out.empty()) throw ConfigError("--out is required");
    io::ensure_output_distinct(options.out, {options.scenario});
    sim::Scenario scenario = sim::load_scenario(options.scenario);
    if (options.seed) scenario.seed = *options.seed;
    if (options.num_threads != 0) scenario.parallel.num_threads = options.num_threads;
    // Runs over the hard limit were refused by validation; a large one is announced up front.
    const sim::RecordingEstimate estimate = sim::estimate_recording(scenario);
    if (estimate.total_bytes > sim::kLargeRecordingBytes)
        fmt::print(stderr, "note: {}\n", estimate.describe());
    // From here on Ctrl-C stops the run between two ticks and removes the partial recording.
    const InterruptScope interrupt;
    sim::ScenarioRunOptions run_options;
    run_options.overwrite = options.force;
    run_options.stop_requested = [&interrupt] { return interrupt.requested(); };
    if (options.progress) run_options.progress = draw_progress;
    sim::ScenarioRunResult result;
    try {
        result = sim::run_scenario(scenario, options.out, run_options);
    } catch (const sim::ScenarioInterrupted& e) {
        if (options.progress) std::fputs("\n", stderr);
        exit_interrupted(e.what(), interrupt.signal_number());
    }
    if (options.progress) std::fputs("\n", stderr);
    out << summary_text(scenario, result);
}

}  // namespace scantling::app
