// The local EKF's configuration checks, names and measurement models (local_ekf.hpp).
#include <array>

#include <scantling/core/error.hpp>
#include <scantling/localization/local_ekf.hpp>

#include "detail/config_checks.hpp"

namespace scantling::localization {

std::string_view to_string(ImuPredictionStatus status) {
    switch (status) {
        case ImuPredictionStatus::kOk:
            return "ok";
        case ImuPredictionStatus::kFirst:
            return "first";
        case ImuPredictionStatus::kGap:
            return "gap";
        case ImuPredictionStatus::kOutOfOrder:
            return "out_of_order";
        case ImuPredictionStatus::kNotInitialized:
            return "not_initialized";
    }
    return "unknown";
}

std::string_view to_string(UpdateStatus status) {
    switch (status) {
        case UpdateStatus::kApplied:
            return "applied";
        case UpdateStatus::kRejected:
            return "rejected";
        case UpdateStatus::kTooOld:
            return "too_old";
        case UpdateStatus::kInvalid:
            return "invalid";
        case UpdateStatus::kNoClone:
            return "no_clone";
        case UpdateStatus::kNoInformation:
            return "no_information";
        case UpdateStatus::kUnknownAnchor:
            return "unknown_anchor";
        case UpdateStatus::kNoLocal:
            return "no_local";
        case UpdateStatus::kNotInitialized:
            return "not_initialized";
    }
    return "unknown";
}

namespace {

void validate_imu_noise(const LocalEkfConfig& c, std::string_view prefix) {
    detail::require_positive(c.gravity_mps2, prefix, "gravity_mps2");
    detail::require_positive(c.accel_noise_density_mps2_per_sqrt_hz, prefix,
                             "accel_noise_density_mps2_per_sqrt_hz");
    detail::require_positive(c.gyro_noise_density_radps_per_sqrt_hz, prefix,
                             "gyro_noise_density_radps_per_sqrt_hz");
    detail::require_non_negative(c.accel_bias_random_walk_mps3_per_sqrt_hz, prefix,
                                 "accel_bias_random_walk_mps3_per_sqrt_hz");
    detail::require_non_negative(c.gyro_bias_random_walk_radps2_per_sqrt_hz, prefix,
                                 "gyro_bias_random_walk_radps2_per_sqrt_hz");
}

void validate_initial(const LocalEkfConfig& c, std::string_view prefix) {
    detail::require_non_negative(c.initial_position_sigma_m, prefix, "initial_position_sigma_m");
    detail::require_non_negative(c.initial_tilt_sigma_rad, prefix, "initial_tilt_sigma_rad");
    detail::require_non_negative(c.initial_yaw_sigma_rad, prefix, "initial_yaw_sigma_rad");
    detail::require_non_negative(c.initial_velocity_sigma_mps, prefix,
                                 "initial_velocity_sigma_mps");
    detail::require_non_negative(c.initial_accel_bias_sigma_mps2, prefix,
                                 "initial_accel_bias_sigma_mps2");
    detail::require_non_negative(c.initial_gyro_bias_sigma_radps, prefix,
                                 "initial_gyro_bias_sigma_radps");
}

void validate_timing(const LocalEkfConfig& c, std::string_view prefix) {
    detail::require_positive(c.max_imu_gap_s, prefix, "max_imu_gap_s");
    detail::require_non_negative(c.gap_acceleration_sigma_mps2, prefix,
                                 "gap_acceleration_sigma_mps2");
    detail::require_non_negative(c.gap_angular_rate_sigma_radps, prefix,
                                 "gap_angular_rate_sigma_radps");
    detail::require_non_negative(c.max_measurement_delay_s, prefix, "max_measurement_delay_s");
    config_checks::require_open_unit(c.information_relative_threshold, prefix,
                                     "information_relative_threshold");
}

void validate_height(const LocalEkfConfig& c, std::string_view prefix) {
    detail::require_positive(c.range_sigma_m, prefix, "range_sigma_m");
    detail::require_non_negative(c.min_range_m, prefix, "min_range_m");
    detail::require(std::isfinite(c.max_range_m) && c.max_range_m > c.min_range_m, prefix,
                    "max_range_m", c.max_range_m, "finite > min_range_m");
    detail::require(c.max_range_tilt_rad > 0.0 && c.max_range_tilt_rad < 1.5, prefix,
                    "max_range_tilt_rad", c.max_range_tilt_rad, "in (0, 1.5)");
    detail::require(std::isfinite(c.floor_height_m), prefix, "floor_height_m", c.floor_height_m,
                    "finite");
    detail::require_positive(c.range_gate_chi2, prefix, "range_gate_chi2");
    detail::require_non_negative(c.barometer_bias_random_walk_m_per_sqrt_s, prefix,
                                 "barometer_bias_random_walk_m_per_sqrt_s");
    detail::require_positive(c.barometer_gate_chi2, prefix, "barometer_gate_chi2");
}

void validate_underwater(const LocalEkfConfig& c, std::string_view prefix) {
    detail::require_positive(c.velocity_gate_chi2, prefix, "velocity_gate_chi2");
    detail::require_positive(c.depth_gate_chi2, prefix, "depth_gate_chi2");
    detail::require_positive(c.yaw_gate_chi2, prefix, "yaw_gate_chi2");
}

void validate_mount(const Eigen::Isometry3d& T, std::string_view prefix, std::string_view field) {
    const bool finite = T.matrix().allFinite();
    const double orthogonality =
        finite ? (T.linear().transpose() * T.linear() - Eigen::Matrix3d::Identity()).norm() : 1.0;
    detail::require(finite && orthogonality < 1e-6, prefix, field, orthogonality,
                    "a finite rigid transform (|RᵀR − I| < 1e-6)");
}

}  // namespace

void LocalEkfConfig::validate(std::string_view prefix) const {
    validate_mount(T_body_imu, prefix, "T_body_imu");
    validate_mount(T_body_sensor, prefix, "T_body_sensor");
    validate_mount(T_body_velocity_sensor, prefix, "T_body_velocity_sensor");
    validate_imu_noise(*this, prefix);
    validate_initial(*this, prefix);
    validate_timing(*this, prefix);
    validate_height(*this, prefix);
    validate_underwater(*this, prefix);
}

Eigen::Matrix<double, 6, 12> increment_jacobian(const Eigen::Isometry3d& T_odom_body0,
                                                const Eigen::Isometry3d& T_odom_body1) {
    // ρ = R₀ᵀ(δp₁ − δp₀ + [p₁ − p₀]× δθ₁), ω = R₀ᵀ(δθ₁ − δθ₀): the δθ₀ terms of ρ cancel
    // between the rotated displacement and the twist's ω × t coupling.
    const Eigen::Matrix3d R0t = T_odom_body0.linear().transpose();
    const Eigen::Vector3d d = T_odom_body1.translation() - T_odom_body0.translation();
    Eigen::Matrix<double, 6, 12> J = Eigen::Matrix<double, 6, 12>::Zero();
    J.block<3, 3>(0, 0) = R0t;
    J.block<3, 3>(0, 3) = R0t * hat(d);
    J.block<3, 3>(0, 6) = -R0t;
    J.block<3, 3>(3, 3) = R0t;
    J.block<3, 3>(3, 9) = -R0t;
    return J;
}

RangePrediction predict_range(const Eigen::Isometry3d& T_odom_body,
                              const Eigen::Isometry3d& T_body_sensor, double floor_height_m) {
    const Eigen::Matrix3d& R = T_odom_body.linear();
    const Eigen::Vector3d lever = R * T_body_sensor.translation();
    const Eigen::Vector3d ray = R * T_body_sensor.linear().col(2);
    const Eigen::RowVector3d ez = Eigen::RowVector3d::UnitZ();
    RangePrediction out;
    out.cos_tilt = -ray.z();
    if (out.cos_tilt <= 0.0) return out;
    const double height_m = T_odom_body.translation().z() + lever.z() - floor_height_m;
    out.range_m = height_m / out.cos_tilt;
    // Left perturbation: R_true·x = x − [x]× δθ, so ∂(Rx)_z/∂δθ = −e_zᵀ[Rx]×.
    out.jacobian.leftCols<3>() = ez / out.cos_tilt;
    out.jacobian.rightCols<3>() =
        -ez * hat(lever) / out.cos_tilt - height_m * ez * hat(ray) / (out.cos_tilt * out.cos_tilt);
    return out;
}

BodyVelocityPrediction predict_body_velocity(const Eigen::Matrix3d& R_odom_body,
                                             const Eigen::Vector3d& v_odom_mps,
                                             const Eigen::Vector3d& omega_body_radps,
                                             const Eigen::Isometry3d& T_body_sensor) {
    const Eigen::Matrix3d Rst = T_body_sensor.linear().transpose();
    const Eigen::Vector3d lever = T_body_sensor.translation();
    BodyVelocityPrediction out;
    out.v_sensor_mps = Rst * (R_odom_body.transpose() * v_odom_mps + omega_body_radps.cross(lever));
    // Left perturbation: R_trueᵀ v = Rᵀ exp(−δθ) v ≈ Rᵀ v + Rᵀ [v]× δθ.
    out.d_theta = Rst * R_odom_body.transpose() * hat(v_odom_mps);
    out.d_velocity = Rst * R_odom_body.transpose();
    // ω_true = ω − δb_g, so ω_true × t = ω × t + [t]× δb_g.
    out.d_gyro_bias = Rst * hat(lever);
    return out;
}

double chi2_quantile_999(int dof) {
    static constexpr std::array<double, 6> kQuantiles = {10.828, 13.816, 16.266,
                                                         18.467, 20.515, 22.458};
    if (dof < 1 || dof > 6) throw InputError("chi2_quantile_999: dof must be in [1, 6]");
    return kQuantiles[static_cast<std::size_t>(dof - 1)];
}

}  // namespace scantling::localization
