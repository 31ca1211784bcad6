#pragma once
// The models and the EKF/UKF algebra of PoseFilter (pose_filter.hpp), as pure functions.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <scantling/core/se3.hpp>
#include <scantling/localization/pose_filter.hpp>

namespace scantling::localization::detail {

/// kDropout for an invalid sample, kJump for a step faster than `max_speed_mps`, else kOk.
OdometryStatus classify_step(const io::VioRecord& from, const io::VioRecord& to,
                             double max_speed_mps);

/// Covariance added to the drift's left twist by the step from `from` to `to`; the yaw acts
/// about `c_world` (the body's estimated position).
Matrix6d process_noise(const PoseFilterConfig& config, const io::VioRecord& from,
                       const io::VioRecord& to, OdometryStatus status,
                       const Eigen::Vector3d& c_world);

/// State correction (left twist applied to the drift) and the posterior covariance.
struct Correction {
    Vector6d delta = Vector6d::Zero();
    Matrix6d covariance = Matrix6d::Zero();
};

/// First order: the residual log(Z · B⁻¹) = ξ + n.
Innovation ekf_innovation(const Matrix6d& P, const Matrix6d& R, const Eigen::Isometry3d& B,
                          const Eigen::Isometry3d& Z);
Correction ekf_correction(const Matrix6d& P, const Matrix6d& R, const Eigen::Isometry3d& B,
                          const Eigen::Isometry3d& Z);

struct UnscentedInnovation {
    Innovation innovation;
    Matrix6d cross_covariance = Matrix6d::Zero();  ///< of state error and residual
};
/// Sigma points of (ξ, n) through log(exp(n) · exp(ξ)).
UnscentedInnovation ukf_innovation(const Matrix6d& P, const Matrix6d& R, const Eigen::Isometry3d& B,
                                   const Eigen::Isometry3d& Z, const PoseFilterConfig& config);
Correction ukf_correction(const Matrix6d& P, const Matrix6d& R, const Eigen::Isometry3d& B,
                          const Eigen::Isometry3d& Z, const PoseFilterConfig& config);

}  // namespace scantling::localization::detail
