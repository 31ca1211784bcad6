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
    bool force = false;                 ///< write into a non-empty directory (replaces a recording)
    bool progress = true;               ///< progress line on stderr
    int num_threads = 0;                ///< 0 = the scenario's setting
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
    std::string out;      ///< where the 4×4 T_target_source is written (alone, atomically)
    int num_threads = 0;  ///< 0 = all hardware threads
};

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
/// checked before the clouds are read; nothing is written on failure.
void run_register(const RegisterOptions& options, std::ostream& out);

}  // namespace scantling::app
