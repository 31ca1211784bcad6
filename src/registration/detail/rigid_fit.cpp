#include "rigid_fit.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <vector>

namespace scantling::registration::detail {
namespace {

double weight_of(std::span<const double> weights, std::size_t k) {
    return weights.empty() ? 1.0 : weights[k];
}

Eigen::Vector3d centroid(std::span<const Eigen::Vector3d> points) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& p : points) sum += p;
    return sum / static_cast<double>(points.size());
}

std::vector<Eigen::Vector3d> centred(std::span<const Eigen::Vector3d> points,
                                     const Eigen::Vector3d& c) {
    std::vector<Eigen::Vector3d> out(points.begin(), points.end());
    for (auto& p : out) p -= c;
    return out;
}

}  // namespace

Eigen::Matrix3d fit_rotation(std::span<const Eigen::Vector3d> source,
                             std::span<const Eigen::Vector3d> target,
                             std::span<const double> weights) {
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    for (std::size_t k = 0; k < source.size(); ++k) {
        H += weight_of(weights, k) * target[k] * source[k].transpose();
    }
    if (H.isZero(0.0)) return Eigen::Matrix3d::Identity();
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
    // Force det(R) = +1: flip the axis of the smallest singular value if needed (Umeyama 1991).
    Eigen::Vector3d d(1.0, 1.0, (svd.matrixU() * svd.matrixV().transpose()).determinant());
    return svd.matrixU() * d.asDiagonal() * svd.matrixV().transpose();
}

double fit_yaw(std::span<const Eigen::Vector3d> source, std::span<const Eigen::Vector3d> target,
               std::span<const double> weights) {
    double c = 0.0;
    double s = 0.0;
    for (std::size_t k = 0; k < source.size(); ++k) {
        const double w = weight_of(weights, k);
        c += w * (source[k].x() * target[k].x() + source[k].y() * target[k].y());
        s += w * (source[k].x() * target[k].y() - source[k].y() * target[k].x());
    }
    return (c == 0.0 && s == 0.0) ? 0.0 : std::atan2(s, c);
}

Eigen::Matrix3d yaw_rotation(double yaw_rad) {
    return Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

Eigen::Isometry3d fit_rigid(std::span<const Eigen::Vector3d> source,
                            std::span<const Eigen::Vector3d> target, bool yaw_only) {
    const Eigen::Vector3d cs = centroid(source);
    const Eigen::Vector3d ct = centroid(target);
    const auto s = centred(source, cs);
    const auto t = centred(target, ct);
    const Eigen::Matrix3d R = yaw_only ? yaw_rotation(fit_yaw(s, t)) : fit_rotation(s, t);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R;
    T.translation() = ct - R * cs;
    return T;
}

double principal_spread_m(std::span<const Eigen::Vector3d> points, bool horizontal) {
    if (points.empty()) return 0.0;
    const Eigen::Vector3d mean = centroid(points);
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : points) cov += (p - mean) * (p - mean).transpose();
    cov /= static_cast<double>(points.size());
    if (horizontal) {
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov.topLeftCorner<2, 2>());
        return std::sqrt(std::max(es.eigenvalues()(1), 0.0));
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    return std::sqrt(std::max(es.eigenvalues()(1), 0.0));  // ascending: (1) is the middle one
}

}  // namespace scantling::registration::detail
