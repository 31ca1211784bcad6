#include "pose_filter_math.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>

namespace scantling::localization::detail {
namespace {

using Matrix12d = Eigen::Matrix<double, 12, 12>;

Matrix6d symmetric(const Matrix6d& m) { return 0.5 * (m + m.transpose()); }

/// A square root of a covariance; eigen-decomposition (negative eigenvalues clamped) when
/// rounding made it indefinite.
Matrix12d square_root(const Matrix12d& m) {
    Eigen::LLT<Matrix12d> llt(m);
    if (llt.info() == Eigen::Success) return llt.matrixL();
    Eigen::SelfAdjointEigenSolver<Matrix12d> eig(m);
    return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
}

double mahalanobis_squared(const Vector6d& r, const Matrix6d& S) {
    return r.dot(S.ldlt().solve(r));
}

}  // namespace

OdometryStatus classify_step(const io::VioRecord& from, const io::VioRecord& to,
                             double max_speed_mps) {
    if (!to.valid) return OdometryStatus::kDropout;
    const double dt = to.stamp_s - from.stamp_s;
    const double d = (to.T_odom_body.translation() - from.T_odom_body.translation()).norm();
    return d > max_speed_mps * dt ? OdometryStatus::kJump : OdometryStatus::kOk;
}

Matrix6d process_noise(const PoseFilterConfig& config, const io::VioRecord& from,
                       const io::VioRecord& to, OdometryStatus status,
                       const Eigen::Vector3d& c_world) {
    const double dt = to.stamp_s - from.stamp_s;
    double var_p = 0.0, var_yaw = 0.0, var_tilt = 0.0;
    if (status == OdometryStatus::kDropout) {
        var_p = std::pow(config.dropout_position_random_walk_m_per_sqrt_s, 2) * dt;
        var_yaw = std::pow(config.dropout_yaw_random_walk_rad_per_sqrt_s, 2) * dt;
        var_tilt = std::pow(config.tilt_random_walk_rad_per_sqrt_m, 2) * dt;
    } else {
        const double d =
            status == OdometryStatus::kJump
                ? 0.0
                : (to.T_odom_body.translation() - from.T_odom_body.translation()).norm();
        const double q = to.feature_quality.value_or(1.0);
        const double s = std::pow(1.0 + config.poor_features_drift_gain * (1.0 - q), 2);
        var_p = s * std::pow(config.position_random_walk_m_per_sqrt_m, 2) * d +
                std::pow(config.position_random_walk_m_per_sqrt_s, 2) * dt;
        var_yaw = s * std::pow(config.yaw_random_walk_rad_per_sqrt_m, 2) * d +
                  std::pow(config.yaw_random_walk_rad_per_sqrt_s, 2) * dt;
        var_tilt = std::pow(config.tilt_random_walk_rad_per_sqrt_m, 2) * d + 1e-12 * dt;
    }
    if (status == OdometryStatus::kJump) {
        var_p += config.jump_position_sigma_m * config.jump_position_sigma_m;
        var_yaw += config.jump_yaw_sigma_rad * config.jump_yaw_sigma_rad;
    }
    Vector6d d;
    d << var_p, var_p, var_p, var_tilt, var_tilt, var_yaw;
    // A rotation ω about c moves the origin by c × ω: ρ = δp + c × ω.
    Matrix6d G = Matrix6d::Identity();
    G.topRightCorner<3, 3>() = hat(c_world);
    return G * d.asDiagonal() * G.transpose();
}

Innovation ekf_innovation(const Matrix6d& P, const Matrix6d& R, const Eigen::Isometry3d& B,
                          const Eigen::Isometry3d& Z) {
    Innovation in;
    in.residual = se3_log(Z * B.inverse());
    in.covariance = symmetric(P + R);
    in.mahalanobis_squared = mahalanobis_squared(in.residual, in.covariance);
    return in;
}

Correction ekf_correction(const Matrix6d& P, const Matrix6d& R, const Eigen::Isometry3d& B,
                          const Eigen::Isometry3d& Z) {
    const Innovation in = ekf_innovation(P, R, B, Z);
    const Matrix6d K = in.covariance.ldlt().solve(P).transpose();  // P S⁻¹ (both symmetric)
    const Matrix6d I_K = Matrix6d::Identity() - K;
    Correction c;
    c.delta = K * in.residual;
    c.covariance = symmetric(I_K * P * I_K.transpose() + K * R * K.transpose());  // Joseph form
    return c;
}

UnscentedInnovation ukf_innovation(const Matrix6d& P, const Matrix6d& R, const Eigen::Isometry3d& B,
                                   const Eigen::Isometry3d& Z, const PoseFilterConfig& config) {
    constexpr int L = 12;
    const double alpha2 = config.ukf_alpha * config.ukf_alpha;
    const double lambda = alpha2 * (L + config.ukf_kappa) - L;
    const double w0_mean = lambda / (L + lambda);
    const double w0_cov = w0_mean + 1.0 - alpha2 + config.ukf_beta;
    const double wi = 0.5 / (L + lambda);

    Matrix12d Pa = Matrix12d::Zero();
    Pa.topLeftCorner<6, 6>() = symmetric(P);
    Pa.bottomRightCorner<6, 6>() = symmetric(R);
    const Matrix12d S = std::sqrt(L + lambda) * square_root(Pa);

    // The measurement of sigma point (ξ, n): log(exp(n) · exp(ξ)), relative to B.
    auto measure = [](const Eigen::Matrix<double, 12, 1>& x) {
        return se3_log(se3_exp(x.tail<6>()) * se3_exp(x.head<6>()));
    };
    std::array<Eigen::Matrix<double, 12, 1>, 2 * L + 1> points;
    std::array<Vector6d, 2 * L + 1> y;
    points[0].setZero();
    for (int k = 0; k < L; ++k) {
        points[1 + k] = S.col(k);
        points[1 + L + k] = -S.col(k);
    }
    Vector6d mean = Vector6d::Zero();
    for (int k = 0; k < 2 * L + 1; ++k) {
        y[k] = measure(points[k]);
        mean += (k == 0 ? w0_mean : wi) * y[k];
    }
    UnscentedInnovation out;
    Matrix6d Syy = Matrix6d::Zero();
    for (int k = 0; k < 2 * L + 1; ++k) {
        const double w = k == 0 ? w0_cov : wi;
        const Vector6d dy = y[k] - mean;
        Syy += w * dy * dy.transpose();
        out.cross_covariance += w * points[k].head<6>() * dy.transpose();
    }
    out.innovation.residual = se3_log(Z * B.inverse()) - mean;
    out.innovation.covariance = symmetric(Syy);
    out.innovation.mahalanobis_squared =
        mahalanobis_squared(out.innovation.residual, out.innovation.covariance);
    return out;
}

Correction ukf_correction(const Matrix6d& P, const Matrix6d& R, const Eigen::Isometry3d& B,
                          const Eigen::Isometry3d& Z, const PoseFilterConfig& config) {
    const UnscentedInnovation u = ukf_innovation(P, R, B, Z, config);
    const Matrix6d& S = u.innovation.covariance;
    const Matrix6d K = S.ldlt().solve(u.cross_covariance.transpose()).transpose();  // C S⁻¹
    Correction c;
    c.delta = K * u.innovation.residual;
    c.covariance = symmetric(P - K * S * K.transpose());
    return c;
}

}  // namespace scantling::localization::detail
