#include <scantling/registration/icp.hpp>

#include <algorithm>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

namespace scantling::registration {
namespace {

/// Left twist at the origin from one at `c` (same axes): delta = Ad(translation c) delta_c.
Matrix6d adjoint_of_translation(const Eigen::Vector3d& c) {
    Matrix6d A = Matrix6d::Identity();
    A.topRightCorner<3, 3>() = hat(c);
    return A;
}

/// delta = to_origin · u: the twist at the origin of a twist u taken about `centroid` with its
/// rotation scaled by `radius_m` (see below).
Matrix6d to_origin_of(const Eigen::Vector3d& centroid, double radius_m) {
    Vector6d scale_inv;
    scale_inv << 1.0, 1.0, 1.0, 1.0 / radius_m, 1.0 / radius_m, 1.0 / radius_m;
    return adjoint_of_translation(centroid) * scale_inv.asDiagonal();
}

}  // namespace

// Why move and scale before the eigen-decomposition: about a far-away origin every rotation
// looks like a translation, and rad and m eigenvalues are not comparable. About the centroid,
// with omega measured as L·omega (metres of displacement at the RMS radius L), a rotation and a
// translation that move the points equally have equal eigenvalues.
DegeneracyReport analyze_degeneracy(const Matrix6d& H, const Eigen::Vector3d& centroid_target,
                                    double radius_m, double threshold) {
    const Matrix6d to_origin = to_origin_of(centroid_target, radius_m);
    const Matrix6d H_u = to_origin.transpose() * H * to_origin;
    const Eigen::SelfAdjointEigenSolver<Matrix6d> solver(0.5 * (H_u + H_u.transpose()));
    DegeneracyReport report;
    const double largest = solver.eigenvalues()(5);
    report.eigenvalues =
        largest > 0.0 ? Vector6d((solver.eigenvalues() / largest).cwiseMax(0.0)) : Vector6d::Zero();
    for (int k = 0; k < 6; ++k) {
        if (report.eigenvalues(k) >= threshold) break;
        report.weak_directions.push_back((to_origin * solver.eigenvectors().col(k)).normalized());
    }
    report.degenerate = !report.weak_directions.empty();
    return report;
}

DegeneracyReport analyze_degeneracy(const Matrix6d& H, const Eigen::Vector3d& centroid_target,
                                    double radius_m, double threshold,
                                    const Eigen::Matrix<double, 6, Eigen::Dynamic>& free_basis) {
    const Eigen::Index k = free_basis.cols();
    if (k >= 6) return analyze_degeneracy(H, centroid_target, radius_m, threshold);
    if (k == 0)
        return {.eigenvalues = Vector6d::Ones(), .weak_directions = {}, .degenerate = false};
    const Matrix6d to_origin = to_origin_of(centroid_target, radius_m);
    const Matrix6d H_u = to_origin.transpose() * H * to_origin;
    // The free directions in the scaled coordinates u (delta = to_origin u), orthonormalised so
    // that the reduced eigenvalues keep the scale of the six-direction analysis.
    const Eigen::MatrixXd basis_u = to_origin.inverse() * free_basis;
    const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(basis_u).householderQ() *
                              Eigen::MatrixXd::Identity(6, k);
    const Eigen::MatrixXd H_free = Q.transpose() * H_u * Q;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(0.5 *
                                                                (H_free + H_free.transpose()));
    DegeneracyReport report;
    report.eigenvalues = Vector6d::Ones();
    const double largest = solver.eigenvalues()(k - 1);
    for (Eigen::Index i = 0; i < k; ++i) {
        report.eigenvalues(i) =
            largest > 0.0 ? std::max(solver.eigenvalues()(i) / largest, 0.0) : 0.0;
    }
    for (Eigen::Index i = 0; i < k; ++i) {
        if (report.eigenvalues(i) >= threshold) break;
        report.weak_directions.push_back(
            Vector6d((to_origin * Q * solver.eigenvectors().col(i)).normalized()));
    }
    report.degenerate = !report.weak_directions.empty();
    return report;
}

}  // namespace scantling::registration
