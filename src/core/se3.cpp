#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>

#include <fmt/format.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace scantling {
namespace {

// Below this angle the closed-form coefficients lose digits to cancellation (error ~ eps/θ²);
// their Taylor series truncated after θ⁴ is exact to < 1e-17 here.
constexpr double kSeriesAngleRad = 1e-2;
// Beyond this angle sin θ is too small to read the axis from the antisymmetric part of R.
constexpr double kNearPiAngleRad = 3.0;
constexpr int kKarcherIterations = 10;
constexpr double kKarcherStepTolRad = 1e-14;

struct SinCos {
    double theta;  // rotation angle in [0, π]
    double sin_theta;
    double cos_theta;
};

SinCos angle_of(const Eigen::Matrix3d& R) {
    const double s = 0.5 * vee(R - R.transpose()).norm();
    const double c = std::clamp(0.5 * (R.trace() - 1.0), -1.0, 1.0);
    return {std::atan2(s, c), s, c};
}

// (1 - cos θ)/θ² and (θ - sin θ)/θ³, the coefficients of hat(ω) and hat(ω)² in J_l.
std::pair<double, double> left_jacobian_coefficients(double theta) {
    const double t2 = theta * theta;
    if (theta < kSeriesAngleRad) {
        return {0.5 - t2 / 24.0 + t2 * t2 / 720.0, 1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0};
    }
    const double half_sin = std::sin(0.5 * theta);
    return {2.0 * half_sin * half_sin / t2, (theta - std::sin(theta)) / (t2 * theta)};
}

// The axis of a rotation by θ near π, from (R + Rᵀ)/2 = cos θ I + (1 - cos θ) a aᵀ.
Eigen::Vector3d axis_near_pi(const Eigen::Matrix3d& R, const SinCos& angle) {
    const Eigen::Matrix3d outer =
        (0.5 * (R + R.transpose()) - angle.cos_theta * Eigen::Matrix3d::Identity()) /
        (1.0 - angle.cos_theta);
    Eigen::Index k = 0;
    outer.diagonal().maxCoeff(&k);
    Eigen::Vector3d axis = outer.col(k) / std::sqrt(std::max(outer(k, k), 0.0));
    // The antisymmetric part 2 sin θ a fixes the sign (θ < π: the two signs differ).
    if (axis.dot(vee(R - R.transpose())) < 0.0) axis = -axis;
    return axis.normalized();
}

void check_weights(std::span<const Eigen::Matrix3d> rotations, std::span<const double> weights) {
    if (rotations.empty()) throw InputError("average_rotations: no rotations given");
    if (!weights.empty() && weights.size() != rotations.size()) {
        throw InputError(fmt::format("average_rotations: {} weights for {} rotations",
                                     weights.size(), rotations.size()));
    }
    double sum = 0.0;
    for (std::size_t i = 0; i < weights.size(); ++i) {
        if (!std::isfinite(weights[i]) || weights[i] < 0.0) {
            throw InputError(fmt::format("average_rotations: weight {} = {}, expected finite >= 0",
                                         i, weights[i]));
        }
        sum += weights[i];
    }
    if (!weights.empty() && !(sum > 0.0)) {
        throw InputError("average_rotations: weights sum to 0, expected a positive sum");
    }
    for (std::size_t i = 0; i < rotations.size(); ++i) {
        if (!rotations[i].allFinite()) {
            throw InputError(fmt::format("average_rotations: rotation {} is not finite", i));
        }
    }
}

double weight_at(std::span<const double> weights, std::size_t i) {
    return weights.empty() ? 1.0 : weights[i];
}

}  // namespace

Eigen::Matrix3d hat(const Eigen::Vector3d& v) {
    Eigen::Matrix3d S;
    S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
    return S;
}

Eigen::Vector3d vee(const Eigen::Matrix3d& S) { return {S(2, 1), S(0, 2), S(1, 0)}; }

Eigen::Matrix3d so3_exp(const Eigen::Vector3d& omega_rad) {
    const double theta = omega_rad.norm();
    const Eigen::Matrix3d K = hat(omega_rad);
    double a = 1.0;  // sin θ / θ
    double b = 0.5;  // (1 - cos θ) / θ²
    if (theta < kSeriesAngleRad) {
        const double t2 = theta * theta;
        a = 1.0 - t2 / 6.0 + t2 * t2 / 120.0;
        b = 0.5 - t2 / 24.0 + t2 * t2 / 720.0;
    } else {
        const double half_sin = std::sin(0.5 * theta);
        a = std::sin(theta) / theta;
        b = 2.0 * half_sin * half_sin / (theta * theta);
    }
    return Eigen::Matrix3d::Identity() + a * K + b * K * K;
}

Eigen::Vector3d so3_log(const Eigen::Matrix3d& R) {
    const SinCos angle = angle_of(R);
    if (angle.theta > kNearPiAngleRad) return angle.theta * axis_near_pi(R, angle);
    // θ / (2 sin θ) → 1/2 + θ²/12 as θ → 0.
    const double t2 = angle.theta * angle.theta;
    const double scale = angle.theta < kSeriesAngleRad ? 0.5 + t2 / 12.0 + 7.0 * t2 * t2 / 720.0
                                                       : 0.5 * angle.theta / angle.sin_theta;
    return scale * vee(R - R.transpose());
}

Eigen::Matrix3d so3_left_jacobian(const Eigen::Vector3d& omega_rad) {
    const auto [b, c] = left_jacobian_coefficients(omega_rad.norm());
    const Eigen::Matrix3d K = hat(omega_rad);
    return Eigen::Matrix3d::Identity() + b * K + c * K * K;
}

Eigen::Matrix3d so3_left_jacobian_inverse(const Eigen::Vector3d& omega_rad) {
    const double theta = omega_rad.norm();
    const double t2 = theta * theta;
    // 1/θ² - cot(θ/2)/(2θ), finite at θ = π where the sin θ form is 0/0.
    const double c = theta < kSeriesAngleRad
                         ? 1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0
                         : 1.0 / t2 - std::cos(0.5 * theta) / (2.0 * theta * std::sin(0.5 * theta));
    const Eigen::Matrix3d K = hat(omega_rad);
    return Eigen::Matrix3d::Identity() - 0.5 * K + c * K * K;
}

Eigen::Matrix3d so3_right_jacobian(const Eigen::Vector3d& omega_rad) {
    return so3_left_jacobian(-omega_rad);
}

Eigen::Matrix3d so3_right_jacobian_inverse(const Eigen::Vector3d& omega_rad) {
    return so3_left_jacobian_inverse(-omega_rad);
}

Eigen::Isometry3d se3_exp(const Vector6d& xi) {
    const Eigen::Vector3d rho = xi.head<3>();
    const Eigen::Vector3d omega = xi.tail<3>();
    return make_isometry(so3_exp(omega), so3_left_jacobian(omega) * rho);
}

Vector6d se3_log(const Eigen::Isometry3d& T) {
    const Eigen::Vector3d omega = so3_log(T.linear());
    Vector6d xi;
    xi << so3_left_jacobian_inverse(omega) * T.translation(), omega;
    return xi;
}

Matrix6d se3_adjoint(const Eigen::Isometry3d& T_a_b) {
    const Eigen::Matrix3d R = T_a_b.linear();
    Matrix6d adjoint = Matrix6d::Zero();
    adjoint.topLeftCorner<3, 3>() = R;
    adjoint.topRightCorner<3, 3>() = hat(T_a_b.translation()) * R;
    adjoint.bottomRightCorner<3, 3>() = R;
    return adjoint;
}

Eigen::Isometry3d interpolate(const Eigen::Isometry3d& T_w_a, const Eigen::Isometry3d& T_w_b,
                              double t) {
    const Eigen::Matrix3d R_a_b = T_w_a.linear().transpose() * T_w_b.linear();
    const Eigen::Matrix3d R_w_t = T_w_a.linear() * so3_exp(t * so3_log(R_a_b));
    return make_isometry(R_w_t, (1.0 - t) * T_w_a.translation() + t * T_w_b.translation());
}

Eigen::Isometry3d interpolate_geodesic(const Eigen::Isometry3d& T_w_a,
                                       const Eigen::Isometry3d& T_w_b, double t) {
    const Eigen::Isometry3d T_a_b = T_w_a.inverse() * T_w_b;
    return T_w_a * se3_exp(t * se3_log(T_a_b));
}

Eigen::Matrix3d rotation_from_euler_zyx(double roll_rad, double pitch_rad, double yaw_rad) {
    const Eigen::AngleAxisd R_z(yaw_rad, Eigen::Vector3d::UnitZ());
    const Eigen::AngleAxisd R_y(pitch_rad, Eigen::Vector3d::UnitY());
    const Eigen::AngleAxisd R_x(roll_rad, Eigen::Vector3d::UnitX());
    return (R_z * R_y * R_x).toRotationMatrix();
}

Eigen::Vector3d euler_zyx_from_rotation(const Eigen::Matrix3d& R) {
    // R(2,0) = -sin(pitch); cos(pitch) = |(R(0,0), R(1,0))| keeps pitch in [-π/2, π/2].
    const double cos_pitch = std::hypot(R(0, 0), R(1, 0));
    // Below this cos(pitch) the roll and yaw terms are pure rounding noise.
    constexpr double kGimbalLockCos = 1e-12;
    if (cos_pitch < kGimbalLockCos) {
        // With roll = 0 both lock cases give R(0,1) = -sin(yaw), R(1,1) = cos(yaw).
        return {0.0, std::atan2(-R(2, 0), cos_pitch), std::atan2(-R(0, 1), R(1, 1))};
    }
    const double yaw = std::atan2(R(1, 0), R(0, 0));
    // Near gimbal lock yaw is only known to eps / cos(pitch); reading roll and pitch from
    // R_z(yaw)ᵀ R = R_y(pitch) R_x(roll), whose entries are O(1), keeps the triple consistent.
    const Eigen::Matrix3d M = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * R;
    return {std::atan2(-M(1, 2), M(1, 1)), std::atan2(-M(2, 0), M(0, 0)), yaw};
}

Eigen::Matrix3d average_rotations(std::span<const Eigen::Matrix3d> rotations,
                                  std::span<const double> weights) {
    check_weights(rotations, weights);
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    double weight_sum = 0.0;
    for (std::size_t i = 0; i < rotations.size(); ++i) {
        sum += weight_at(weights, i) * rotations[i];
        weight_sum += weight_at(weights, i);
    }
    Eigen::Matrix3d mean = orthonormalize(sum);
    // Karcher refinement: the chordal mean is biased for spread samples; the geodesic mean is
    // the fixed point of mean ← mean exp(Σ wᵢ log(meanᵀ Rᵢ) / Σ wᵢ).
    for (int iteration = 0; iteration < kKarcherIterations; ++iteration) {
        Eigen::Vector3d step = Eigen::Vector3d::Zero();
        for (std::size_t i = 0; i < rotations.size(); ++i) {
            step += weight_at(weights, i) * so3_log(mean.transpose() * rotations[i]);
        }
        step /= weight_sum;
        mean = orthonormalize(mean * so3_exp(step));
        if (step.norm() < kKarcherStepTolRad) break;
    }
    return mean;
}

Eigen::Isometry3d make_isometry(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R;
    T.translation() = t;
    return T;
}

Eigen::Matrix3d orthonormalize(const Eigen::Matrix3d& M) {
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Vector3d signs(1.0, 1.0, 1.0);
    if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) signs.z() = -1.0;
    return svd.matrixU() * signs.asDiagonal() * svd.matrixV().transpose();
}

double rotation_angle_rad(const Eigen::Matrix3d& R) { return angle_of(R).theta; }

PoseError pose_error(const Eigen::Isometry3d& T_w_a, const Eigen::Isometry3d& T_w_b) {
    return {(T_w_a.translation() - T_w_b.translation()).norm(),
            rotation_angle_rad(T_w_a.linear().transpose() * T_w_b.linear())};
}

}  // namespace scantling
