#include <scantling/sim/vio.hpp>

#include <scantling/core/error.hpp>

#include "detail/motion_checks.hpp"
#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <cmath>

namespace scantling::sim {
namespace {

// Gravity-aligned frame at the body: the body position and yaw, no roll or pitch.
Eigen::Isometry3d yaw_frame(const Eigen::Isometry3d& T_world_body) {
    const Eigen::Matrix3d& R = T_world_body.linear();
    const double yaw_rad = std::atan2(R(1, 0), R(0, 0));
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = T_world_body.translation();
    return T;
}

// Rotation by yaw_rad about the vertical through `pivot`, then a shift: a drift increment.
Eigen::Isometry3d drift_increment(const Eigen::Vector3d& pivot, double yaw_rad,
                                  const Eigen::Vector3d& shift) {
    Eigen::Isometry3d N = Eigen::Isometry3d::Identity();
    N.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    N.translation() = pivot - N.linear() * pivot + shift;
    return N;
}

}  // namespace

void VioConfig::validate(std::string_view prefix) const {
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require_non_negative(prefix, "position_random_walk_m_per_sqrt_m",
                                 position_random_walk_m_per_sqrt_m);
    detail::require_non_negative(prefix, "yaw_random_walk_rad_per_sqrt_m",
                                 yaw_random_walk_rad_per_sqrt_m);
    detail::require_non_negative(prefix, "poor_features_drift_gain", poor_features_drift_gain);
    detail::require_probability(prefix, "lost_feature_quality", lost_feature_quality);
    detail::require_non_negative(prefix, "position_jitter_m", position_jitter_m);
    detail::require_non_negative(prefix, "attitude_jitter_rad", attitude_jitter_rad);
    detail::require_non_negative(prefix, "velocity_sigma_mps", velocity_sigma_mps);
    detail::require_non_negative(prefix, "dropout_rate_per_s", dropout_rate_per_s);
    detail::require_non_negative(prefix, "dropout_duration_s", dropout_duration_s);
}

VioConfig noiseless(VioConfig config) {
    config.position_random_walk_m_per_sqrt_m = 0.0;
    config.yaw_random_walk_rad_per_sqrt_m = 0.0;
    config.lost_feature_quality = 0.0;
    config.position_jitter_m = 0.0;
    config.attitude_jitter_rad = 0.0;
    config.velocity_sigma_mps = 0.0;
    config.dropout_rate_per_s = 0.0;
    return config;
}

VioSimulator::VioSimulator(VioConfig config) : config_(config) { config_.validate(); }

void VioSimulator::start(const MotionState& truth) {
    started_ = true;
    previous_stamp_s_ = truth.stamp_s;
    previous_p_world_ = truth.T_world_body.translation();
    T_world_odom_ = yaw_frame(truth.T_world_body);
}

void VioSimulator::update_dropout(double stamp_s, double dt_s, double feature_quality,
                                  double uniform) {
    const bool in_dropout = stamp_s < dropout_until_s_;
    const double p_start = 1.0 - std::exp(-config_.dropout_rate_per_s * dt_s);
    if (!in_dropout && uniform < p_start) dropout_until_s_ = stamp_s + config_.dropout_duration_s;
    tracking_ = feature_quality >= config_.lost_feature_quality && stamp_s >= dropout_until_s_;
}

void VioSimulator::propagate_drift(const Eigen::Vector3d& p_world, double scale, Rng& rng) {
    const Eigen::Vector3d delta = p_world - previous_p_world_;
    const double d_m = delta.norm();
    distance_m_ += d_m;
    const double sigma_p = scale * config_.position_random_walk_m_per_sqrt_m * std::sqrt(d_m);
    const double sigma_yaw = scale * config_.yaw_random_walk_rad_per_sqrt_m * std::sqrt(d_m);
    const Eigen::Vector3d shift = rng.normal3(sigma_p);
    const double yaw_rad = rng.normal(0.0, sigma_yaw);
    E_drift_ = drift_increment(E_drift_ * p_world, yaw_rad, shift) * E_drift_;
    // Linearised error propagation: a yaw error ψ turns the displacement Δ by ψ ẑ × Δ.
    Eigen::Matrix4d transition = Eigen::Matrix4d::Identity();
    transition.block<3, 1>(0, 3) = Eigen::Vector3d::UnitZ().cross(delta);
    const Eigen::Vector4d q(sigma_p * sigma_p, sigma_p * sigma_p, sigma_p * sigma_p,
                            sigma_yaw * sigma_yaw);
    drift_covariance_ = transition * drift_covariance_ * transition.transpose();
    drift_covariance_ += q.asDiagonal();
    previous_p_world_ = p_world;
}

VioSample VioSimulator::step(const MotionState& truth, double feature_quality, Rng& rng) {
    detail::check_motion(truth, "vio");
    if (!(feature_quality >= 0.0 && feature_quality <= 1.0)) {
        throw InputError(
            fmt::format("vio: feature_quality = {}, expected in [0, 1]", feature_quality));
    }
    if (!started_) start(truth);
    detail::check_stamp_order(truth.stamp_s, previous_stamp_s_, "vio");
    const double dt_s = truth.stamp_s - previous_stamp_s_;
    update_dropout(truth.stamp_s, dt_s, feature_quality, rng.uniform());
    propagate_drift(truth.T_world_body.translation(),
                    1.0 + config_.poor_features_drift_gain * (1.0 - feature_quality), rng);
    previous_stamp_s_ = truth.stamp_s;
    VioSample sample = output(truth, rng);
    sample.feature_quality = feature_quality;
    return sample;
}

VioSample VioSimulator::output(const MotionState& truth, Rng& rng) const {
    const Eigen::Isometry3d T_odom_world = T_world_odom_.inverse();
    Eigen::Isometry3d T_odom_body = T_odom_world * E_drift_ * truth.T_world_body;
    T_odom_body.translation() += rng.normal3(config_.position_jitter_m);
    T_odom_body.linear() = so3_exp(rng.normal3(config_.attitude_jitter_rad)) * T_odom_body.linear();

    VioSample sample;
    sample.stamp_s = truth.stamp_s;
    sample.T_odom_body = T_odom_body;
    sample.v_body_mps = truth.T_world_body.linear().transpose() * truth.v_world_mps +
                        rng.normal3(config_.velocity_sigma_mps);
    sample.valid = tracking_;

    const Eigen::Matrix3d R = T_odom_world.linear();
    Matrix6d& P = sample.covariance;
    P.block<3, 3>(0, 0) = R * drift_covariance_.block<3, 3>(0, 0) * R.transpose();
    P.block<3, 1>(0, 5) = R * drift_covariance_.block<3, 1>(0, 3);
    P.block<1, 3>(5, 0) = P.block<3, 1>(0, 5).transpose();
    P(5, 5) = drift_covariance_(3, 3);
    P.diagonal().head<3>().array() += config_.position_jitter_m * config_.position_jitter_m;
    P.diagonal().tail<3>().array() += config_.attitude_jitter_rad * config_.attitude_jitter_rad;
    sample.velocity_covariance =
        Eigen::Matrix3d::Identity() * config_.velocity_sigma_mps * config_.velocity_sigma_mps;
    return sample;
}

}  // namespace scantling::sim
