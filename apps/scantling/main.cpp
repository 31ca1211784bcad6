// `scantling`: command-line tools over the scantling libraries. The only file with CLI11.
// Errors: exactly one line "scantling: error: <message>" on stderr and exit code 2.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <malloc.h>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <iostream>
#include <limits>
#include <string>

#include <scantling/core/parallel.hpp>
#include <scantling/core/text_escape.hpp>

#include "scantling/commands.hpp"
#include "scantling/option_values.hpp"
#include "scantling/terminal_output.hpp"

namespace {

constexpr int kExitError = 2;
const std::string kSeeHelp = " (see scantling --help)";

struct CommandLine {
    bool verbose = false;
    int num_threads = 0;
    double voxel_size_m = 0.0;
    scantling::app::InfoOptions info;
    scantling::app::ConvertOptions convert;
    CLI::App* info_cmd = nullptr;
    CLI::App* convert_cmd = nullptr;
    CLI::App* downsample_cmd = nullptr;
    CLI::Option* convert_voxel = nullptr;
    scantling::app::SimOptions sim;
    CLI::App* sim_cmd = nullptr;
    CLI::Option* sim_seed = nullptr;
    scantling::app::MissionOptions mission;
    CLI::App* mission_cmd = nullptr;
    CLI::Option* mission_seed = nullptr;
    std::uint64_t seed = 0;
    bool no_progress = false;
    scantling::app::RegisterOptions reg;
    CLI::App* register_cmd = nullptr;
    CLI::Option* register_init = nullptr;
    CLI::Option* register_voxel = nullptr;
    CLI::Option* register_max_distance = nullptr;
    std::string init_path;
    double max_distance_m = 0.0;
    scantling::app::EvalOptions eval;
    CLI::App* eval_cmd = nullptr;
    CLI::Option* eval_format = nullptr;
    CLI::Option* eval_plots = nullptr;
    std::string eval_format_name;
    std::string eval_plots_dir;
    bool eval_no_plots = false;
    scantling::app::OdometryOptions odo;
    CLI::App* odometry_cmd = nullptr;
    CLI::Option* odometry_format = nullptr;
    CLI::Option* odometry_preset = nullptr;
    CLI::Option* odometry_config = nullptr;
    CLI::Option* odometry_period = nullptr;
    CLI::Option* odometry_max_frames = nullptr;
    std::string odo_format;
    std::string odo_config;
    double odo_period_s = 0.1;
    std::size_t odo_max_frames = 0;
    scantling::app::LocalizeOptions loc;
    CLI::App* localize_cmd = nullptr;
    struct {
        std::string config, filter, method, vio, map, metadata, cache;
        double rate_hz = 0.0;
        std::size_t max_frames = 0;
        CLI::Option *config_opt = nullptr, *filter_opt = nullptr, *method_opt = nullptr,
                    *vio_opt = nullptr, *map_opt = nullptr, *metadata_opt = nullptr,
                    *cache_opt = nullptr, *rate_opt = nullptr, *max_frames_opt = nullptr;
    } loc_cli;
};

/// One line, escaped: messages quote file names and file contents (terminal_output.hpp).
int report_error(std::string message) {
    std::replace(message.begin(), message.end(), '\n', ' ');
    fmt::print(stderr, "scantling: error: {}\n", scantling::escape_control_characters(message));
    return kExitError;
}

/// More worker threads than any machine this runs on has: a larger --threads is a typo.
constexpr std::uint64_t kMaxThreads = 1024;

/// Integer options: a decimal number in [min, max], checked on the text (option_values.hpp).
CLI::Validator whole_number_in(std::uint64_t min, std::uint64_t max) {
    return {[min, max](std::string& text) {
                return scantling::app::check_decimal_integer(text, min, max);
            },
            "", ""};
}

/// Real options: finite and > 0 or >= 0 (CLI11 alone lets "nan" and "inf" through).
CLI::Validator finite_number(scantling::app::LowerBound bound) {
    return {[bound](std::string& text) { return scantling::app::check_finite_number(text, bound); },
            "", ""};
}

void add_threads_option(CLI::App& app, CommandLine& cl) {
    app.add_option("--threads", cl.num_threads, "Worker threads (0 = all hardware threads)")
        ->type_name("N")
        ->transform(whole_number_in(0, kMaxThreads));
}

void add_in_out(CLI::App& cmd, CommandLine& cl) {
    cmd.add_option("IN", cl.convert.input, "Input cloud: .pcd, .ply or .bin (KITTI velodyne)")
        ->required()
        ->type_name("");
    cmd.add_option("OUT", cl.convert.output,
                   "Output cloud: .pcd, .ply or .bin (format from the extension)")
        ->required()
        ->type_name("");
    cmd.add_flag("--ascii", cl.convert.ascii, "Write ascii PCD (.pcd output only; default binary)");
    add_threads_option(cmd, cl);
}

void define_sim(CLI::App& app, CommandLine& cl) {
    cl.sim_cmd = app.add_subcommand("sim", "Run a simulation scenario and write its recording");
    cl.sim_cmd->add_option("SCENARIO", cl.sim.scenario, "Scenario YAML (see scenarios/)")
        ->required()
        ->type_name("");
    cl.sim_cmd->add_option("--out", cl.sim.out, "Recording directory (created)")
        ->required()
        ->type_name("DIR");
    cl.sim_seed = cl.sim_cmd->add_option("--seed", cl.seed, "Overrides the scenario's seed")
                      ->type_name("N")
                      ->transform(whole_number_in(0, std::numeric_limits<std::uint64_t>::max()));
    cl.sim_cmd->add_flag(
        "--force", cl.sim.force,
        "Replace an existing recording, only once the new one is complete (a folder holding "
        "anything else is refused)");
    cl.sim_cmd->add_flag("--no-progress", cl.no_progress, "No progress line on stderr");
}

void define_mission(CLI::App& app, CommandLine& cl) {
    auto* cmd = cl.mission_cmd = app.add_subcommand(
        "mission", "Fly a mission in closed loop (simulator + the robot's stack) and record it");
    cmd->add_option("SCENARIO", cl.mission.scenario, "Mission scenario YAML (see scenarios/)")
        ->required()
        ->type_name("");
    cmd->add_option("--out", cl.mission.out, "Recording directory (created)")
        ->required()
        ->type_name("DIR");
    cl.mission_seed =
        cmd->add_option("--seed", cl.seed, "Overrides the scenario's seed")
            ->type_name("N")
            ->transform(whole_number_in(0, std::numeric_limits<std::uint64_t>::max()));
    cmd->add_flag("--force", cl.mission.force,
                  "Replace an existing recording, only once the new one is complete");
    cmd->add_option("--set", cl.mission.overrides,
                    "Override a scenario key, e.g. stack.manager.tracking.use_vtp=false "
                    "(repeatable; VALUE in YAML)")
        ->type_name("KEY=VALUE");
    cmd->add_flag("--no-progress", cl.no_progress, "No progress line on stderr");
}

void define_register(CLI::App& app, CommandLine& cl) {
    auto* cmd = cl.register_cmd = app.add_subcommand(
        "register", "Align SRC to TGT and write the 4x4 T_target_source to --out");
    cmd->add_option("SRC", cl.reg.source, "Cloud to align (.pcd, .ply, .bin)")
        ->required()
        ->type_name("");
    cmd->add_option("TGT", cl.reg.target, "Cloud to align it to")->required()->type_name("");
    cmd->add_option("--method", cl.reg.method,
                    "icp, p2plane, gicp (local, from --init), fpfh-teaser, fpfh-ransac (global), "
                    "stein (particles around --init)")
        ->required()
        ->type_name("M");
    cl.register_init = cmd->add_option("--init", cl.init_path,
                                       "Initial T_target_source: 4 lines of 4 numbers (default "
                                       "identity; local methods only)")
                           ->type_name("FILE");
    cl.register_voxel = cmd->add_option("--voxel", cl.voxel_size_m,
                                        "Voxel edge in metres, >= 0 (0 = none; default 0.1 for "
                                        "local methods, 0.05 for global ones)")
                            ->type_name("SIZE_M")
                            ->check(finite_number(scantling::app::LowerBound::kNonNegative));
    cl.register_max_distance =
        cmd->add_option("--max-distance", cl.max_distance_m,
                        "Correspondence distance in metres (default: ICP 1, stein 0.5, "
                        "refinement after a global method 2 voxels)")
            ->type_name("M")
            ->check(finite_number(scantling::app::LowerBound::kPositive));
    cmd->add_option("--back-faces", cl.reg.back_faces,
                    "ICP pairs with target points facing away from the sensor, by the target "
                    "file's normals: keep, prefer_front (default: the nearest front face among "
                    "the 8 nearest) or reject")
        ->type_name("MODE");
    cmd->add_option("--out", cl.reg.out, "Output: the 4x4 T_target_source alone")
        ->required()
        ->type_name("FILE");
    add_threads_option(*cmd, cl);
}

void define_eval(CLI::App& app, CommandLine& cl) {
    auto* cmd = cl.eval_cmd = app.add_subcommand(
        "eval", "Compare an estimated trajectory with ground truth (KITTI RTE/RRE, ATE, RPE)");
    cmd->add_option("--gt", cl.eval.ground_truth, "Ground truth: KITTI poses or TUM trajectory")
        ->required()
        ->type_name("GT");
    cmd->add_option("--est", cl.eval.estimate, "Estimated trajectory, same format as --gt")
        ->required()
        ->type_name("EST");
    cl.eval_format = cmd->add_option("--format", cl.eval_format_name,
                                     "kitti (matched by line) or tum (matched by time stamp); "
                                     "default: from the count of numbers on a line")
                         ->type_name("F");
    cmd->add_option("--max-dt", cl.eval.max_time_difference_s,
                    "TUM: largest time difference of a matched pose, seconds (default 0.02)")
        ->type_name("S")
        ->check(finite_number(scantling::app::LowerBound::kNonNegative));
    cmd->add_flag("--json", cl.eval.json, "Print one JSON object instead of key: value lines");
    cl.eval_plots = cmd->add_option("--plots", cl.eval_plots_dir,
                                    "Folder for <est-stem>_top.svg and <est-stem>_errors.svg "
                                    "(created; default: beside EST)")
                        ->type_name("DIR");
    cmd->add_flag("--no-plots", cl.eval_no_plots, "Write no plots");
}

void define_odometry(CLI::App& app, CommandLine& cl) {
    auto* cmd = cl.odometry_cmd = app.add_subcommand(
        "odometry", "LiDAR odometry (LiODOM) over a recording, KITTI sequence or folder of scans");
    cmd->add_option("INPUT", cl.odo.input,
                    "Simulator recording, KITTI sequence folder (velodyne/*.bin) or folder of "
                    ".pcd/.ply/.bin sweeps")
        ->required()
        ->type_name("");
    cmd->add_option("--out", cl.odo.out, "Trajectory file (T_world_sensor per sweep)")
        ->type_name("TRAJ");
    cl.odometry_format = cmd->add_option("--format", cl.odo_format,
                                         "kitti (3x4 per line) or tum (default: from --out's "
                                         "extension, .tum = tum)")
                             ->type_name("kitti|tum");
    cl.odometry_preset =
        cmd->add_option("--preset", cl.odo.preset, "kitti, os1_drone or confined (default kitti)")
            ->type_name("NAME");
    cl.odometry_config =
        cmd->add_option("--config", cl.odo_config, "YAML config: preset + overrides")
            ->type_name("FILE");
    cl.odometry_period = cmd->add_option("--period", cl.odo_period_s,
                                         "Seconds between sweeps for inputs without stamps "
                                         "(default 0.1)")
                             ->type_name("S")
                             ->check(finite_number(scantling::app::LowerBound::kPositive));
    cl.odometry_max_frames =
        cmd->add_option("--max-frames", cl.odo_max_frames, "Only the first N sweeps")
            ->type_name("N")
            ->transform(whole_number_in(1, std::numeric_limits<std::size_t>::max()));
    cmd->add_option("--method", cl.odo.method,
                    "liodom, or icp: the scan-to-scan point-to-plane baseline (same range gate "
                    "and voxel as the preset)")
        ->type_name("liodom|icp");
    cmd->add_option("--prior", cl.odo.prior,
                    "Motion prior of each prediction: none (constant velocity) or vio (the "
                    "recording's vio.csv); degenerate directions keep it")
        ->type_name("none|vio");
    cmd->add_flag("--print-config", cl.odo.print_config,
                  "Print the resolved config as YAML and exit");
    cmd->add_flag("--no-progress", cl.no_progress, "No progress bar on stderr");
    add_threads_option(*cmd, cl);
}

void define_localize(CLI::App& app, CommandLine& cl) {
    auto* cmd = cl.localize_cmd = app.add_subcommand(
        "localize",
        "Absolute localisation in a known map: depth frames registered, gated and fused with VIO");
    auto& c = cl.loc_cli;
    cmd->add_option("RECORDING", cl.loc.recording,
                    "Recording with depth/, vio.csv, imu.csv (optional) and world/ (the map)")
        ->required()
        ->type_name("");
    cmd->add_option("--out", cl.loc.out,
                    "Output folder: trajectory.tum, events.csv, summary.json, defects.json, "
                    "defects.csv, defects/ (all or none)")
        ->type_name("DIR");
    c.config_opt = cmd->add_option("--config", c.config,
                                   "YAML localizer config (see --print-config for every key)")
                       ->type_name("FILE");
    c.filter_opt = cmd->add_option("--filter", c.filter, "Fusion filter (default: config, ekf)")
                       ->type_name("ekf|ukf");
    c.method_opt =
        cmd->add_option("--method", c.method,
                        "Tracking: point-to-plane ICP, Stein-ICP, the frame x longitudinal "
                        "landmarks seen (art. B) or the column's 3-DoF registration "
                        "on its wall and downcomer (art. F; default: config, icp)")
            ->type_name("icp|stein|landmarks|column");
    c.vio_opt = cmd->add_option("--vio", c.vio,
                                "What the VIO gives the filter: its pose, or only its body "
                                "velocity, integrated with the IMU's roll and pitch and the VIO's "
                                "yaw steps (default: config, pose)")
                    ->type_name("pose|velocity");
    cmd->add_option("--start", cl.loc.start,
                    "known: the true first pose with 5 cm / 3 deg uncertainty; unknown: a "
                    "kidnapped start, global search over every compartment (default known)")
        ->type_name("known|unknown");
    c.rate_opt = cmd->add_option("--rate", c.rate_hz,
                                 "Registrations per second (0 = every frame; the sources: 0.1)")
                     ->type_name("HZ")
                     ->check(finite_number(scantling::app::LowerBound::kNonNegative));
    c.map_opt = cmd->add_option("--map", c.map, "Map cloud (default RECORDING/world/map.ply)")
                    ->type_name("FILE");
    c.metadata_opt = cmd->add_option("--metadata", c.metadata,
                                     "Structural map (default RECORDING/world/metadata.json)")
                         ->type_name("FILE");
    c.cache_opt = cmd->add_option("--descriptor-cache", c.cache,
                                  "Map descriptor cache (default <map>.fpfh; rebuilt when stale)")
                      ->type_name("FILE");
    cmd->add_flag("--no-descriptor-cache", cl.loc.no_descriptor_cache,
                  "Compute the map descriptors without reading or writing a cache");
    cmd->add_option("--latency", cl.loc.latency_s,
                    "Seconds after its capture a frame reaches the localiser (default 0.1); its "
                    "registration is applied at the capture time")
        ->type_name("S")
        ->check(finite_number(scantling::app::LowerBound::kNonNegative));
    c.max_frames_opt =
        cmd->add_option("--max-frames", c.max_frames, "Only the first N depth frames")
            ->type_name("N")
            ->transform(whole_number_in(1, std::numeric_limits<std::size_t>::max()));
    cmd->add_flag("--print-config", cl.loc.print_config,
                  "Print the resolved config as YAML and exit");
    cmd->add_flag("--no-progress", cl.no_progress, "No progress bar on stderr");
    add_threads_option(*cmd, cl);
}

void run_localize(CommandLine& cl) {
    auto& c = cl.loc_cli;
    if (c.config_opt->count() > 0) cl.loc.config_path = c.config;
    if (c.filter_opt->count() > 0) cl.loc.filter = c.filter;
    if (c.method_opt->count() > 0) cl.loc.method = c.method;
    if (c.vio_opt->count() > 0) cl.loc.vio = c.vio;
    if (c.rate_opt->count() > 0) cl.loc.rate_hz = c.rate_hz;
    if (c.map_opt->count() > 0) cl.loc.map_path = c.map;
    if (c.metadata_opt->count() > 0) cl.loc.metadata_path = c.metadata;
    if (c.cache_opt->count() > 0) cl.loc.descriptor_cache = c.cache;
    if (c.max_frames_opt->count() > 0) cl.loc.max_frames = c.max_frames;
    cl.loc.progress = !cl.no_progress;
    cl.loc.num_threads = cl.num_threads;
    scantling::app::run_localize(cl.loc, std::cout);
}

void define_commands(CLI::App& app, CommandLine& cl) {
    app.set_version_flag("--version", std::string("scantling ") + SCANTLING_VERSION);
    app.add_flag("-v,--verbose", cl.verbose, "Debug logging on stderr");
    add_threads_option(app, cl);
    // Checked after parsing (not require_subcommand) so that a misspelt subcommand is named.
    app.require_subcommand(0, 1);
    // Subcommands created below inherit this: `scantling info FILE -v` works too.
    app.fallthrough();

    cl.info_cmd = app.add_subcommand(
        "info", "Print size, fields, bounds (and area of a mesh) of a cloud or mesh");
    cl.info_cmd
        ->add_option("FILE", cl.info.input,
                     "Cloud (.pcd, .bin, .ply without faces) or mesh (.obj, .stl, .ply with faces)")
        ->required()
        ->type_name("");

    cl.convert_cmd = app.add_subcommand(
        "convert", "Convert a cloud between .pcd, .ply and .bin (optionally downsampled)");
    add_in_out(*cl.convert_cmd, cl);
    cl.convert_voxel = cl.convert_cmd
                           ->add_option("--voxel", cl.voxel_size_m,
                                        "Voxel-downsample first: voxel edge in metres (> 0)")
                           ->type_name("SIZE_M")
                           ->check(finite_number(scantling::app::LowerBound::kPositive));

    cl.downsample_cmd = app.add_subcommand(
        "downsample", "Voxel-grid downsample a cloud (one centroid per occupied voxel)");
    add_in_out(*cl.downsample_cmd, cl);
    cl.downsample_cmd->add_option("--voxel", cl.voxel_size_m, "Voxel edge in metres (> 0)")
        ->required()
        ->type_name("SIZE_M")
        ->check(finite_number(scantling::app::LowerBound::kPositive));
    define_sim(app, cl);
    define_mission(app, cl);
    define_register(app, cl);
    define_eval(app, cl);
    define_odometry(app, cl);
    define_localize(app, cl);
    // Set last: subcommands created after it would inherit it.
    app.footer("Run 'scantling SUBCOMMAND --help' for the options of a subcommand.");
}

void run(CommandLine& cl) {
    cl.convert.num_threads = cl.num_threads;
    if (cl.info_cmd->parsed()) return scantling::app::run_info(cl.info, std::cout);
    if (cl.sim_cmd->parsed()) {
        if (cl.sim_seed->count() > 0) cl.sim.seed = cl.seed;
        cl.sim.progress = !cl.no_progress;
        cl.sim.num_threads = cl.num_threads;
        return scantling::app::run_sim(cl.sim, std::cout);
    }
    if (cl.mission_cmd->parsed()) {
        if (cl.mission_seed->count() > 0) cl.mission.seed = cl.seed;
        cl.mission.progress = !cl.no_progress;
        cl.mission.num_threads = cl.num_threads;
        return scantling::app::run_mission(cl.mission, std::cout);
    }
    if (cl.eval_cmd->parsed()) {
        if (cl.eval_format->count() > 0) cl.eval.format = cl.eval_format_name;
        if (cl.eval_plots->count() > 0) cl.eval.plots_dir = cl.eval_plots_dir;
        cl.eval.plots = !cl.eval_no_plots;
        return scantling::app::run_eval(cl.eval, std::cout);
    }
    if (cl.register_cmd->parsed()) {
        if (cl.register_init->count() > 0) cl.reg.init_path = cl.init_path;
        if (cl.register_voxel->count() > 0) cl.reg.voxel_size_m = cl.voxel_size_m;
        if (cl.register_max_distance->count() > 0) cl.reg.max_distance_m = cl.max_distance_m;
        cl.reg.num_threads = cl.num_threads;
        return scantling::app::run_register(cl.reg, std::cout);
    }
    if (cl.odometry_cmd->parsed()) {
        if (cl.odometry_format->count() > 0) cl.odo.format = cl.odo_format;
        cl.odo.preset_given = cl.odometry_preset->count() > 0;
        if (cl.odometry_config->count() > 0) cl.odo.config_path = cl.odo_config;
        if (cl.odometry_period->count() > 0) cl.odo.period_s = cl.odo_period_s;
        if (cl.odometry_max_frames->count() > 0) cl.odo.max_frames = cl.odo_max_frames;
        cl.odo.progress = !cl.no_progress;
        cl.odo.num_threads = cl.num_threads;
        return scantling::app::run_odometry(cl.odo, std::cout);
    }
    if (cl.localize_cmd->parsed()) return run_localize(cl);
    if (cl.downsample_cmd->parsed() || cl.convert_voxel->count() > 0) {
        cl.convert.voxel_size_m = cl.voxel_size_m;
    }
    if (cl.convert_cmd->parsed()) return scantling::app::run_convert(cl.convert, std::cout);
    scantling::app::run_downsample(cl.convert, std::cout);
}

int run_main(int argc, char** argv) {
    CLI::App app("Tools for the scantling inspection-robot stack", "scantling");
    CommandLine cl;
    try {
        define_commands(app, cl);
        app.parse(argc, argv);
        if (app.get_subcommands().empty()) {
            return report_error(
                "a subcommand is required: info, convert, downsample, sim, mission, register, "
                "odometry, localize or eval" +
                kSeeHelp);
        }
    } catch (const CLI::Success& e) {
        return app.exit(e);  // --help, --version: printed on stdout, exit 0
    } catch (const CLI::Error& e) {
        return report_error(e.what() + kSeeHelp);
    }
    scantling::app::set_up_logging(cl.verbose);
    const scantling::app::EscapedOutput escaped_stdout(std::cout);
    // One task arena of --threads for the whole command: the parallel loops inside share its
    // workers instead of each building an arena of its own (core/parallel.hpp).
    scantling::ParallelConfig threads;
    threads.num_threads = cl.num_threads;
    scantling::with_threads(threads, [&cl] { run(cl); });
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    // Every sweep allocates and frees tens of megabytes of clouds. glibc's defaults return that
    // memory to the kernel after each sweep and fault it back in (zeroed) for the next: 12 % of
    // the 16 real sweeps' run time was system time (docs/benchmarks.md). Big blocks from the heap
    // and up to 128 MiB of freed heap kept: the peak resident size did not change.
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 128 << 20);
    try {
        return run_main(argc, argv);
    } catch (const std::exception& e) {
        return report_error(e.what());
    } catch (...) {
        std::fputs("scantling: error: unknown exception\n", stderr);
        return kExitError;
    }
}
