#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/core/trajectory_metrics.hpp>

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

#include "detail/trajectory_checks.hpp"

namespace scantling {
namespace {

// Second singular value of the cross-covariance below this fraction of the first: the points
// are collinear to within rounding (an exact line gives ~1e-16), the rotation is undetermined.
constexpr double kCollinearRatio = 1e-12;

/// The identity maximises tr(R · cross) over SO(3) exactly when `cross` is symmetric and its
/// two smallest eigenvalues sum to >= 0 (Umeyama's lemma: the optimum is σ1 + σ2 ± σ3): so for
/// positions equal to the ground truth, whose cross-covariance is their scatter matrix. The SVD
/// would return I + O(ε) there and turn an exact match into errors of ~1e-14 m. The tolerance
/// (relative to the largest eigenvalue) absorbs the rounding of a rank-deficient scatter
/// matrix (collinear or coplanar positions), where the rotation is not determined anyway.
bool identity_is_optimal(const Eigen::Matrix3d& cross) {
    if (cross != cross.transpose()) return false;
    const Eigen::Vector3d eigenvalues =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cross, Eigen::EigenvaluesOnly)
            .eigenvalues();  // ascending
    return eigenvalues(0) + eigenvalues(1) >= -kCollinearRatio * std::abs(eigenvalues(2));
}

struct UmeyamaSolution {
    Eigen::Isometry3d T_gt_est = Eigen::Isometry3d::Identity();
    Eigen::Vector3d singular_values = Eigen::Vector3d::Zero();
};

/// Closed-form SE(3) least squares (Umeyama 1991, without scale). Any minimiser when the
/// cross-covariance has rank < 2; the caller decides whether that is an error.
template <typename EstAt, typename GtAt>
UmeyamaSolution solve_umeyama(std::size_t n, EstAt est_at, GtAt gt_at) {
    Eigen::Vector3d mean_est = Eigen::Vector3d::Zero(), mean_gt = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        mean_est += est_at(i);
        mean_gt += gt_at(i);
    }
    mean_est /= static_cast<double>(n);
    mean_gt /= static_cast<double>(n);
    Eigen::Matrix3d cross = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        cross += (gt_at(i) - mean_gt) * (est_at(i) - mean_est).transpose();
    }
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cross, Eigen::ComputeFullU | Eigen::ComputeFullV);
    if (identity_is_optimal(cross)) {
        return {make_isometry(Eigen::Matrix3d::Identity(), mean_gt - mean_est),
                svd.singularValues()};
    }
    Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
    // A reflection would fit better when det(U V^T) < 0; flip the weakest axis instead.
    if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) S(2, 2) = -1.0;
    const Eigen::Matrix3d R = svd.matrixU() * S * svd.matrixV().transpose();
    return {make_isometry(R, mean_gt - R * mean_est), svd.singularValues()};
}

double median_of(std::vector<double> values) {
    const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), mid, values.end());
    if (values.size() % 2 == 1) return *mid;
    return 0.5 * (*mid + *std::max_element(values.begin(), mid));
}

void check_stamps(std::span<const double> stamps_s, std::size_t num_poses, const char* which) {
    if (stamps_s.size() != num_poses) {
        throw InputError(fmt::format("associate_by_time: {} {} stamps for {} poses",
                                     stamps_s.size(), which, num_poses));
    }
    for (std::size_t i = 0; i < stamps_s.size(); ++i) {
        if (!std::isfinite(stamps_s[i]) || (i > 0 && !(stamps_s[i] > stamps_s[i - 1]))) {
            throw InputError(fmt::format(
                "associate_by_time: {} stamp {} ({}) is not finite or not after the previous one",
                which, i, stamps_s[i]));
        }
    }
}

}  // namespace

Eigen::Isometry3d align_umeyama(const std::vector<Eigen::Vector3d>& est_positions,
                                const std::vector<Eigen::Vector3d>& gt_positions) {
    if (est_positions.size() != gt_positions.size()) {
        throw InputError(fmt::format("align_umeyama: {} estimated but {} ground-truth positions",
                                     est_positions.size(), gt_positions.size()));
    }
    if (est_positions.size() < 3) {
        throw InputError(fmt::format("align_umeyama: {} point pairs, expected at least 3",
                                     est_positions.size()));
    }
    for (std::size_t i = 0; i < est_positions.size(); ++i) {
        if (!est_positions[i].allFinite() || !gt_positions[i].allFinite()) {
            throw InputError(fmt::format("align_umeyama: point pair {} is not finite", i));
        }
    }
    const UmeyamaSolution solution = solve_umeyama(
        est_positions.size(), [&](std::size_t i) { return est_positions[i]; },
        [&](std::size_t i) { return gt_positions[i]; });
    const Eigen::Vector3d& sv = solution.singular_values;
    if (!(sv(1) > kCollinearRatio * sv(0))) {
        throw InputError(
            "align_umeyama: the points are collinear or coincident, so the rotation about their "
            "line is not determined (expected at least 3 non-collinear points)");
    }
    return solution.T_gt_est;
}

AteResult absolute_trajectory_error(std::span<const Eigen::Isometry3d> gt,
                                    std::span<const Eigen::Isometry3d> est) {
    detail::check_matched_trajectories(gt, est, "absolute_trajectory_error");
    AteResult ate;
    ate.T_gt_est = solve_umeyama(
                       gt.size(), [&](std::size_t i) { return est[i].translation(); },
                       [&](std::size_t i) { return gt[i].translation(); })
                       .T_gt_est;
    ate.errors_m.resize(gt.size());
    double sum_sq = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < gt.size(); ++i) {
        const double e = (ate.T_gt_est * est[i].translation() - gt[i].translation()).norm();
        ate.errors_m[i] = e;
        sum_sq += e * e;
        sum += e;
        ate.max_m = std::max(ate.max_m, e);
    }
    const auto n = static_cast<double>(gt.size());
    ate.rmse_m = std::sqrt(sum_sq / n);
    ate.mean_m = sum / n;
    ate.median_m = median_of(ate.errors_m);
    const double path_m = cumulative_distances_m(gt).back();
    ate.percent_of_path =
        path_m > 0.0 ? 100.0 * ate.rmse_m / path_m : std::numeric_limits<double>::quiet_NaN();
    return ate;
}

void AssociationConfig::validate(std::string_view prefix) const {
    if (!(max_time_difference_s >= 0.0) || !std::isfinite(max_time_difference_s)) {
        throw ConfigError(fmt::format("{}.max_time_difference_s = {}, expected finite >= 0", prefix,
                                      max_time_difference_s));
    }
}

AssociatedTrajectories associate_by_time(std::span<const double> gt_stamps_s,
                                         std::span<const Eigen::Isometry3d> gt,
                                         std::span<const double> est_stamps_s,
                                         std::span<const Eigen::Isometry3d> est,
                                         const AssociationConfig& config) {
    config.validate();
    if (gt.empty() || est.empty()) {
        throw InputError(
            fmt::format("associate_by_time: empty trajectory ({} ground-truth, {} estimated poses)",
                        gt.size(), est.size()));
    }
    check_stamps(gt_stamps_s, gt.size(), "ground-truth");
    check_stamps(est_stamps_s, est.size(), "estimated");
    detail::check_finite_poses(gt, "associate_by_time", "ground-truth");
    detail::check_finite_poses(est, "associate_by_time", "estimated");
    AssociatedTrajectories out;
    for (std::size_t i = 0; i < est.size(); ++i) {
        const double t = est_stamps_s[i];
        const auto after = static_cast<std::size_t>(
            std::lower_bound(gt_stamps_s.begin(), gt_stamps_s.end(), t) - gt_stamps_s.begin());
        // Nearest ground-truth stamp: the first at or after t, or the one before it.
        std::size_t nearest = after;
        if (after == gt.size() ||
            (after > 0 && t - gt_stamps_s[after - 1] < gt_stamps_s[after] - t)) {
            nearest = after - 1;
        }
        if (std::abs(gt_stamps_s[nearest] - t) > config.max_time_difference_s) {
            ++out.num_unmatched;
            continue;
        }
        Eigen::Isometry3d T_gt = gt[nearest];
        if (config.interpolate_gt && after > 0 && after < gt.size() && gt_stamps_s[after] != t) {
            const double fraction =
                (t - gt_stamps_s[after - 1]) / (gt_stamps_s[after] - gt_stamps_s[after - 1]);
            T_gt = interpolate(gt[after - 1], gt[after], fraction);
        }
        out.stamps_s.push_back(t);
        out.gt.push_back(T_gt);
        out.est.push_back(est[i]);
    }
    if (out.est.size() < 2) {
        throw InputError(fmt::format(
            "associate_by_time: {} of {} estimated poses lie within {} s of a ground-truth stamp, "
            "expected at least 2 (estimate stamps {}..{} s, ground truth {}..{} s)",
            out.est.size(), est.size(), config.max_time_difference_s, est_stamps_s.front(),
            est_stamps_s.back(), gt_stamps_s.front(), gt_stamps_s.back()));
    }
    return out;
}

}  // namespace scantling
