#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/file_path.hpp>

#include "scantling/commands.hpp"

namespace scantling::app {
namespace {

using Clock = std::chrono::steady_clock;

double elapsed_ms(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void check_output(const ConvertOptions& options) {
    const io::CloudFormat format = io::cloud_format_from_path(options.output);
    if (options.ascii && format != io::CloudFormat::kPcd) {
        throw ConfigError("--ascii applies to .pcd output only, got '" + options.output + "'");
    }
    io::check_output_file(options.output);
    io::ensure_output_distinct(options.output, {options.input});
}

void check_numbers(const ConvertOptions& options) {
    if (options.voxel_size_m &&
        !(std::isfinite(*options.voxel_size_m) && *options.voxel_size_m > 0.0)) {
        throw ConfigError(
            fmt::format("--voxel = {}, expected a voxel edge > 0 m", *options.voxel_size_m));
    }
    if (options.num_threads < 0) {
        throw ConfigError(fmt::format("--threads = {}, expected >= 0 (0 = all hardware threads)",
                                      options.num_threads));
    }
}

/// Voxel centroid of the finite points; returns the cloud and how many points were dropped.
std::pair<PointCloud, std::size_t> downsample(const PointCloud& cloud,
                                              const ConvertOptions& options) {
    const PointCloud finite = remove_non_finite(cloud);
    VoxelGridConfig config;
    config.voxel_size_m = *options.voxel_size_m;
    config.parallel.num_threads = options.num_threads;
    const auto start = Clock::now();
    PointCloud result = voxel_downsample(finite, config);
    spdlog::debug("voxel grid {} m: {} -> {} points in {:.1f} ms", config.voxel_size_m,
                  finite.size(), result.size(), elapsed_ms(start));
    return {std::move(result), cloud.size() - finite.size()};
}

}  // namespace

void run_convert(const ConvertOptions& options, std::ostream& out) {
    // Everything that can be checked without reading the input, so that a bad option never
    // costs a read and never leaves a file behind.
    (void)io::cloud_format_from_path(options.input);
    check_output(options);
    check_numbers(options);
    auto start = Clock::now();
    const PointCloud input = io::read_cloud(options.input);
    spdlog::debug("read {} points from {} in {:.1f} ms", input.size(), options.input,
                  elapsed_ms(start));
    PointCloud downsampled;
    std::size_t dropped = 0;
    if (options.voxel_size_m) std::tie(downsampled, dropped) = downsample(input, options);
    const PointCloud& output = options.voxel_size_m ? downsampled : input;
    start = Clock::now();
    io::write_cloud(options.output, output, io::CloudWriteOptions{.binary = !options.ascii});
    spdlog::debug("wrote {} in {:.1f} ms", options.output, elapsed_ms(start));
    const std::string note = dropped > 0 ? fmt::format(" ({} non-finite dropped)", dropped) : "";
    out << fmt::format("{}: {} points -> {}: {} points{}\n", options.input, input.size(),
                       options.output, output.size(), note);
}

}  // namespace scantling::app
