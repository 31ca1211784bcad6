#include <scantling/sim/dvl.hpp>

#include "detail/motion_checks.hpp"
#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

// Weight floor of a beam: 1 µm/s, far below any real DVL noise.
constexpr double kMinSigmaMps = 1e-6;

}  // namespace

Eigen::Isometry3d DvlConfig::looking_down() {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
    return T;
}

void DvlConfig::validate(std::string_view prefix) const {
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require_angle(prefix, "beam_angle_rad", beam_angle_rad, std::numbers::pi / 3.0);
    detail::require_positive(prefix, "min_altitude_m", min_altitude_m);
    detail::require(std::isfinite(max_altitude_m) && max_altitude_m > min_altitude_m, prefix,
                    "max_altitude_m", max_altitude_m,
                    fmt::format("finite and > min_altitude_m = {}", min_altitude_m));
    detail::require_non_negative(prefix, "beam_velocity_sigma_mps", beam_velocity_sigma_mps);
    detail::require_non_negative(prefix, "beam_velocity_sigma_fraction",
                                 beam_velocity_sigma_fraction);
    detail::require_non_negative(prefix, "range_sigma_m", range_sigma_m);
    validate_mount(T_body_sensor, prefix);
}

DvlConfig noiseless(DvlConfig config) {
    config.beam_velocity_sigma_mps = config.beam_velocity_sigma_fraction = 0.0;
    config.range_sigma_m = 0.0;
    return config;
}

Dvl::Dvl(DvlConfig config) : config_(std::move(config)) {
    config_.validate();
    const double a = config_.beam_angle_rad;
    for (int i = 0; i < 4; ++i) {
        const double phi = std::numbers::pi / 4.0 + std::numbers::pi / 2.0 * i;
        beams_sensor_[i] = {std::sin(a) * std::cos(phi), std::sin(a) * std::sin(phi), std::cos(a)};
    }
}

double Dvl::beam_sigma_mps(double radial_velocity_mps) const {
    return std::hypot(config_.beam_velocity_sigma_mps,
                      config_.beam_velocity_sigma_fraction * radial_velocity_mps);
}

DvlBeam Dvl::measure_beam(const SceneView& scene, const Eigen::Isometry3d& T_world_sensor, int i,
                          const Eigen::Vector3d& v_sensor_mps, Rng& rng) const {
    const double velocity_noise = rng.normal();
    const double range_noise = rng.normal();
    const double cos_a = std::cos(config_.beam_angle_rad);
    const RayHit hit = scene.cast(T_world_sensor.translation(),
                                  (T_world_sensor.linear() * beams_sensor_[i]).normalized(),
                                  config_.max_altitude_m / cos_a);
    DvlBeam beam;
    if (!hit.hit || hit.range_m < config_.min_altitude_m / cos_a) return beam;
    beam.locked = true;
    beam.range_m = hit.range_m + config_.range_sigma_m * range_noise;
    const double radial_mps = beams_sensor_[i].dot(v_sensor_mps);
    beam.velocity_mps = radial_mps + beam_sigma_mps(radial_mps) * velocity_noise;
    return beam;
}

DvlSample Dvl::measure(const SceneView& scene, const MotionState& truth, Rng& rng) const {
    detail::check_motion(truth, "dvl");
    const Eigen::Isometry3d T_world_sensor = truth.T_world_body * config_.T_body_sensor;
    const Eigen::Vector3d r_body = config_.T_body_sensor.translation();
    const Eigen::Vector3d v_world_sensor =
        truth.v_world_mps + truth.T_world_body.linear() * truth.omega_body_radps.cross(r_body);
    const Eigen::Vector3d v_sensor = T_world_sensor.linear().transpose() * v_world_sensor;
    DvlSample sample;
    sample.stamp_s = truth.stamp_s;
    for (int i = 0; i < 4; ++i) {
        sample.beams[i] = measure_beam(scene, T_world_sensor, i, v_sensor, rng);
    }
    fit_velocity(sample);
    return sample;
}

void Dvl::fit_velocity(DvlSample& sample) const {
    Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    int locked = 0;
    double altitude_sum_m = 0.0;
    for (int i = 0; i < 4; ++i) {
        const DvlBeam& beam = sample.beams[i];
        if (!beam.locked) continue;
        // Weights from the measured radial speed (the instrument does not know the truth);
        // the floor keeps a noiseless config solvable.
        const double sigma = std::max(kMinSigmaMps, beam_sigma_mps(beam.velocity_mps));
        const Eigen::Vector3d& b = beams_sensor_[i];
        information += b * b.transpose() / (sigma * sigma);
        rhs += b * beam.velocity_mps / (sigma * sigma);
        altitude_sum_m += beam.range_m * std::cos(config_.beam_angle_rad);
        ++locked;
    }
    if (locked < 3) return;
    const Eigen::Matrix3d R_body_sensor = config_.T_body_sensor.linear();
    const Eigen::Matrix3d covariance_sensor = information.inverse();
    sample.valid = true;
    sample.v_body_mps = R_body_sensor * (covariance_sensor * rhs);
    sample.covariance = R_body_sensor * covariance_sensor * R_body_sensor.transpose();
    sample.altitude_m = altitude_sum_m / locked;
}

}  // namespace scantling::sim
