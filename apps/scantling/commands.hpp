#pragma once
/// @file
/// The `scantling` subcommands as plain functions over option structs, so that CLI11 (slow to
/// compile) stays in main.cpp. Each prints its report to `out` only once it has succeeded and
/// throws scantling::Error (naming the file or the option) on failure.

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

/// `scantling info FILE`: counts, fields, bounds (and area for meshes), one "key: value" a line.
void run_info(const InfoOptions& options, std::ostream& out);

/// `scantling convert IN OUT`: reads, optionally downsamples, writes atomically, and prints
/// one summary line. Options and the output path are checked before the input is read, so
/// nothing is written when anything is wrong.
void run_convert(const ConvertOptions& options, std::ostream& out);

/// `scantling downsample IN OUT --voxel SIZE_M`: run_convert with a mandatory voxel size.
void run_downsample(const ConvertOptions& options, std::ostream& out);

}  // namespace scantling::app
