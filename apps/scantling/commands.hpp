#pragma once
/// @file
/// The `scantling` subcommands as plain functions over option structs, so that CLI11 (slow to
/// compile) stays in main.cpp. Each prints its report to `out` only once it has succeeded and
/// throws scantling::Error (naming the file or the option) on failure.

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace scantling::app {

struct InfoOptions {
    std::string input;  ///< cloud (.pcd, .bin, .ply without faces) or mesh (.obj, .stl, .ply)
};

struct ConvertOptions {
    std::string input;                   ///< .pcd, .ply or .bin
    std::string output;                  ///< .pcd, .ply or .bin (format from the extension)
    std::optional<double> voxel_size_m;  ///< voxel-downsample first when set (> 0)
    bool ascii = false;                  ///< ascii PCD output (.pcd only)
    int num_threads = 0;                 ///< 0 = all hardware threads
};

struct SimOptions {
    std::string scenario;               ///< scenario YAML
    std::string out;                    ///< recording directory
    std::optional<std::uint64_t> seed;  ///< overrides the scenario's seed
    bool force = false;                 ///< replace a recording folder once the new one is complete
    bool progress = true;               ///< progress line on stderr
    int num_threads = 0;                ///< 0 = the scenario's setting
};

struct MissionOptions {
    std::string scenario;               ///< mission scenario YAML (mission/mission_scenario.hpp)
    std::string out;                    ///< recording directory
    std::optional<std::uint64_t> seed;  ///< overrides simulation.seed
    bool force = false;                 ///< replace a recording folder once the new one is complete
    bool progress = true;               ///< progress line on stderr
    int num_threads = 0;                ///< ray casting threads; 0 = the scenario's setting
    std::vector<std::string> overrides;  ///< --set KEY=VALUE, applied before parsing
};

struct RegisterOptions {
    std::string source;                    ///< cloud to move (.pcd, .ply, .bin)
    std::string target;                    ///< cloud it is aligned to
    std::string method;                    ///< icp, p2plane, gicp, fpfh-teaser, fpfh-ransac, stein
    std::optional<std::string> init_path;  ///< initial T_target_source, 4 lines of 4 numbers
    /// Voxel edge, metres, >= 0 (0 = no downsampling, local methods only). Unset: 0.1 m for the
    /// local methods, 0.05 m for the global ones.
    std::optional<double> voxel_size_m;
    /// Correspondence distance, metres, > 0. Unset: the method's default (ICP 1 m, Stein 0.5 m,
    /// the refinement after a global method 2 voxels).
    std::optional<double> max_distance_m;
    /// ICP (local methods and the refinement): keep, prefer_front or reject the target points
    /// facing away from the sensor (IcpConfig::back_faces; the target file's normals).
    std::string back_faces = "prefer_front";
    std::string out;      ///< where the 4×4 T_target_source is written (alone, atomically)
    int num_threads = 0;  ///< 0 = all hardware threads
};

/// `scantling mission SCENARIO --out DIR`: one closed-loop run (mission/closed_loop.hpp); prints
/// the path deviation, the estimate's error against the truth and the run's figures.
void run_mission(const MissionOptions& options, std::ostream& out);

/// `scantling info FILE`: counts, fields, bounds (and area for meshes), one "key: value" a line.
void run_info(const InfoOptions& options, std::ostream& out);

/// `scantling convert IN OUT`: reads, optionally downsamples, writes atomically, and prints
/// one summary line. Options and the output path are checked before the input is read, so
/// nothing is written when anything is wrong.
void run_convert(const ConvertOptions& options, std::ostream& out);

/// `scantling downsample IN OUT --voxel SIZE_M`: run_convert with a mandatory voxel size.
void run_downsample(const ConvertOptions& options, std::ostream& out);

/// `scantling sim SCENARIO --out DIR`: runs the scenario, draws a progress line on stderr and
/// prints the recording path and a summary. The scenario is loaded and its world built before
/// the directory is created, so a bad scenario leaves nothing behind.
void run_sim(const SimOptions& options, std::ostream& out);

/// Reads a rigid transform written as 4 lines of 4 numbers (blank lines and lines starting with
/// '#' skipped; the last row must be 0 0 0 1; a rotation within 1e-3 of orthonormal is projected
/// onto SO(3), since printed digits are rounded). Throws FileError when the file cannot be
/// opened, ParseError naming the line otherwise.
Eigen::Isometry3d read_transform_file(const std::string& path);

/// `scantling register SRC TGT --method M --out T.txt`: registers SRC to TGT, writes the 4×4
/// T_target_source (full precision) to `out` and prints it with fitness, RMSE, status, time and
/// the 6×6 covariance where the method gives one. Options, --init and the output directory are
/// checked before the clouds are read; nothing is written on failure. A registration that did
/// not converge (the method's converged flag; Stein-ICP: fewer source points within reach of
/// the target at its mode than ICP's min_correspondences) throws NotConvergedError naming the
/// method, the reason, fitness and RMSE, and what to try, and writes nothing.
void run_register(const RegisterOptions& options, std::ostream& out);

struct OdometryOptions {
    std::string input;  ///< simulator recording, KITTI sequence folder or folder of clouds
    std::string out;    ///< trajectory file (kitti or tum)
    std::optional<std::string> format;  ///< kitti or tum (unset: from --out's extension)
    std::string method = "liodom";      ///< liodom, or icp (the scan-to-scan baseline)
    std::string preset = "kitti";       ///< liodom_preset() name
    bool preset_given = false;          ///< --preset was on the command line
    /// Motion prior of the predictions: "none" (constant velocity) or "vio" (the recording's
    /// vio.csv; recordings only).
    std::string prior = "none";
    std::optional<std::string> config_path;  ///< YAML config (preset + overrides)
    std::optional<double> period_s;          ///< sweep period when the input has no stamps
    std::optional<std::size_t> max_frames;   ///< only the first N sweeps
    bool print_config = false;               ///< print the resolved config as YAML and exit
    bool progress = true;                    ///< progress bar on stderr
    int num_threads = 0;                     ///< 0 = the config's setting
};

/// `scantling odometry INPUT --out TRAJ`: runs LiODOM, writes the trajectory (atomically), the
/// per-frame report `<stem>_frames.csv` and, when the input has ground truth, `<stem>_gt.*` in
/// the same format; prints a summary (and the drift against the ground truth when there is one).
void run_odometry(const OdometryOptions& options, std::ostream& out);

/// Prints the drift of `estimate` against `ground_truth` (same length, same frame): the KITTI
/// metric when the path is long enough, ATE as a percentage of the path length.
void print_drift(const std::vector<Eigen::Isometry3d>& ground_truth,
                 const std::vector<Eigen::Isometry3d>& estimate, std::ostream& out);

struct LocalizeOptions {
    std::string recording;  ///< simulator recording (depth/, vio.csv, imu.csv, world/)
    std::string out;        ///< output folder
    std::optional<std::string> config_path;  ///< YAML LocalizerConfig
    std::optional<std::string> filter;       ///< ekf | ukf (overrides the config)
    std::optional<std::string> method;  ///< icp | stein | landmarks | column (overrides the config)
    std::optional<std::string> vio;     ///< pose | velocity (overrides the config)
    std::string start = "known";        ///< known (true first pose) | unknown (kidnapped)
    std::optional<double> rate_hz;      ///< registration rate (0 = every frame)
    std::optional<std::string> map_path;          ///< default: RECORDING/world/map.ply
    std::optional<std::string> metadata_path;     ///< default: RECORDING/world/metadata.json
    std::optional<std::string> descriptor_cache;  ///< default: <map>.fpfh
    bool no_descriptor_cache = false;
    double latency_s = 0.1;  ///< frames reach the localiser this long after their capture
    std::optional<std::size_t> max_frames;
    bool print_config = false;
    bool progress = true;
    int num_threads = 0;
};

/// `scantling localize RECORDING --out DIR`: absolute localisation (localization/localizer.hpp)
/// over a recording; writes DIR/trajectory.tum (fused, at the VIO rate), DIR/events.csv (one
/// row per depth frame and per warning), DIR/summary.json (errors against the ground truth,
/// counts, timings), the defects the camera saw (defects.json, defects.csv, defects/; see
/// localize_defects.hpp), all or none; prints the summary.
void run_localize(const LocalizeOptions& options, std::ostream& out);

struct EvalOptions {
    std::string ground_truth;             ///< --gt: KITTI pose file or TUM trajectory
    std::string estimate;                 ///< --est: same format as the ground truth
    std::optional<std::string> format;    ///< kitti or tum (unset: from the numbers on a line)
    double max_time_difference_s = 0.02;  ///< TUM association: largest stamp difference, >= 0
    bool json = false;                    ///< one JSON object instead of "key: value" lines
    /// Folder for <est-stem>_top.svg and <est-stem>_errors.svg (created; unset: beside EST).
    std::optional<std::string> plots_dir;
    bool plots = true;  ///< false: write no plots (--no-plots)
};

/// `scantling eval --gt GT --est EST`: the KITTI metric (RTE, RRE), ATE after SE(3) alignment
/// and RPE over 10 m, plus a top view and an error-along-path plot (SVG). Everything is
/// computed and rendered before the first plot is written, so nothing is written on failure.
void run_eval(const EvalOptions& options, std::ostream& out);

}  // namespace scantling::app
