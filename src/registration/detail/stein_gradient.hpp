#pragma once
/// @file
/// Gradient of the ICP cost with respect to the Euler parametrisation of a Stein-ICP particle
/// (private; stein_icp.hpp documents the parametrisation).

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/icp.hpp>

namespace scantling::registration::detail {

/// A particle's rotation factors, kept to differentiate R = R_z R_y R_x cheaply.
struct EulerPose {
    Eigen::Matrix3d R_x, R_y, R_z, R;
    Eigen::Vector3d t;
};

/// Factors of the particle (x, y, z, roll, pitch, yaw).
EulerPose make_euler_pose(const Vector6d& params);

/// d(e²)/d(params) for e = n·(R p + t − q) (point-to-plane, `normal` non-null) or
/// e = |R p + t − q| (point-to-point).
Vector6d residual_sq_gradient(const EulerPose& pose, const Eigen::Vector3d& p_source,
                              const Eigen::Vector3d& q_target, const Eigen::Vector3d* normal);

/// Gauss-Newton information Jᵀ J of the same residual (J = d e / d params, 1 × 6 or 3 × 6):
/// the curvature of e² / 2 about a fit.
Matrix6d residual_information(const EulerPose& pose, const Eigen::Vector3d& p_source,
                              const Eigen::Vector3d* normal);

/// Sum (and sum of outer products) of residual_sq_gradient and sum of residual_information over the
/// source points at `indices` whose nearest target point lies within `max_distance_m`, and how many
/// did. `back_faces` as in IcpConfig, the sensor at the source frame's origin (only with
/// `target_normals`).
struct BatchGradient {
    Vector6d sum = Vector6d::Zero();
    Matrix6d sum_outer = Matrix6d::Zero();  ///< Σ g gᵀ of the per-point gradients g
    Matrix6d information = Matrix6d::Zero();
    std::size_t num_inliers = 0;
};

BatchGradient batch_gradient(const Vector6d& params, std::span<const Eigen::Vector3d> source,
                             std::span<const std::size_t> indices, const KdTree& target_tree,
                             std::span<const Eigen::Vector3d> target_normals, double max_distance_m,
                             BackFaces back_faces);

}  // namespace scantling::registration::detail
