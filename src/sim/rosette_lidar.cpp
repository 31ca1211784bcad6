#include <scantling/sim/rosette_lidar.hpp>

#include "detail/beam_sweep.hpp"
#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <cmath>
#include <complex>

namespace scantling::sim {
namespace {

// Phase in radians of a rotation at `rate_hz` at absolute time t, reduced to one turn first
// so that large absolute times keep full precision.
double phase_rad(double rate_hz, double time_s) {
    const double turns = rate_hz * time_s;
    return 2.0 * std::numbers::pi * (turns - std::floor(turns));
}

}  // namespace

struct RosetteLidar::Frame {
    std::vector<Eigen::Vector3d> directions_sensor;
    std::vector<double> times_s;
};

int RosetteLidarConfig::points_per_frame() const {
    return static_cast<int>(std::lround(point_rate_hz / frame_rate_hz));
}

void RosetteLidarConfig::validate(std::string_view prefix) const {
    detail::require_angle(prefix, "fov_rad", fov_rad, std::numbers::pi);
    detail::require_positive(prefix, "point_rate_hz", point_rate_hz);
    detail::require_positive(prefix, "frame_rate_hz", frame_rate_hz);
    detail::require(frame_rate_hz <= point_rate_hz && point_rate_hz / frame_rate_hz < 1e8, prefix,
                    "frame_rate_hz", frame_rate_hz,
                    fmt::format("<= point_rate_hz = {} and > point_rate_hz / 1e8", point_rate_hz));
    detail::require_positive(prefix, "prism_a_hz", prism_a_hz);
    detail::require_positive(prefix, "prism_b_hz", prism_b_hz);
    detail::require_range_window(prefix, min_range_m, max_range_m);
    returns.validate(detail::sub(prefix, "returns"));
    validate_mount(T_body_sensor, prefix);
}

RosetteLidarConfig livox_mid70() { return RosetteLidarConfig{}; }

RosetteLidar::RosetteLidar(RosetteLidarConfig config) : config_(std::move(config)) {
    config_.validate();
}

Eigen::Vector3d RosetteLidar::beam_direction(double time_s) const {
    const std::complex<double> z =
        (config_.fov_rad / 4.0) * (std::polar(1.0, phase_rad(config_.prism_a_hz, time_s)) +
                                   std::polar(1.0, -phase_rad(config_.prism_b_hz, time_s)));
    const double polar_rad = std::abs(z);
    const double azimuth_rad = std::arg(z);
    return {std::cos(polar_rad), std::sin(polar_rad) * std::cos(azimuth_rad),
            std::sin(polar_rad) * std::sin(azimuth_rad)};
}

RosetteLidar::Frame RosetteLidar::frame_at(double stamp_s) const {
    const int n = config_.points_per_frame();
    Frame frame;
    frame.directions_sensor.resize(static_cast<std::size_t>(n));
    frame.times_s.resize(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
        frame.times_s[k] = k / config_.point_rate_hz;
        frame.directions_sensor[k] = beam_direction(stamp_s + frame.times_s[k]);
    }
    return frame;
}

PointCloud RosetteLidar::cast_frame(const SceneView& scene, const Frame& frame,
                                    std::span<const Eigen::Isometry3d> poses, Rng& rng,
                                    double stamp_s, const ParallelConfig& parallel) const {
    return detail::cast_schedule(scene, {frame.directions_sensor, frame.times_s, 1, {}}, poses,
                                 {config_.min_range_m, config_.max_range_m, config_.returns}, rng,
                                 stamp_s, parallel);
}

PointCloud RosetteLidar::scan(const SceneView& scene, const Eigen::Isometry3d& T_world_body,
                              Rng& rng, double stamp_s, const ParallelConfig& parallel) const {
    const Eigen::Isometry3d T_world_sensor = T_world_body * config_.T_body_sensor;
    return cast_frame(scene, frame_at(stamp_s), {&T_world_sensor, 1}, rng, stamp_s, parallel);
}

PointCloud RosetteLidar::scan_moving(const SceneView& scene, const PoseAtTime& T_world_body_at,
                                     double stamp_s, Rng& rng,
                                     const ParallelConfig& parallel) const {
    const Frame frame = frame_at(stamp_s);
    const std::vector<Eigen::Isometry3d> poses =
        detail::firing_poses(T_world_body_at, stamp_s, frame.times_s, config_.T_body_sensor);
    return cast_frame(scene, frame, poses, rng, stamp_s, parallel);
}

}  // namespace scantling::sim
