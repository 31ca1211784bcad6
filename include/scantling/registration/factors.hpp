#pragma once
/// @file
/// Residuals and analytic Jacobians of one correspondence for the ICP family.
///
/// Notation: `p` a source point, `q = T_target_source * p` the same point in the target frame,
/// `t` its corresponding target point. All Jacobians are with respect to the LEFT perturbation
/// in the target frame, `T ← se3_exp(delta) * T` with delta = (rho, omega):
/// `d q / d delta = [I, −hat(q)]` at delta = 0. Solving in the target frame makes the Hessian
/// (and hence the information matrix) a target-frame quantity.
///
/// Inline because they run once per correspondence per iteration. Pure and thread-safe; each
/// Jacobian is checked against central differences in tests/registration/factors_test.cpp.

#include <Eigen/Core>
#include <Eigen/LU>

#include <scantling/core/se3.hpp>

namespace scantling::registration {

using Matrix36d = Eigen::Matrix<double, 3, 6>;
using RowVector6d = Eigen::Matrix<double, 1, 6>;

/// Point-to-point residual q − t (metres).
inline Eigen::Vector3d point_to_point_residual(const Eigen::Vector3d& q, const Eigen::Vector3d& t) {
    return q - t;
}

/// d(q − t)/d delta = [I, −hat(q)].
inline Matrix36d point_to_point_jacobian(const Eigen::Vector3d& q) {
    Matrix36d J;
    J.leftCols<3>().setIdentity();
    J.rightCols<3>() = -hat(q);
    return J;
}

/// Point-to-plane residual n · (q − t): signed distance to the target's tangent plane, metres.
/// `n_target` is the target point's unit normal (its sign does not matter for the cost).
inline double point_to_plane_residual(const Eigen::Vector3d& q, const Eigen::Vector3d& t,
                                      const Eigen::Vector3d& n_target) {
    return n_target.dot(q - t);
}

/// d(n · (q − t))/d delta = [nᵀ, (q × n)ᵀ].
inline RowVector6d point_to_plane_jacobian(const Eigen::Vector3d& q,
                                           const Eigen::Vector3d& n_target) {
    RowVector6d J;
    J.leftCols<3>() = n_target.transpose();
    J.rightCols<3>() = q.cross(n_target).transpose();
    return J;
}

/// GICP (Segal et al. 2009) weight Ω = (C_t + R C_s Rᵀ)⁻¹ for the residual q − t, with C_s the
/// source point's covariance in the source frame and R the rotation of T_target_source. The
/// cost is (q − t)ᵀ Ω (q − t); its Jacobian is point_to_point_jacobian(q). As in the paper and
/// in small_gicp, Ω is held fixed within one linearisation (its dependence on R is dropped).
inline Eigen::Matrix3d gicp_weight(const Eigen::Matrix3d& C_target, const Eigen::Matrix3d& C_source,
                                   const Eigen::Matrix3d& R_target_source) {
    const Eigen::Matrix3d C = C_target + R_target_source * C_source * R_target_source.transpose();
    return C.inverse();
}

}  // namespace scantling::registration
