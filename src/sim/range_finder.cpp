#include <scantling/sim/range_finder.hpp>

#include "detail/sensor_checks.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Rotation taking the sensor's +x beam onto `axis_body` (a body axis ±z here).
Eigen::Isometry3d beam_along(const Eigen::Vector3d& axis_body) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), axis_body).toRotationMatrix();
    return T;
}

std::vector<Eigen::Vector3d> cone_rays(const RangeFinderConfig& config) {
    std::vector<Eigen::Vector3d> rays{Eigen::Vector3d::UnitX()};
    for (int k = 1; k <= config.cone_rings; ++k) {
        const double polar_rad = config.beam_half_angle_rad * k / config.cone_rings;
        for (int j = 0; j < config.rays_per_ring; ++j) {
            const double azimuth_rad =
                2.0 * std::numbers::pi * (j + 0.5 * (k % 2)) / config.rays_per_ring;
            rays.emplace_back(std::cos(polar_rad), std::sin(polar_rad) * std::cos(azimuth_rad),
                              std::sin(polar_rad) * std::sin(azimuth_rad));
        }
    }
    return rays;
}

}  // namespace

void RangeFinderConfig::validate(std::string_view prefix) const {
    detail::require_range_window(prefix, min_range_m, max_range_m);
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require_non_negative(prefix, "range_sigma_m", range_sigma_m);
    detail::require_non_negative(prefix, "range_sigma_fraction", range_sigma_fraction);
    detail::require(beam_half_angle_rad >= 0.0 && beam_half_angle_rad < std::numbers::pi / 2.0,
                    prefix, "beam_half_angle_rad", beam_half_angle_rad, "in [0, pi/2)");
    detail::require(cone_rings >= 0 && cone_rings <= 64, prefix, "cone_rings", cone_rings,
                    "in [0, 64]");
    detail::require(rays_per_ring >= 1 && rays_per_ring <= 1024, prefix, "rays_per_ring",
                    rays_per_ring, "in [1, 1024]");
    validate_mount(T_body_sensor, prefix);
}

RangeFinderConfig down_looking_lidar_lite_v3() {
    RangeFinderConfig config;
    config.T_body_sensor = beam_along(-Eigen::Vector3d::UnitZ());
    return config;
}

RangeFinderConfig up_looking_teraranger_evo_60m() {
    RangeFinderConfig config;
    config.min_range_m = 0.5;
    config.max_range_m = 60.0;
    config.rate_hz = 100.0;
    config.range_sigma_m = 0.04;
    config.range_sigma_fraction = 0.015;
    config.beam_half_angle_rad = 1.0 * kDeg;
    config.cone_rings = 1;
    config.rays_per_ring = 6;
    config.T_body_sensor = beam_along(Eigen::Vector3d::UnitZ());
    return config;
}

RangeFinderConfig ultrasonic_hc_sr04() {
    RangeFinderConfig config;
    config.min_range_m = 0.02;
    config.max_range_m = 4.0;
    config.rate_hz = 20.0;
    config.range_sigma_m = 0.003;
    config.beam_half_angle_rad = 7.5 * kDeg;
    config.cone_rings = 2;
    config.rays_per_ring = 8;
    return config;
}

RangeFinder::RangeFinder(RangeFinderConfig config) : config_(std::move(config)) {
    config_.validate();
    rays_sensor_ = cone_rays(config_);
}

RangeMeasurement RangeFinder::measure(const SceneView& scene, const Eigen::Isometry3d& T_world_body,
                                      Rng& rng, double stamp_s) const {
    const Eigen::Isometry3d T_world_sensor = T_world_body * config_.T_body_sensor;
    double nearest_m = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& d : rays_sensor_) {
        const RayHit hit =
            scene.cast(T_world_sensor.translation(), (T_world_sensor.linear() * d).normalized(),
                       config_.max_range_m);
        if (hit.hit) nearest_m = std::min(nearest_m, hit.range_m);
    }
    const double noise = rng.normal();
    RangeMeasurement measurement;
    measurement.stamp_s = stamp_s;
    if (nearest_m < config_.min_range_m || !std::isfinite(nearest_m)) return measurement;
    const double sigma_m =
        std::max(config_.range_sigma_m, config_.range_sigma_fraction * nearest_m);
    measurement.valid = true;
    measurement.range_m = nearest_m + sigma_m * noise;
    return measurement;
}

}  // namespace scantling::sim
