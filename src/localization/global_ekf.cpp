// The global EKF: T_world_odom's drift, UWB ranges and position fixes (global_ekf.hpp).
#include "scantling/localization/global_ekf.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include <fmt/format.h>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>

#include "detail/config_checks.hpp"

namespace scantling::localization {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

using Matrix97 = Eigen::Matrix<double, 9, 7>;
using Matrix7d = Eigen::Matrix<double, 7, 7>;
using Vector7d = Eigen::Matrix<double, 7, 1>;

Matrix3d yaw_rotation(double yaw_rad) {
    return Eigen::AngleAxisd(yaw_rad, Vector3d::UnitZ()).toRotationMatrix();
}

/// The positive part of a symmetric matrix (a covariance growth, never a shrink).
Matrix3d positive_part(const Matrix3d& M) {
    const Eigen::SelfAdjointEigenSolver<Matrix3d> solver(0.5 * (M + M.transpose()));
    const Vector3d lambda = solver.eigenvalues().cwiseMax(0.0);
    return solver.eigenvectors() * lambda.asDiagonal() * solver.eigenvectors().transpose();
}

/// ∂(world point)/∂(δt, δψ, δd) for a point q with the yaw pivot at c (the drift velocity d
/// moves no point at the current instant).
Eigen::Matrix<double, 3, 7> point_jacobian(const Vector3d& q_world, const Vector3d& c_world) {
    Eigen::Matrix<double, 3, 7> J = Eigen::Matrix<double, 3, 7>::Zero();
    J.leftCols<3>().setIdentity();
    J.col(3) = Vector3d::UnitZ().cross(q_world - c_world);
    return J;
}

void require_finite_state(const DroneState& s) {
    if (!std::isfinite(s.stamp_s) || !s.T_odom_body.matrix().allFinite() ||
        !s.v_odom_mps.allFinite() || !s.a_odom_mps2.allFinite() || !s.covariance.allFinite())
        throw InputError(fmt::format("global_ekf: local state at {} s is not finite", s.stamp_s));
}

}  // namespace

void GlobalEkfConfig::validate(std::string_view prefix) const {
    for (const auto& [id, p_world_m] : uwb_anchors_world_m) {
        detail::require(p_world_m.allFinite(), prefix, fmt::format("uwb_anchors_world_m[{}]", id),
                        p_world_m.norm(), "finite");
    }
    detail::require(p_body_uwb_tag_m.allFinite(), prefix, "p_body_uwb_tag_m",
                    p_body_uwb_tag_m.norm(), "finite");
    detail::require_positive(uwb_range_sigma_m, prefix, "uwb_range_sigma_m");
    detail::require_positive(uwb_gate_chi2, prefix, "uwb_gate_chi2");
    detail::require_positive(position_fix_gate_chi2, prefix, "position_fix_gate_chi2");
    detail::require_non_negative(translation_random_walk_m_per_sqrt_s, prefix,
                                 "translation_random_walk_m_per_sqrt_s");
    detail::require_non_negative(yaw_random_walk_rad_per_sqrt_s, prefix,
                                 "yaw_random_walk_rad_per_sqrt_s");
    detail::require_non_negative(initial_translation_sigma_m, prefix,
                                 "initial_translation_sigma_m");
    detail::require_non_negative(initial_yaw_sigma_rad, prefix, "initial_yaw_sigma_rad");
    detail::require_positive(max_local_age_s, prefix, "max_local_age_s");
    detail::require_positive(reacquire_translation_sigma_m, prefix,
                             "reacquire_translation_sigma_m");
    detail::require_non_negative(reacquire_yaw_sigma_rad, prefix, "reacquire_yaw_sigma_rad");
    detail::require_non_negative(reacquire_drift_velocity_sigma_mps, prefix,
                                 "reacquire_drift_velocity_sigma_mps");
    detail::require_non_negative(drift_velocity_random_walk_mps_per_sqrt_s, prefix,
                                 "drift_velocity_random_walk_mps_per_sqrt_s");
    detail::require_non_negative(initial_drift_velocity_sigma_mps, prefix,
                                 "initial_drift_velocity_sigma_mps");
    detail::require(uwb_reacquire_min_anchors >= 1, prefix, "uwb_reacquire_min_anchors",
                    static_cast<double>(uwb_reacquire_min_anchors), ">= 1");
    detail::require(uwb_reacquire_fraction > 0.0 && uwb_reacquire_fraction <= 1.0, prefix,
                    "uwb_reacquire_fraction", uwb_reacquire_fraction, "in (0, 1]");
}

GlobalEkf::GlobalEkf(GlobalEkfConfig config, const Eigen::Isometry3d& T_world_odom)
    : config_(std::move(config)) {
    config_.validate();
    if (!T_world_odom.matrix().allFinite())
        throw InputError("global_ekf: the initial T_world_odom is not finite");
    t_world_odom_ = T_world_odom.translation();
    yaw_rad_ = euler_zyx_from_rotation(T_world_odom.linear()).z();
    c_world_ = t_world_odom_;  // the initial yaw uncertainty is about the odom origin
    P_.diagonal() << Vector3d::Constant(std::pow(config_.initial_translation_sigma_m, 2)),
        std::pow(config_.initial_yaw_sigma_rad, 2),
        Vector3d::Constant(std::pow(config_.initial_drift_velocity_sigma_mps, 2));
}

Eigen::Isometry3d GlobalEkf::T_world_odom() const {
    return make_isometry(yaw_rotation(yaw_rad_), t_world_odom_);
}

bool GlobalEkf::add_local(const DroneState& local) {
    require_finite_state(local);
    if (local_ && local.stamp_s < local_->stamp_s) return false;
    predict(local);
    local_ = local;
    ++counters_.local_states;
    return true;
}

void GlobalEkf::predict(const DroneState& local) {
    const Matrix3d R = yaw_rotation(yaw_rad_);
    const Vector3d c_next = R * local.T_odom_body.translation() + t_world_odom_;
    const double dt_s = local_ ? std::max(0.0, local.stamp_s - local_->stamp_s) : 0.0;
    Matrix7d F = Matrix7d::Identity();
    F.block<3, 1>(0, 3) = Vector3d::UnitZ().cross(c_next - c_world_);  // move the yaw pivot
    F.block<3, 3>(0, 4) = dt_s * Matrix3d::Identity();                 // t += d dt
    Matrix7d Q = Matrix7d::Zero();
    if (local_) {
        const Matrix3d growth =
            local.covariance.topLeftCorner<3, 3>() - local_->covariance.topLeftCorner<3, 3>();
        Q.topLeftCorner<3, 3>() = R * positive_part(growth) * R.transpose();
        Q.topLeftCorner<3, 3>().diagonal().array() +=
            std::pow(config_.translation_random_walk_m_per_sqrt_s, 2) * dt_s;
        Q(3, 3) = std::max(0.0, local.covariance(5, 5) - local_->covariance(5, 5)) +
                  std::pow(config_.yaw_random_walk_rad_per_sqrt_s, 2) * dt_s;
        Q.bottomRightCorner<3, 3>().diagonal().setConstant(
            std::pow(config_.drift_velocity_random_walk_mps_per_sqrt_s, 2) * dt_s);
    }
    t_world_odom_ += drift_velocity_mps_ * dt_s;
    P_ = F * P_ * F.transpose() + Q;
    c_world_ = c_next;
}

std::optional<Vector3d> GlobalEkf::local_position_at(double stamp_s,
                                                     const Vector3d& lever_body) const {
    if (!local_) return std::nullopt;
    const double dt_s = stamp_s - local_->stamp_s;
    if (std::abs(dt_s) > config_.max_local_age_s) return std::nullopt;
    return local_->T_odom_body.translation() + local_->v_odom_mps * dt_s +
           local_->T_odom_body.linear() * lever_body;
}

UpdateResult GlobalEkf::correct(const Eigen::MatrixXd& H, const Eigen::VectorXd& residual,
                                const Eigen::MatrixXd& noise, double gate_chi2) {
    const Eigen::MatrixXd PHt = P_ * H.transpose();
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(H * PHt + noise);
    UpdateResult result{UpdateStatus::kRejected, residual.dot(ldlt.solve(residual)),
                        static_cast<int>(residual.size())};
    if (!(result.mahalanobis_squared <= gate_chi2)) return result;
    const Eigen::MatrixXd K = ldlt.solve(PHt.transpose()).transpose();
    const Matrix7d IKH = Matrix7d::Identity() - K * H;
    P_ = IKH * P_ * IKH.transpose() + K * noise * K.transpose();
    P_ = 0.5 * (P_ + P_.transpose()).eval();
    const Vector7d dx = K * residual;
    drift_velocity_mps_ += dx.tail<3>();
    // q_true = c + R_z(δψ)(q − c) + δt for every point q of the odom frame.
    const Matrix3d dR = yaw_rotation(dx(3));
    t_world_odom_ = c_world_ + dR * (t_world_odom_ - c_world_) + dx.head<3>();
    yaw_rad_ = std::remainder(yaw_rad_ + dx(3), 2.0 * std::numbers::pi);
    result.status = UpdateStatus::kApplied;
    return result;
}

UpdateResult GlobalEkf::update_uwb(const io::UwbRecord& range) {
    if (!range.valid) return UpdateResult{UpdateStatus::kInvalid, 0.0, 0};
    if (!std::isfinite(range.stamp_s) || !std::isfinite(range.range_m))
        throw InputError(fmt::format("global_ekf: UWB range at {} s is not finite", range.stamp_s));
    const auto anchor = config_.uwb_anchors_world_m.find(range.anchor_id);
    if (anchor == config_.uwb_anchors_world_m.end())
        return UpdateResult{UpdateStatus::kUnknownAnchor, 0.0, 0};
    const auto tag_odom = local_position_at(range.stamp_s, config_.p_body_uwb_tag_m);
    if (!tag_odom) return UpdateResult{UpdateStatus::kNoLocal, 0.0, 0};
    const Vector3d tag_world = yaw_rotation(yaw_rad_) * *tag_odom + t_world_odom_;
    const Vector3d diff = tag_world - anchor->second;
    const double distance_m = diff.norm();
    if (distance_m < 1e-6) return UpdateResult{UpdateStatus::kInvalid, 0.0, 0};
    const Eigen::MatrixXd H = (diff / distance_m).transpose() * point_jacobian(tag_world, c_world_);
    const double residual_m = range.range_m - distance_m;
    const UpdateResult result =
        correct(H, Eigen::VectorXd::Constant(1, residual_m),
                Eigen::MatrixXd::Constant(1, 1, std::pow(config_.uwb_range_sigma_m, 2)),
                config_.uwb_gate_chi2);
    ++(result.status == UpdateStatus::kApplied ? counters_.uwb_applied : counters_.uwb_rejected);
    track_refusals(result.status == UpdateStatus::kApplied, range.anchor_id, residual_m);
    return result;
}

void GlobalEkf::track_refusals(bool applied, int anchor_id, double residual_m) {
    if (config_.uwb_reacquire_window == 0) return;
    recent_ranges_.push_back({anchor_id, !applied, residual_m});
    if (recent_ranges_.size() > config_.uwb_reacquire_window) recent_ranges_.pop_front();
    if (recent_ranges_.size() < config_.uwb_reacquire_window) return;
    std::vector<int> anchors;
    double sum_sq = 0.0;
    std::size_t refused = 0;
    for (const RangeOutcome& r : recent_ranges_) {
        if (!r.refused) continue;
        ++refused;
        sum_sq += r.residual_m * r.residual_m;
        if (std::find(anchors.begin(), anchors.end(), r.anchor_id) == anchors.end())
            anchors.push_back(r.anchor_id);
    }
    if (static_cast<double>(refused) < config_.uwb_reacquire_fraction * recent_ranges_.size() ||
        anchors.size() < config_.uwb_reacquire_min_anchors) {
        return;
    }
    const double sigma_m = std::max(config_.reacquire_translation_sigma_m,
                                    2.0 * std::sqrt(sum_sq / static_cast<double>(refused)));
    P_.topLeftCorner<3, 3>() += sigma_m * sigma_m * Matrix3d::Identity();
    P_(3, 3) += config_.reacquire_yaw_sigma_rad * config_.reacquire_yaw_sigma_rad;
    P_.bottomRightCorner<3, 3>().diagonal().array() +=
        std::pow(config_.reacquire_drift_velocity_sigma_mps, 2);
    ++counters_.uwb_reacquisitions;
    recent_ranges_.clear();
}

UpdateResult GlobalEkf::update_position(const PositionFix& fix) {
    const Eigen::LLT<Matrix3d> llt(fix.covariance);
    if (!std::isfinite(fix.stamp_s) || !fix.p_world_m.allFinite() || !fix.covariance.allFinite() ||
        llt.info() != Eigen::Success)
        throw InputError(fmt::format(
            "global_ekf: position fix at {} s is not finite or its covariance not positive "
            "definite",
            fix.stamp_s));
    const auto p_odom = local_position_at(fix.stamp_s, Vector3d::Zero());
    if (!p_odom) return UpdateResult{UpdateStatus::kNoLocal, 0.0, 0};
    const Vector3d p_world = yaw_rotation(yaw_rad_) * *p_odom + t_world_odom_;
    const UpdateResult result = correct(point_jacobian(p_world, c_world_), fix.p_world_m - p_world,
                                        fix.covariance, config_.position_fix_gate_chi2);
    ++(result.status == UpdateStatus::kApplied ? counters_.fixes_applied
                                               : counters_.fixes_rejected);
    return result;
}

DroneState GlobalEkf::state() const {
    DroneState world = local_.value_or(DroneState{});
    const Matrix3d R = yaw_rotation(yaw_rad_);
    world.T_odom_body = T_world_odom() * world.T_odom_body;
    // The body's world velocity: the local one turned into the world, plus the odom frame's
    // drift (what the local filter gets wrong along directions it cannot observe).
    const Vector3d v_local_world = R * world.v_odom_mps;
    world.v_odom_mps = v_local_world + drift_velocity_mps_;
    world.a_odom_mps2 = R * world.a_odom_mps2;
    Matrix97 Jg = Matrix97::Zero();
    Jg.topRows<3>() = point_jacobian(world.T_odom_body.translation(), c_world_);
    Jg(5, 3) = 1.0;
    Jg.block<3, 1>(6, 3) = Vector3d::UnitZ().cross(v_local_world);
    Jg.block<3, 3>(6, 4) = Matrix3d::Identity();
    // The local's position and yaw drift are in P_g (see the file comment): keep its tilt and
    // velocity only.
    Matrix9d Jl = Matrix9d::Zero();
    Jl.block<3, 3>(3, 3) = R * Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal();
    Jl.block<3, 3>(6, 6) = R;
    const Matrix9d P_local = local_ ? local_->covariance : Matrix9d::Zero();
    world.covariance = Jg * P_ * Jg.transpose() + Jl * P_local * Jl.transpose();
    return world;
}

}  // namespace scantling::localization
