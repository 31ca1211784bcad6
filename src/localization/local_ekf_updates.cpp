// The local EKF's measurements: LiDAR increments (stochastic cloning), range, barometer,
// and underwater a DVL's body velocity and a pressure depth.
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include <scantling/core/error.hpp>
#include <scantling/localization/local_ekf.hpp>

#include "detail/local_ekf_layout.hpp"

namespace scantling::localization {

using namespace detail;

namespace {

void require_finite(bool ok, std::string_view what, double stamp_s) {
    if (!ok) throw InputError(fmt::format("local_ekf: {} at {} s is not finite", what, stamp_s));
}

/// Symmetric (to rounding) and positive definite: a Cholesky factorisation exists.
bool symmetric_positive_definite(const Eigen::Matrix3d& M) {
    if (!M.allFinite() || !M.isApprox(M.transpose(), 1e-9)) return false;
    return Eigen::LLT<Eigen::Matrix3d>(M).info() == Eigen::Success;
}

void require_valid(const BodyVelocityMeasurement& m) {
    require_finite(std::isfinite(m.stamp_s), "body velocity stamp_s", m.stamp_s);
    require_finite(m.v_sensor_mps.allFinite(), "body velocity v_sensor_mps", m.stamp_s);
    require_finite(m.covariance_mps2.allFinite(), "body velocity covariance_mps2", m.stamp_s);
    if (!symmetric_positive_definite(m.covariance_mps2))
        throw InputError(fmt::format(
            "local_ekf: body velocity covariance_mps2 at {} s is not symmetric positive definite",
            m.stamp_s));
}

/// The information's non-null eigen-space: directions (columns) and their eigenvalues.
struct InformationBasis {
    Eigen::MatrixXd directions;
    Eigen::VectorXd eigenvalues;
};

InformationBasis information_basis(const Matrix6d& information, double relative_threshold) {
    const Eigen::SelfAdjointEigenSolver<Matrix6d> solver(0.5 *
                                                         (information + information.transpose()));
    const Vector6d& lambda = solver.eigenvalues();
    const double largest = lambda.maxCoeff();
    InformationBasis basis;
    basis.directions.resize(6, 0);
    for (int i = 0; i < 6; ++i) {
        if (!(largest > 0.0) || lambda(i) <= relative_threshold * largest) continue;
        basis.directions.conservativeResize(6, basis.directions.cols() + 1);
        basis.directions.rightCols<1>() = solver.eigenvectors().col(i);
        basis.eigenvalues.conservativeResize(basis.eigenvalues.size() + 1);
        basis.eigenvalues(basis.eigenvalues.size() - 1) = lambda(i);
    }
    return basis;
}

}  // namespace

std::optional<UpdateStatus> LocalEkf::advance_to(double stamp_s) {
    if (!initialized_) return UpdateStatus::kNotInitialized;
    if (stamp_s < stamp_s_ - config_.max_measurement_delay_s) return UpdateStatus::kTooOld;
    const double dt_s = stamp_s - stamp_s_;
    // Ahead of the IMU: hold its last sample (a gap if long, as for a late IMU sample).
    if (dt_s > 0.0) predict(dt_s, held_, dt_s > config_.max_imu_gap_s);
    return std::nullopt;
}

UpdateStatus LocalEkf::clone_pose(double stamp_s) {
    require_finite(std::isfinite(stamp_s), "clone stamp", stamp_s);
    if (const auto refused = advance_to(stamp_s)) return *refused;
    x_.clone_p_odom = x_.p_odom;
    x_.clone_R_odom_body = x_.R_odom_body;
    // The clone is a copy of (δp, δθ): same rows, same columns, fully correlated.
    P_.block<6, kStateDim>(kCloneP, 0) = P_.block<6, kStateDim>(kP, 0);
    P_.block<kStateDim, 6>(0, kCloneP) = P_.block<kStateDim, 6>(0, kP);
    clone_stamp_s_ = stamp_s;
    return UpdateStatus::kApplied;
}

UpdateResult LocalEkf::update_increment(const PoseIncrement& increment) {
    require_finite(std::isfinite(increment.start_stamp_s) && std::isfinite(increment.end_stamp_s) &&
                       increment.T_body0_body1.matrix().allFinite() &&
                       increment.information.allFinite(),
                   "increment", increment.end_stamp_s);
    UpdateResult result;
    if (const auto refused = advance_to(increment.end_stamp_s)) {
        result.status = *refused;
    } else if (!clone_stamp_s_ || std::abs(*clone_stamp_s_ - increment.start_stamp_s) >
                                      std::max(config_.max_measurement_delay_s, 1e-9)) {
        result.status = UpdateStatus::kNoClone;
    } else {
        result = fuse_increment(increment);
        clone_pose(increment.end_stamp_s);  // the next sweep starts where this one ended
    }
    if (result.status == UpdateStatus::kApplied)
        ++counters_.increments_applied;
    else if (result.status != UpdateStatus::kNotInitialized)
        ++counters_.increments_rejected;
    return result;
}

UpdateResult LocalEkf::fuse_increment(const PoseIncrement& increment) {
    const InformationBasis basis =
        information_basis(increment.information, config_.information_relative_threshold);
    const int m = static_cast<int>(basis.eigenvalues.size());
    if (m == 0) return UpdateResult{UpdateStatus::kNoInformation, 0.0, 0};
    const Eigen::Isometry3d T0 = make_isometry(x_.clone_R_odom_body, x_.clone_p_odom);
    const Eigen::Isometry3d T1 = make_isometry(x_.R_odom_body, x_.p_odom);
    // z = exp(−ε) · h(x): the residual log(z · ĥ⁻¹) ≈ H δx − ε.
    const Vector6d residual = se3_log(increment.T_body0_body1 * (T0.inverse() * T1).inverse());
    const Eigen::Matrix<double, 6, 12> J = increment_jacobian(T0, T1);
    Eigen::MatrixXd H6 = Eigen::MatrixXd::Zero(6, kStateDim);
    H6.middleCols<6>(kP) = J.leftCols<6>();
    H6.middleCols<6>(kCloneP) = J.rightCols<6>();
    // Each kept eigen-direction is a 1-D measurement of variance 1/λ; null ones are dropped.
    const Eigen::MatrixXd Ut = basis.directions.transpose();
    const Eigen::MatrixXd noise = basis.eigenvalues.cwiseInverse().asDiagonal();
    const double gate =
        config_.gate_increments ? chi2_quantile_999(m) : std::numeric_limits<double>::infinity();
    return correct(Ut * H6, Ut * residual, noise, gate);
}

UpdateResult LocalEkf::update_range(const io::RangeRecord& range) {
    if (!range.valid) return UpdateResult{UpdateStatus::kInvalid, 0.0, 0};
    require_finite(std::isfinite(range.stamp_s) && std::isfinite(range.range_m), "range",
                   range.stamp_s);
    if (const auto refused = advance_to(range.stamp_s)) return UpdateResult{*refused, 0.0, 0};
    const RangePrediction predicted = predict_range(make_isometry(x_.R_odom_body, x_.p_odom),
                                                    config_.T_body_sensor, config_.floor_height_m);
    if (range.range_m < config_.min_range_m || range.range_m > config_.max_range_m ||
        predicted.cos_tilt < std::cos(config_.max_range_tilt_rad))
        return UpdateResult{UpdateStatus::kInvalid, 0.0, 0};
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(1, kStateDim);
    H.middleCols<6>(kP) = predicted.jacobian;
    const Eigen::VectorXd residual =
        Eigen::VectorXd::Constant(1, range.range_m - predicted.range_m);
    const Eigen::MatrixXd noise =
        Eigen::MatrixXd::Constant(1, 1, std::pow(config_.range_sigma_m, 2));
    const UpdateResult result = correct(H, residual, noise, config_.range_gate_chi2);
    ++(result.status == UpdateStatus::kApplied ? counters_.ranges_applied
                                               : counters_.ranges_rejected);
    return result;
}

void LocalEkf::initialize_barometer_bias(const BarometerMeasurement& altitude) {
    // b = altitude − p_z: its error is −δp_z plus the sample's noise.
    x_.barometer_bias_m = altitude.altitude_m - x_.p_odom.z();
    P_.row(kBaro) = -P_.row(kP + 2);
    P_.col(kBaro) = -P_.col(kP + 2);
    P_(kBaro, kBaro) = P_(kP + 2, kP + 2) + altitude.sigma_m * altitude.sigma_m;
    barometer_initialized_ = true;
}

UpdateResult LocalEkf::update_barometer(const BarometerMeasurement& altitude) {
    require_finite(std::isfinite(altitude.stamp_s) && std::isfinite(altitude.altitude_m) &&
                       std::isfinite(altitude.sigma_m) && altitude.sigma_m > 0.0,
                   "barometer altitude (or sigma_m <= 0)", altitude.stamp_s);
    if (const auto refused = advance_to(altitude.stamp_s)) return UpdateResult{*refused, 0.0, 0};
    if (!barometer_initialized_) {
        initialize_barometer_bias(altitude);
        return UpdateResult{UpdateStatus::kApplied, 0.0, 0};
    }
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(1, kStateDim);
    H(0, kP + 2) = 1.0;
    H(0, kBaro) = 1.0;
    const double predicted_m = x_.p_odom.z() + x_.barometer_bias_m;
    const Eigen::VectorXd residual =
        Eigen::VectorXd::Constant(1, altitude.altitude_m - predicted_m);
    const Eigen::MatrixXd noise =
        Eigen::MatrixXd::Constant(1, 1, altitude.sigma_m * altitude.sigma_m);
    const UpdateResult result = correct(H, residual, noise, config_.barometer_gate_chi2);
    ++(result.status == UpdateStatus::kApplied ? counters_.barometer_applied
                                               : counters_.barometer_rejected);
    return result;
}

UpdateResult LocalEkf::update_body_velocity(const BodyVelocityMeasurement& velocity) {
    require_valid(velocity);
    if (const auto refused = advance_to(velocity.stamp_s)) return UpdateResult{*refused, 0.0, 0};
    // The lever arm turns with the held sample's rate, the same ω that state() reports.
    const BodyVelocityPrediction predicted =
        predict_body_velocity(x_.R_odom_body, x_.v_odom, held_.angular_rate_radps - x_.gyro_bias,
                              config_.T_body_velocity_sensor);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(3, kStateDim);
    H.middleCols<3>(kTheta) = predicted.d_theta;
    H.middleCols<3>(kV) = predicted.d_velocity;
    H.middleCols<3>(kBg) = predicted.d_gyro_bias;
    const Eigen::VectorXd residual = velocity.v_sensor_mps - predicted.v_sensor_mps;
    // ω is one raw gyro sample: its white noise reaches the lever arm's velocity ω × t.
    const double gyro_var =
        imu_interval_s_ > 0.0
            ? std::pow(config_.gyro_noise_density_radps_per_sqrt_hz, 2) / imu_interval_s_
            : 0.0;
    const Eigen::MatrixXd noise = velocity.covariance_mps2 + gyro_var * predicted.d_gyro_bias *
                                                                 predicted.d_gyro_bias.transpose();
    const UpdateResult result = correct(H, residual, noise, config_.velocity_gate_chi2);
    ++(result.status == UpdateStatus::kApplied ? counters_.velocity_applied
                                               : counters_.velocity_rejected);
    return result;
}

UpdateResult LocalEkf::update_depth(const DepthMeasurement& depth) {
    require_finite(std::isfinite(depth.stamp_s) && std::isfinite(depth.z_odom_m) &&
                       std::isfinite(depth.sigma_m) && depth.sigma_m > 0.0,
                   "depth z_odom_m (or sigma_m <= 0)", depth.stamp_s);
    if (const auto refused = advance_to(depth.stamp_s)) return UpdateResult{*refused, 0.0, 0};
    // Water pressure is an absolute depth: p_z alone, no bias state as the barometer has.
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(1, kStateDim);
    H(0, kP + 2) = 1.0;
    const Eigen::VectorXd residual = Eigen::VectorXd::Constant(1, depth.z_odom_m - x_.p_odom.z());
    const Eigen::MatrixXd noise = Eigen::MatrixXd::Constant(1, 1, depth.sigma_m * depth.sigma_m);
    const UpdateResult result = correct(H, residual, noise, config_.depth_gate_chi2);
    ++(result.status == UpdateStatus::kApplied ? counters_.depth_applied
                                               : counters_.depth_rejected);
    return result;
}

UpdateResult LocalEkf::update_yaw(const YawMeasurement& yaw) {
    require_finite(std::isfinite(yaw.stamp_s) && std::isfinite(yaw.yaw_odom_rad) &&
                       std::isfinite(yaw.sigma_rad) && yaw.sigma_rad > 0.0,
                   "yaw yaw_odom_rad (or sigma_rad <= 0)", yaw.stamp_s);
    if (const auto refused = advance_to(yaw.stamp_s)) return UpdateResult{*refused, 0.0, 0};
    const Eigen::Vector3d euler = euler_zyx_from_rotation(x_.R_odom_body);  // roll, pitch, yaw
    // Left perturbation R_true = exp(δθ) R: ψ changes by δθ_z + tan θ (cos ψ δθ_x + sin ψ δθ_y).
    const double tan_pitch = std::tan(euler.y());
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(1, kStateDim);
    H(0, kTheta) = tan_pitch * std::cos(euler.z());
    H(0, kTheta + 1) = tan_pitch * std::sin(euler.z());
    H(0, kTheta + 2) = 1.0;
    const double wrapped = std::remainder(yaw.yaw_odom_rad - euler.z(), 2.0 * std::numbers::pi);
    const Eigen::VectorXd residual = Eigen::VectorXd::Constant(1, wrapped);
    const Eigen::MatrixXd noise = Eigen::MatrixXd::Constant(1, 1, yaw.sigma_rad * yaw.sigma_rad);
    const UpdateResult result = correct(H, residual, noise, config_.yaw_gate_chi2);
    ++(result.status == UpdateStatus::kApplied ? counters_.yaw_applied : counters_.yaw_rejected);
    return result;
}

}  // namespace scantling::localization
