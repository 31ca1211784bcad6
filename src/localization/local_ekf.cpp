// The local EKF's IMU prediction, generic update and error injection (local_ekf.hpp).
#include "scantling/localization/local_ekf.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include <scantling/core/error.hpp>

#include "detail/local_ekf_layout.hpp"

namespace scantling::localization {

using namespace detail;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

using CoreMatrix = Eigen::Matrix<double, kCoreDim, kCoreDim>;

void set_diagonal(CoreMatrix& M, int index, double variance) {
    M.block<3, 3>(index, index).diagonal().array() += variance;
}

LocalEkf::StateMatrix initial_covariance(const LocalEkfConfig& c) {
    LocalEkf::StateMatrix P = LocalEkf::StateMatrix::Zero();
    P.block<3, 3>(kP, kP).diagonal().setConstant(c.initial_position_sigma_m *
                                                 c.initial_position_sigma_m);
    const double tilt_var = c.initial_tilt_sigma_rad * c.initial_tilt_sigma_rad;
    P.block<3, 3>(kTheta, kTheta).diagonal() << tilt_var, tilt_var,
        c.initial_yaw_sigma_rad * c.initial_yaw_sigma_rad;
    P.block<3, 3>(kV, kV).diagonal().setConstant(c.initial_velocity_sigma_mps *
                                                 c.initial_velocity_sigma_mps);
    P.block<3, 3>(kBa, kBa).diagonal().setConstant(c.initial_accel_bias_sigma_mps2 *
                                                   c.initial_accel_bias_sigma_mps2);
    P.block<3, 3>(kBg, kBg).diagonal().setConstant(c.initial_gyro_bias_sigma_radps *
                                                   c.initial_gyro_bias_sigma_radps);
    return P;
}

void require_finite(const io::ImuRecord& s) {
    if (!std::isfinite(s.stamp_s) || !s.specific_force_mps2.allFinite() ||
        !s.angular_rate_radps.allFinite()) {
        throw InputError(fmt::format("local_ekf: IMU sample at {} s is not finite", s.stamp_s));
    }
}

}  // namespace

LocalEkf::LocalEkf(LocalEkfConfig config) : config_(std::move(config)) { config_.validate(); }

void LocalEkf::initialize(double stamp_s, const Eigen::Isometry3d& T_odom_body,
                          const Vector3d& v_odom_mps) {
    if (!std::isfinite(stamp_s) || !T_odom_body.matrix().allFinite() || !v_odom_mps.allFinite())
        throw InputError("local_ekf.initialize: stamp, pose or velocity is not finite");
    x_ = Nominal{};
    x_.p_odom = T_odom_body.translation();
    x_.R_odom_body = orthonormalize(T_odom_body.linear());
    x_.v_odom = v_odom_mps;
    P_ = initial_covariance(config_);
    stamp_s_ = stamp_s;
    initialized_ = true;
    last_imu_.reset();
    imu_interval_s_ = 0.0;
    clone_stamp_s_.reset();
    barometer_initialized_ = false;
    // Until a sample arrives, hold what a hovering IMU reads: gravity's reaction, no rotation.
    held_ = BodyRates{x_.R_odom_body.transpose() * Vector3d(0, 0, config_.gravity_mps2),
                      Vector3d::Zero()};
}

LocalEkf::BodyRates LocalEkf::to_body(const io::ImuRecord& sample) const {
    const Matrix3d& R_body_imu = config_.T_body_imu.linear();
    const Vector3d lever_body = config_.T_body_imu.translation();
    const Vector3d w = R_body_imu * sample.angular_rate_radps;
    // An IMU off the body origin also feels the centripetal acceleration ω × (ω × r).
    const Vector3d f = R_body_imu * sample.specific_force_mps2 - w.cross(w.cross(lever_body));
    return BodyRates{f, w};
}

ImuPredictionStatus LocalEkf::add_imu(const io::ImuRecord& sample) {
    require_finite(sample);
    if (!initialized_) return ImuPredictionStatus::kNotInitialized;
    if (last_imu_ && sample.stamp_s <= last_imu_->stamp_s) {
        ++counters_.imu_out_of_order;
        return ImuPredictionStatus::kOutOfOrder;
    }
    const BodyRates now = to_body(sample);
    ImuPredictionStatus status = last_imu_ ? ImuPredictionStatus::kOk : ImuPredictionStatus::kFirst;
    const double dt_s = sample.stamp_s - stamp_s_;
    if (dt_s > 0.0) {
        const BodyRates mean{0.5 * (held_.specific_force_mps2 + now.specific_force_mps2),
                             0.5 * (held_.angular_rate_radps + now.angular_rate_radps)};
        const bool gap = dt_s > config_.max_imu_gap_s;
        predict(dt_s, last_imu_ ? mean : now, gap);
        if (gap) status = ImuPredictionStatus::kGap;
    }
    ++counters_.imu_samples;
    if (last_imu_) imu_interval_s_ = sample.stamp_s - last_imu_->stamp_s;
    held_ = now;
    last_imu_ = sample;
    return status;
}

void LocalEkf::predict(double dt_s, const BodyRates& rates, bool gap) {
    if (gap) ++counters_.imu_gaps;
    const Vector3d w = rates.angular_rate_radps - x_.gyro_bias;
    const Vector3d a_body = rates.specific_force_mps2 - x_.accel_bias;
    const Vector3d gravity(0.0, 0.0, -config_.gravity_mps2);
    // The midpoint attitude makes the velocity step second-order accurate under rotation.
    const Matrix3d R_mid = x_.R_odom_body * so3_exp(0.5 * dt_s * w);
    const Vector3d a_odom = R_mid * a_body + gravity;
    propagate_covariance(dt_s, a_body, gap);
    x_.p_odom += x_.v_odom * dt_s + 0.5 * a_odom * dt_s * dt_s;
    x_.v_odom += a_odom * dt_s;
    const Eigen::Quaterniond q(Matrix3d(x_.R_odom_body * so3_exp(dt_s * w)));
    x_.R_odom_body = q.normalized().toRotationMatrix();
    stamp_s_ += dt_s;
}

void LocalEkf::propagate_covariance(double dt_s, const Vector3d& a_body, bool gap) {
    const Matrix3d& R = x_.R_odom_body;
    const Matrix3d Ra = hat(R * a_body);
    const double dt2 = dt_s * dt_s;
    CoreMatrix F = CoreMatrix::Identity();
    F.block<3, 3>(kP, kV) = Matrix3d::Identity() * dt_s;
    F.block<3, 3>(kP, kTheta) = -0.5 * Ra * dt2;
    F.block<3, 3>(kP, kBa) = -0.5 * R * dt2;
    F.block<3, 3>(kV, kTheta) = -Ra * dt_s;
    F.block<3, 3>(kV, kBa) = -R * dt_s;
    F.block<3, 3>(kTheta, kBg) = -R * dt_s;
    const LocalEkfConfig& c = config_;
    const double gap_a = gap ? c.gap_acceleration_sigma_mps2 : 0.0;
    const double gap_w = gap ? c.gap_angular_rate_sigma_radps : 0.0;
    CoreMatrix Q = CoreMatrix::Zero();
    set_diagonal(Q, kV,
                 (std::pow(c.accel_noise_density_mps2_per_sqrt_hz, 2) + gap_a * gap_a) * dt_s);
    set_diagonal(Q, kTheta,
                 (std::pow(c.gyro_noise_density_radps_per_sqrt_hz, 2) + gap_w * gap_w) * dt_s);
    set_diagonal(Q, kBa, std::pow(c.accel_bias_random_walk_mps3_per_sqrt_hz, 2) * dt_s);
    set_diagonal(Q, kBg, std::pow(c.gyro_bias_random_walk_radps2_per_sqrt_hz, 2) * dt_s);
    if (barometer_initialized_)
        Q(kBaro, kBaro) = std::pow(c.barometer_bias_random_walk_m_per_sqrt_s, 2) * dt_s;
    // The clone does not move: only the core block and its cross terms change.
    P_.topLeftCorner<kCoreDim, kCoreDim>() =
        F * P_.topLeftCorner<kCoreDim, kCoreDim>() * F.transpose() + Q;
    P_.topRightCorner<kCoreDim, 6>() = F * P_.topRightCorner<kCoreDim, 6>();
    P_.bottomLeftCorner<6, kCoreDim>() = P_.topRightCorner<kCoreDim, 6>().transpose();
}

UpdateResult LocalEkf::correct(const Eigen::MatrixXd& H, const Eigen::VectorXd& residual,
                               const Eigen::MatrixXd& noise, double gate_chi2) {
    const Eigen::MatrixXd PHt = P_ * H.transpose();
    const Eigen::MatrixXd S = H * PHt + noise;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(S);
    UpdateResult result;
    result.dof = static_cast<int>(residual.size());
    result.mahalanobis_squared = residual.dot(ldlt.solve(residual));
    // A NaN χ² (degenerate S) fails the comparison and is rejected like an outlier.
    if (!(result.mahalanobis_squared <= gate_chi2)) {
        result.status = UpdateStatus::kRejected;
        return result;
    }
    const Eigen::MatrixXd K = ldlt.solve(PHt.transpose()).transpose();
    const StateMatrix IKH = StateMatrix::Identity() - K * H;
    // Joseph form: stays symmetric positive semi-definite with a suboptimal or rounded gain.
    P_ = IKH * P_ * IKH.transpose() + K * noise * K.transpose();
    P_ = 0.5 * (P_ + P_.transpose()).eval();
    inject(K * residual);
    result.status = UpdateStatus::kApplied;
    return result;
}

void LocalEkf::inject(const Eigen::Matrix<double, kStateDim, 1>& dx) {
    x_.p_odom += dx.segment<3>(kP);
    x_.R_odom_body = so3_exp(dx.segment<3>(kTheta)) * x_.R_odom_body;
    x_.v_odom += dx.segment<3>(kV);
    x_.accel_bias += dx.segment<3>(kBa);
    x_.gyro_bias += dx.segment<3>(kBg);
    x_.barometer_bias_m += dx(kBaro);
    x_.clone_p_odom += dx.segment<3>(kCloneP);
    x_.clone_R_odom_body = so3_exp(dx.segment<3>(kCloneTheta)) * x_.clone_R_odom_body;
}

DroneState LocalEkf::state() const {
    DroneState s;
    s.stamp_s = stamp_s_;
    s.T_odom_body = make_isometry(x_.R_odom_body, x_.p_odom);
    s.v_odom_mps = x_.v_odom;
    s.a_odom_mps2 = x_.R_odom_body * (held_.specific_force_mps2 - x_.accel_bias) +
                    Vector3d(0.0, 0.0, -config_.gravity_mps2);
    s.omega_body_radps = held_.angular_rate_radps - x_.gyro_bias;
    s.accel_bias_mps2 = x_.accel_bias;
    s.gyro_bias_radps = x_.gyro_bias;
    s.covariance = P_.topLeftCorner<9, 9>();  // δp, δθ, δv lead the layout
    return s;
}

}  // namespace scantling::localization
