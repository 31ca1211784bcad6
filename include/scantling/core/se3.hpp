#pragma once
/// @file
/// SO(3)/SE(3) helpers on Eigen types: exponential and logarithm maps, Jacobians, adjoint,
/// interpolation, Euler angles, rotation averaging and pose errors.
///
/// Conventions used throughout:
/// - Rotation vectors `omega_rad` are axis × angle in radians; `hat(omega_rad)` is the skew
///   matrix with `hat(a) * b == a.cross(b)`.
/// - Twists are `Vector6d xi = (rho, omega)`: translation part first (metres), rotation part
///   last (radians). `se3_exp(xi)` has rotation `so3_exp(omega)` and translation
///   `so3_left_jacobian(omega) * rho`.
/// - Perturbations: `exp(omega + delta) ≈ exp(J_l(omega) delta) exp(omega)` (left Jacobian)
///   and `exp(omega + delta) ≈ exp(omega) exp(J_r(omega) delta)` (right Jacobian).
/// - Transforms are named `T_to_from`: `p_world = T_world_body * p_body`.
///
/// All functions are pure, thread-safe and deterministic; every function is O(1) except
/// `average_rotations` (O(n)).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>

namespace scantling {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Skew-symmetric matrix of `v`: `hat(v) * w == v.cross(w)`.
Eigen::Matrix3d hat(const Eigen::Vector3d& v);

/// Inverse of `hat`: reads (S(2,1), S(0,2), S(1,0)); the symmetric part of `S` is ignored.
Eigen::Vector3d vee(const Eigen::Matrix3d& S);

/// Rotation matrix of the rotation vector `omega_rad` (Rodrigues). Accurate to machine
/// precision for any angle, including |omega| < 1e-9 (Taylor series near zero).
Eigen::Matrix3d so3_exp(const Eigen::Vector3d& omega_rad);

/// Rotation vector of `R` with angle in [0, π]. `R` must be a rotation matrix (call
/// `orthonormalize` first on noisy input). Robust near 0 and near π, where the axis is read
/// from the symmetric part of `R`; at exactly π either sign of the axis may be returned.
Eigen::Vector3d so3_log(const Eigen::Matrix3d& R);

/// Left Jacobian of SO(3): `so3_exp(omega + d) ≈ so3_exp(J_l d) * so3_exp(omega)`.
Eigen::Matrix3d so3_left_jacobian(const Eigen::Vector3d& omega_rad);

/// Inverse of the left Jacobian; defined for |omega| < 2π (singular at 2π).
Eigen::Matrix3d so3_left_jacobian_inverse(const Eigen::Vector3d& omega_rad);

/// Right Jacobian of SO(3): `so3_exp(omega + d) ≈ so3_exp(omega) * so3_exp(J_r d)`.
/// Equals `so3_left_jacobian(-omega)`.
Eigen::Matrix3d so3_right_jacobian(const Eigen::Vector3d& omega_rad);

/// Inverse of the right Jacobian; defined for |omega| < 2π.
Eigen::Matrix3d so3_right_jacobian_inverse(const Eigen::Vector3d& omega_rad);

/// Rigid transform of the twist `xi = (rho [m], omega [rad])`.
Eigen::Isometry3d se3_exp(const Vector6d& xi);

/// Twist `(rho, omega)` of `T`, with |omega| in [0, π]; inverse of `se3_exp`.
Vector6d se3_log(const Eigen::Isometry3d& T);

/// Adjoint of `T_a_b` for the (rho, omega) ordering, [[R, hat(t) R], [0, R]]:
/// `T_a_b * se3_exp(xi_b) * T_a_b.inverse() == se3_exp(se3_adjoint(T_a_b) * xi_b)`.
Matrix6d se3_adjoint(const Eigen::Isometry3d& T_a_b);

/// Pose at fraction `t` between `T_w_a` (t = 0) and `T_w_b` (t = 1): rotation by slerp
/// (`R_a exp(t log(R_aᵀ R_b))`), translation linear. Values outside [0, 1] extrapolate.
/// When the relative rotation is exactly π the rotation direction is arbitrary.
Eigen::Isometry3d interpolate(const Eigen::Isometry3d& T_w_a, const Eigen::Isometry3d& T_w_b,
                              double t);

/// Pose at fraction `t` along the SE(3) geodesic: `T_w_a * se3_exp(t * se3_log(T_a_b))`.
/// Rotation as `interpolate`; the translation follows a screw motion instead of a line.
Eigen::Isometry3d interpolate_geodesic(const Eigen::Isometry3d& T_w_a,
                                       const Eigen::Isometry3d& T_w_b, double t);

/// `R = R_z(yaw) * R_y(pitch) * R_x(roll)` (intrinsic Z-Y'-X'', as used for vehicle attitude).
Eigen::Matrix3d rotation_from_euler_zyx(double roll_rad, double pitch_rad, double yaw_rad);

/// (roll, pitch, yaw) in radians with `R = R_z(yaw) R_y(pitch) R_x(roll)`, roll and yaw in
/// [-π, π], pitch in [-π/2, π/2]. At gimbal lock (|pitch| = π/2, where only yaw ∓ roll is
/// observable) roll is set to 0 and the whole rotation about z is reported as yaw.
Eigen::Vector3d euler_zyx_from_rotation(const Eigen::Matrix3d& R);

/// Weighted mean rotation: the chordal L2 mean (SVD projection of Σ wᵢ Rᵢ onto SO(3)) refined
/// by a few Karcher (geodesic L2) iterations. `weights` empty = all equal; otherwise one per
/// rotation, each finite and >= 0, with a positive sum. Throws InputError on empty input,
/// mismatched or bad weights, or a non-finite rotation. Meaningful when the rotations lie
/// within a ball of radius < π/2 (the usual case for noisy estimates of one rotation).
Eigen::Matrix3d average_rotations(std::span<const Eigen::Matrix3d> rotations,
                                  std::span<const double> weights = {});

/// Rigid transform with rotation `R` and translation `t`.
Eigen::Isometry3d make_isometry(const Eigen::Matrix3d& R, const Eigen::Vector3d& t);

/// Nearest rotation to `M` in the Frobenius norm (SVD, determinant forced to +1).
Eigen::Matrix3d orthonormalize(const Eigen::Matrix3d& M);

/// Rotation angle of `R` in [0, π] (atan2 form: accurate at small angles and near π).
double rotation_angle_rad(const Eigen::Matrix3d& R);

/// Difference between two poses of the same body expressed in the same frame.
struct PoseError {
    double translation_m = 0.0;  ///< |t_a - t_b|, distance between the two positions
    double rotation_rad = 0.0;   ///< angle of R_aᵀ R_b, in [0, π]
};

/// Position and attitude difference between `T_w_a` and `T_w_b` (symmetric in a and b).
PoseError pose_error(const Eigen::Isometry3d& T_w_a, const Eigen::Isometry3d& T_w_b);

}  // namespace scantling
