// Size of the recording a scenario will write (scenario_estimate.hpp).
#include <scantling/sim/scenario_estimate.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include <scantling/core/checked_arithmetic.hpp>
#include <scantling/core/error.hpp>
#include <scantling/sim/scenario_limits.hpp>

#include <scantling/sim/sensor_configs.hpp>

namespace scantling::sim {
namespace {

// Bytes of what each firing writes, measured on recordings of the shipped scenarios and
// rounded up: numbers are written as the shortest text that reads back exactly.
constexpr std::uint64_t kKittiPointBytes = 16;       ///< x, y, z, intensity as float32
constexpr std::uint64_t kLidarPlyPointBytes = 22;    ///< + ring (uint16) and time (float32)
constexpr std::uint64_t kCloudPlyPointBytes = 16;    ///< x, y, z, intensity as float32
constexpr std::uint64_t kRgbBytesPerPixel = 3;       ///< PNG, before compression
constexpr std::uint64_t kSonarBytesPerCell = 4 + 1;  ///< float32 .bin and a grey PNG pixel
constexpr std::uint64_t kFileOverheadBytes = 1024;   ///< headers (PLY, PNG) of one frame file
constexpr std::uint64_t kFrameRowBytes = 512;        ///< its stamps.txt and poses.txt rows
constexpr std::uint64_t kCsvRowBytes = 384;  ///< a row of imu.csv (~130), vio.csv (~340), ...
constexpr std::uint64_t kGroundTruthRowBytes = 192;  ///< a TUM row per tick (~150)
constexpr std::uint64_t kMapPointBytes = 24;         ///< x, y, z, normal as float32

/// a × b, or the largest value when it does not fit: an estimate saturates, it never wraps.
std::uint64_t checked_or_max(std::uint64_t a, std::uint64_t b) {
    return checked_multiply(a, b).value_or(std::numeric_limits<std::uint64_t>::max());
}

/// a + b, or the largest value when it does not fit.
std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
    return checked_add(a, b).value_or(std::numeric_limits<std::uint64_t>::max());
}

/// What one firing of a sensor writes.
struct Firing {
    double rate_hz = 0.0;
    std::uint64_t bytes = 0;
    std::string frame_size;
};

std::uint64_t pixels(int width, int height) {
    return static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
}

/// A frame file of `cells` elements of `cell_bytes`, with its header and index rows.
std::uint64_t frame_bytes(std::uint64_t cells, std::uint64_t cell_bytes) {
    return saturating_add(checked_or_max(cells, cell_bytes), kFileOverheadBytes + kFrameRowBytes);
}

/// One frame in memory is bounded (scenario_limits.hpp): ConfigError naming what sizes it.
void check_frame(const std::string& key, const std::string& frame_size, std::uint64_t count,
                 std::int64_t max, std::string_view unit) {
    if (count <= static_cast<std::uint64_t>(max)) return;
    throw ConfigError(
        fmt::format("{}: {} = {} {} per frame, expected <= {}", key, frame_size, count, unit, max));
}

Firing lidar_firing(const SensorSpec& spec, const std::string& key) {
    const SpinningLidarConfig c = detail::lidar_config(spec, key);
    const bool ply = spec.write_ply || spec.motion_distortion;
    const std::uint64_t points = pixels(c.rings(), c.columns);
    const std::string size = fmt::format("{} rings x columns {}", c.rings(), c.columns);
    check_frame(key, size, points, limits::kMaxPointsPerFrame, "points");
    return {c.rate_hz, frame_bytes(points, kKittiPointBytes + (ply ? kLidarPlyPointBytes : 0)),
            size + (ply ? ", write_ply" : "")};
}

Firing image_firing(const SensorSpec& spec, const std::string& key) {
    if (spec.type == SensorType::kDepthCamera) {
        const DepthCameraConfig c = detail::depth_config(spec, key);
        const PinholeIntrinsics& k = c.intrinsics;
        const std::string size = fmt::format("width {} x height {}", k.width, k.height);
        check_frame(key, size, pixels(k.width, k.height), limits::kMaxPointsPerFrame, "points");
        return {c.rate_hz, frame_bytes(pixels(k.width, k.height), kCloudPlyPointBytes), size};
    }
    const PinholeCameraConfig c = detail::camera_config(spec, key);
    const PinholeIntrinsics& k = c.intrinsics;
    const std::string size = fmt::format("width {} x height {}", k.width, k.height);
    check_frame(key, size, pixels(k.width, k.height), limits::kMaxImagePixels, "pixels");
    // A PNG row also holds one filter byte.
    return {c.rate_hz,
            saturating_add(frame_bytes(pixels(k.width, k.height), kRgbBytesPerPixel),
                           static_cast<std::uint64_t>(k.height)),
            size + " x 3 channels"};
}

Firing imaging_firing(const SensorSpec& spec, const std::string& key) {
    if (spec.type == SensorType::kMultibeamSonar) {
        const MultibeamSonarConfig c = detail::sonar_config(spec, key);
        return {c.rate_hz, frame_bytes(pixels(c.num_beams, c.num_bins), kSonarBytesPerCell),
                fmt::format("num_beams {} x num_bins {}", c.num_beams, c.num_bins)};
    }
    if (spec.type == SensorType::kRosetteLidar) {
        const RosetteLidarConfig c = detail::rosette_config(spec, key);
        const auto points = static_cast<std::uint64_t>(c.points_per_frame());
        const std::string size =
            fmt::format("point_rate_hz {} / rate_hz {}", c.point_rate_hz, c.frame_rate_hz);
        check_frame(key, size, points, limits::kMaxPointsPerFrame, "points");
        return {c.frame_rate_hz, frame_bytes(points, kKittiPointBytes), size};
    }
    const StereoPointsConfig c = detail::stereo_config(spec, key);
    const PinholeIntrinsics& k = c.intrinsics;
    check_frame(key, fmt::format("width {} x height {}", k.width, k.height),
                pixels(k.width, k.height), limits::kMaxImagePixels, "pixels");
    // At most one feature per cell of feature_spacing_px.
    const auto cells = [&](int side) {
        return static_cast<std::uint64_t>(std::ceil(side / c.feature_spacing_px));
    };
    return {c.rate_hz, frame_bytes(cells(k.width) * cells(k.height), kCloudPlyPointBytes),
            fmt::format("width {} x height {} / feature cells", k.width, k.height)};
}

Firing row_firing(const SensorSpec& spec, const std::string& key) {
    switch (spec.type) {
        case SensorType::kImu:
            return {detail::imu_config(spec, key).rate_hz, kCsvRowBytes, "one row"};
        case SensorType::kVio:
            return {detail::vio_config(spec, key).rate_hz, kCsvRowBytes, "one row"};
        case SensorType::kRangeFinder:
            return {detail::range_config(spec, key).rate_hz, kCsvRowBytes, "one row"};
        case SensorType::kUwb:
            return {detail::uwb_config(spec, key).rate_hz, spec.anchors.size() * kCsvRowBytes,
                    fmt::format("one row per anchor ({})", spec.anchors.size())};
        case SensorType::kPressure:
            return {detail::pressure_config(spec, key).rate_hz, kCsvRowBytes, "one row"};
        case SensorType::kDvl:
            return {detail::dvl_config(spec, key).rate_hz, kCsvRowBytes, "one row"};
        case SensorType::kBarometer:
            return {detail::barometer_config(spec, key).rate_hz, kCsvRowBytes, "one row"};
        default:
            return {detail::wheel_config(spec, key).rate_hz, kCsvRowBytes, "one row"};
    }
}

Firing firing_of(const SensorSpec& spec, const std::string& key) {
    switch (spec.type) {
        case SensorType::kSpinningLidar:
            return lidar_firing(spec, key);
        case SensorType::kDepthCamera:
        case SensorType::kCamera:
            return image_firing(spec, key);
        case SensorType::kMultibeamSonar:
        case SensorType::kRosetteLidar:
        case SensorType::kStereoPoints:
            return imaging_firing(spec, key);
        default:
            return row_firing(spec, key);
    }
}

/// Firings at n / rate in [0, duration) (the runner drops a firing at the very end).
std::uint64_t firings(double duration_s, double rate_hz) {
    const double n = std::ceil(duration_s * rate_hz - 1e-9);
    if (!(n > 0.0)) return 0;
    return n < 1.8e19 ? static_cast<std::uint64_t>(n) : std::numeric_limits<std::uint64_t>::max();
}

SensorOutputEstimate sensor_estimate(const SensorSpec& spec, std::size_t index, double duration_s) {
    SensorOutputEstimate e;
    e.key = "sensors[" + std::to_string(index) + "]";
    e.type = std::string(to_string(spec.type));
    Firing f = firing_of(spec, e.key);
    e.rate_hz = f.rate_hz;
    e.firings = firings(duration_s, f.rate_hz);
    e.bytes_per_firing = f.bytes;
    e.bytes = checked_or_max(e.firings, e.bytes_per_firing);
    e.frame_size = std::move(f.frame_size);
    return e;
}

std::int64_t tick_count(double duration_s, double dt_s) {
    // As the runner: ticks cover [0, duration] (the tolerance absorbs 10 / 0.005 = 1999.99...).
    const double ticks = std::floor(duration_s / dt_s + 1e-6) + 1.0;
    return ticks < 9e18 ? static_cast<std::int64_t>(ticks)
                        : std::numeric_limits<std::int64_t>::max();
}

std::uint64_t map_bytes(const Scenario& scenario, std::optional<double> world_area_m2) {
    if (!scenario.export_world.world || !world_area_m2) return 0;
    const double spacing = scenario.export_world.map_spacing_m;
    const double points = std::round(*world_area_m2 / (spacing * spacing));
    const double bytes = points * static_cast<double>(kMapPointBytes);
    return bytes < 1.8e19 ? static_cast<std::uint64_t>(bytes)
                          : std::numeric_limits<std::uint64_t>::max();
}

std::string share_text(const SensorOutputEstimate& s) {
    return fmt::format("{} ({}, rate_hz {}, {}) {} x {} = {}", s.key, s.type, s.rate_hz,
                       s.frame_size, s.firings, format_bytes(s.bytes_per_firing),
                       format_bytes(s.bytes));
}

}  // namespace

std::string format_bytes(std::uint64_t bytes) {
    constexpr double kKiB = 1024.0;
    const auto value = static_cast<double>(bytes);
    if (value >= kKiB * kKiB * kKiB) return fmt::format("{:.1f} GiB", value / (kKiB * kKiB * kKiB));
    if (value >= kKiB * kKiB) return fmt::format("{:.1f} MiB", value / (kKiB * kKiB));
    if (value >= kKiB) return fmt::format("{:.1f} KiB", value / kKiB);
    return fmt::format("{} bytes", bytes);
}

double scenario_duration(const Scenario& scenario) {
    if (scenario.duration_s > 0.0) return scenario.duration_s;
    return make_trajectory(scenario.vehicle.trajectory)->duration_s();
}

RecordingEstimate estimate_recording(const Scenario& scenario,
                                     std::optional<double> world_area_m2) {
    RecordingEstimate e;
    e.duration_s = scenario_duration(scenario);
    e.ticks = tick_count(e.duration_s, scenario.dt_s);
    e.ground_truth_bytes =
        checked_or_max(static_cast<std::uint64_t>(e.ticks), kGroundTruthRowBytes);
    e.map_bytes = map_bytes(scenario, world_area_m2);
    e.total_bytes = saturating_add(e.ground_truth_bytes, e.map_bytes);
    for (std::size_t i = 0; i < scenario.sensors.size(); ++i) {
        e.sensors.push_back(sensor_estimate(scenario.sensors[i], i, e.duration_s));
        e.total_bytes = saturating_add(e.total_bytes, e.sensors.back().bytes);
    }
    return e;
}

std::uint64_t estimate_recording_bytes(const Scenario& scenario) {
    return estimate_recording(scenario).total_bytes;
}

std::string RecordingEstimate::describe() const {
    std::vector<const SensorOutputEstimate*> shares;
    for (const SensorOutputEstimate& s : sensors) shares.push_back(&s);
    std::stable_sort(shares.begin(), shares.end(),
                     [](const auto* a, const auto* b) { return a->bytes > b->bytes; });
    std::string text = fmt::format("recording estimate {} over {} s ({} clock ticks)",
                                   format_bytes(total_bytes), duration_s, ticks);
    for (const SensorOutputEstimate* s : shares) text += "; " + share_text(*s);
    text += "; ground truth " + format_bytes(ground_truth_bytes);
    if (map_bytes > 0) text += "; CAD map " + format_bytes(map_bytes);
    return text;
}

void check_recording_estimate(const RecordingEstimate& estimate) {
    if (estimate.total_bytes <= kMaxRecordingBytes) return;
    throw ConfigError(fmt::format(
        "{}: more than the {} a run may write; lower duration_s, the sensors' rate_hz or their "
        "frame size",
        estimate.describe(), format_bytes(kMaxRecordingBytes)));
}

}  // namespace scantling::sim
