#include <scantling/core/error.hpp>
#include <scantling/sim/spinning_lidar.hpp>

#include "detail/beam_sweep.hpp"
#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <cmath>

namespace scantling::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

bool is_ouster_mode(int columns, double rate_hz) {
    if (rate_hz != 10.0 && rate_hz != 20.0) return false;
    if (columns == 512 || columns == 1024) return true;
    return columns == 2048 && rate_hz == 10.0;
}

void check_elevations(const std::vector<double>& elevations, std::string_view prefix) {
    detail::require(!elevations.empty() && elevations.size() <= 65536, prefix,
                    "ring_elevations_rad.size", static_cast<double>(elevations.size()),
                    "in [1, 65536]");
    for (std::size_t r = 0; r < elevations.size(); ++r) {
        const std::string field = fmt::format("ring_elevations_rad[{}]", r);
        detail::require(std::abs(elevations[r]) < std::numbers::pi / 2.0, prefix, field,
                        elevations[r], "in (-pi/2, pi/2)");
        if (r > 0) {
            detail::require(elevations[r] > elevations[r - 1], prefix, field, elevations[r],
                            fmt::format("> ring {} = {} (ascending)", r - 1, elevations[r - 1]));
        }
    }
}

}  // namespace

std::vector<double> uniform_ring_elevations(int rings, double lowest_rad, double highest_rad) {
    constexpr std::string_view kWhat = "uniform_ring_elevations";
    detail::require(rings >= 2, kWhat, "rings", rings, ">= 2");
    detail::require(std::isfinite(lowest_rad), kWhat, "lowest_rad", lowest_rad, "finite");
    detail::require(std::isfinite(highest_rad) && highest_rad > lowest_rad, kWhat, "highest_rad",
                    highest_rad, fmt::format("finite and > lowest_rad = {}", lowest_rad));
    std::vector<double> elevations(static_cast<std::size_t>(rings));
    for (int r = 0; r < rings; ++r) {
        elevations[r] = lowest_rad + (highest_rad - lowest_rad) * r / (rings - 1);
    }
    return elevations;
}

ReturnModel ouster_os1_returns() {
    return ReturnModel{.sigma_m = 0.015,
                       .sigma_per_m = 0.0002,
                       .dropout_probability = 0.001,
                       .weak_reflectivity = 0.02,
                       .weak_dropout_probability = 0.5};
}

void SpinningLidarConfig::validate(std::string_view prefix) const {
    check_elevations(ring_elevations_rad, prefix);
    detail::require(columns >= 1, prefix, "columns", columns, ">= 1");
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require(std::isfinite(start_azimuth_rad), prefix, "start_azimuth_rad",
                    start_azimuth_rad, "finite");
    detail::require_range_window(prefix, min_range_m, max_range_m);
    returns.validate(detail::sub(prefix, "returns"));
    validate_mount(T_body_sensor, prefix);
}

SpinningLidarConfig ouster_os1_64(int columns, double rate_hz) {
    if (!is_ouster_mode(columns, rate_hz)) {
        throw ConfigError(fmt::format(
            "ouster_os1_64.columns = {} at rate_hz = {}, expected an OS1 lidar mode (512x10, "
            "512x20, 1024x10, 1024x20, 2048x10)",
            columns, rate_hz));
    }
    SpinningLidarConfig config;
    config.columns = columns;
    config.rate_hz = rate_hz;
    return config;
}

SpinningLidarConfig ouster_os0_64(int columns, double rate_hz) {
    if (!is_ouster_mode(columns, rate_hz)) {
        throw ConfigError(fmt::format(
            "ouster_os0_64.columns = {} at rate_hz = {}, expected an Ouster lidar mode (512x10, "
            "512x20, 1024x10, 1024x20, 2048x10)",
            columns, rate_hz));
    }
    SpinningLidarConfig config;
    config.ring_elevations_rad = uniform_ring_elevations(64, -45.0 * kDeg, 45.0 * kDeg);
    config.columns = columns;
    config.rate_hz = rate_hz;
    config.min_range_m = 0.3;
    config.max_range_m = 50.0;
    return config;
}

SpinningLidarConfig velodyne_hdl64e() {
    SpinningLidarConfig config;
    std::vector<double> lower = uniform_ring_elevations(32, -24.8 * kDeg, -8.83 * kDeg);
    const std::vector<double> upper =
        uniform_ring_elevations(32, (2.0 - 31.0 / 3.0) * kDeg, 2.0 * kDeg);
    lower.insert(lower.end(), upper.begin(), upper.end());
    config.ring_elevations_rad = std::move(lower);
    config.columns = 2083;
    config.rate_hz = 10.0;
    config.min_range_m = 0.9;
    config.max_range_m = 120.0;
    config.returns.sigma_m = 0.02;
    config.returns.sigma_per_m = 0.0;
    return config;
}

SpinningLidar::SpinningLidar(SpinningLidarConfig config) : config_(std::move(config)) {
    config_.validate();
    const int rings = config_.rings();
    directions_sensor_.reserve(static_cast<std::size_t>(rings) * config_.columns);
    column_times_s_.resize(static_cast<std::size_t>(config_.columns));
    for (int c = 0; c < config_.columns; ++c) {
        const double azimuth_rad =
            config_.start_azimuth_rad - 2.0 * std::numbers::pi * c / config_.columns;
        column_times_s_[c] = c / (config_.columns * config_.rate_hz);
        for (int r = 0; r < rings; ++r) {
            const double elevation_rad = config_.ring_elevations_rad[r];
            directions_sensor_.emplace_back(std::cos(elevation_rad) * std::cos(azimuth_rad),
                                            std::cos(elevation_rad) * std::sin(azimuth_rad),
                                            std::sin(elevation_rad));
            rings_.push_back(static_cast<std::uint16_t>(r));
        }
    }
}

const std::vector<double>& SpinningLidar::column_times_s() const { return column_times_s_; }

PointCloud SpinningLidar::scan(const SceneView& scene, const Eigen::Isometry3d& T_world_body,
                               Rng& rng, double stamp_s, const ParallelConfig& parallel) const {
    const Eigen::Isometry3d T_world_sensor = T_world_body * config_.T_body_sensor;
    return detail::cast_schedule(
        scene,
        {directions_sensor_, column_times_s_, rings_.size() / column_times_s_.size(), rings_},
        {&T_world_sensor, 1}, {config_.min_range_m, config_.max_range_m, config_.returns}, rng,
        stamp_s, parallel);
}

PointCloud SpinningLidar::scan_moving(const SceneView& scene, const PoseAtTime& T_world_body_at,
                                      double sweep_start_s, Rng& rng,
                                      const ParallelConfig& parallel) const {
    const std::vector<Eigen::Isometry3d> poses = detail::firing_poses(
        T_world_body_at, sweep_start_s, column_times_s_, config_.T_body_sensor);
    return detail::cast_schedule(
        scene,
        {directions_sensor_, column_times_s_, rings_.size() / column_times_s_.size(), rings_},
        poses, {config_.min_range_m, config_.max_range_m, config_.returns}, rng, sweep_start_s,
        parallel);
}

}  // namespace scantling::sim
