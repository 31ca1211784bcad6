#pragma once
/// @file
/// Closed-form least-squares fits of rotations and rigid motions (Horn 1987 / Arun 1987 SVD),
/// private to registration. Spans of equal length; weights empty = all 1.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>

namespace scantling::registration::detail {

/// R minimising Σ w_k |target_k − R source_k|² over rotations (vectors, no translation).
/// Degenerate input (all weights or vectors zero) gives the identity.
Eigen::Matrix3d fit_rotation(std::span<const Eigen::Vector3d> source,
                             std::span<const Eigen::Vector3d> target,
                             std::span<const double> weights = {});

/// Yaw (rotation angle about z, radians) minimising the same over rotations about z:
/// atan2(Σ w (s_x t_y − s_y t_x), Σ w (s_x t_x + s_y t_y)).
double fit_yaw(std::span<const Eigen::Vector3d> source, std::span<const Eigen::Vector3d> target,
               std::span<const double> weights = {});

/// Rotation about z by `yaw_rad`.
Eigen::Matrix3d yaw_rotation(double yaw_rad);

/// T minimising Σ |target_k − T source_k|², T rigid (yaw_only: rotation about z only). Needs at
/// least one pair.
Eigen::Isometry3d fit_rigid(std::span<const Eigen::Vector3d> source,
                            std::span<const Eigen::Vector3d> target, bool yaw_only);

/// Standard deviation of `points` along their second principal axis, metres (horizontal: the
/// largest standard deviation of their x-y coordinates). Rotations are fixed by point sets only
/// when it exceeds the noise: below, the points are (nearly) collinear or coincident (for
/// `horizontal`, stacked on one vertical line). Empty input gives 0.
double principal_spread_m(std::span<const Eigen::Vector3d> points, bool horizontal);

}  // namespace scantling::registration::detail
