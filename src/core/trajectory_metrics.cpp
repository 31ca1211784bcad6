#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/core/trajectory_metrics.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "detail/trajectory_checks.hpp"

namespace scantling {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegPerRad = 180.0 / std::numbers::pi;

/// A rotation further than this from orthonormal (max |RᵀR − I|) is not a rounded rotation but
/// no rotation at all; the pose readers (io/kitti.hpp, io/tum.hpp) accept the same.
constexpr double kMaxOrthonormalityError = 1e-3;

/// `poses` with each rotation projected onto SO(3). Pose files print 6–9 digits, so RᵀR = I
/// only to ~1e-6: the transpose used as the inverse in a relative motion would then leave an
/// error of that size, which the rotation angle turns into ~1e-3 rad (the square root), even
/// between a trajectory and itself. After the projection the transpose is the true inverse.
/// Throws InputError naming `what`, `which` and the pose for a rotation that is not one.
std::vector<Eigen::Isometry3d> rigid_poses(std::span<const Eigen::Isometry3d> poses,
                                           std::string_view what, std::string_view which) {
    std::vector<Eigen::Isometry3d> rigid(poses.begin(), poses.end());
    for (std::size_t i = 0; i < rigid.size(); ++i) {
        const Eigen::Matrix3d R = rigid[i].linear();
        const double error =
            (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
        if (!(error <= kMaxOrthonormalityError) || !(R.determinant() > 0.0)) {
            throw InputError(fmt::format(
                "{}: {} pose {} has no rotation (max |RᵀR − I| = {:.3g}, det R = {:.3g}; expected "
                "orthonormal within {:g}, det > 0)",
                what, which, i, error, R.determinant(), kMaxOrthonormalityError));
        }
        rigid[i].linear() = orthonormalize(R);
    }
    return rigid;
}

/// The devkit's pose_error E = (T_est_i⁻¹ T_est_j)⁻¹ (T_gt_i⁻¹ T_gt_j), as |translation of E|
/// and the rotation angle of E.
struct MotionError {
    double translation_m = 0.0;
    double rotation_rad = 0.0;
};

/// E from the difference of the two relative motions (rigid poses): |t_E| = |R_estᵀ (t_gt −
/// t_est)| = |t_gt − t_est|, and the angle of R_E = R_estᵀ R_gt is 2 asin(|R_gt − R_est|_F / √8).
/// Both equal the devkit's figures (acos(½(trace R_E − 1)) for the angle), but equal motions
/// give exact zeros, and small angles keep their digits where acos near 1 loses half of them.
MotionError motion_error(std::span<const Eigen::Isometry3d> gt,
                         std::span<const Eigen::Isometry3d> est, std::size_t i, std::size_t j) {
    const Eigen::Isometry3d delta_gt = gt[i].inverse() * gt[j];
    const Eigen::Isometry3d delta_est = est[i].inverse() * est[j];
    const double chord = (delta_gt.linear() - delta_est.linear()).norm() / std::sqrt(8.0);
    return {(delta_gt.translation() - delta_est.translation()).norm(),
            2.0 * std::asin(std::min(chord, 1.0))};
}

struct SegmentSums {
    std::size_t count = 0;
    double t_err_per_m = 0.0;  // Σ t_err / len
    double r_err_per_m = 0.0;  // Σ r_err / len, radians per metre
};

}  // namespace

std::vector<double> cumulative_distances_m(std::span<const Eigen::Isometry3d> poses) {
    std::vector<double> dist(poses.size(), 0.0);
    for (std::size_t i = 1; i < poses.size(); ++i) {
        dist[i] = dist[i - 1] + (poses[i].translation() - poses[i - 1].translation()).norm();
    }
    return dist;
}

void KittiMetricConfig::validate(std::string_view prefix) const {
    if (frame_step < 1) {
        throw ConfigError(fmt::format("{}.frame_step = {}, expected >= 1", prefix, frame_step));
    }
    if (segment_lengths_m.empty()) {
        throw ConfigError(
            fmt::format("{}.segment_lengths_m is empty, expected lengths > 0", prefix));
    }
    for (const double length : segment_lengths_m) {
        if (!(length > 0.0) || !std::isfinite(length)) {
            throw ConfigError(fmt::format("{}.segment_lengths_m contains {}, expected finite > 0",
                                          prefix, length));
        }
    }
}

void RpeConfig::validate(std::string_view prefix) const {
    if (!(delta_m > 0.0) || !std::isfinite(delta_m)) {
        throw ConfigError(fmt::format("{}.delta_m = {}, expected finite > 0", prefix, delta_m));
    }
}

void TrajectoryMetricsConfig::validate(std::string_view prefix) const {
    kitti.validate(fmt::format("{}.kitti", prefix));
    rpe.validate(fmt::format("{}.rpe", prefix));
}

KittiMetrics kitti_metrics(std::span<const Eigen::Isometry3d> gt_in,
                           std::span<const Eigen::Isometry3d> est_in,
                           const KittiMetricConfig& config) {
    config.validate();
    detail::check_matched_trajectories(gt_in, est_in, "kitti_metrics");
    const auto gt = rigid_poses(gt_in, "kitti_metrics", "ground-truth");
    const auto est = rigid_poses(est_in, "kitti_metrics", "estimated");
    const std::vector<double> dist = cumulative_distances_m(gt);
    const auto& lengths = config.segment_lengths_m;
    std::vector<SegmentSums> sums(lengths.size());
    for (std::size_t first = 0; first < gt.size(); first += config.frame_step) {
        for (std::size_t k = 0; k < lengths.size(); ++k) {
            // The devkit's lastFrameFromSegmentLength: first frame strictly beyond start + len.
            const auto last_it = std::upper_bound(dist.begin() + static_cast<std::ptrdiff_t>(first),
                                                  dist.end(), dist[first] + lengths[k]);
            if (last_it == dist.end()) continue;
            const auto last = static_cast<std::size_t>(last_it - dist.begin());
            const MotionError error = motion_error(gt, est, first, last);
            ++sums[k].count;
            sums[k].t_err_per_m += error.translation_m / lengths[k];
            sums[k].r_err_per_m += error.rotation_rad / lengths[k];
        }
    }
    KittiMetrics metrics;
    SegmentSums total;
    for (std::size_t k = 0; k < lengths.size(); ++k) {
        const SegmentSums& s = sums[k];
        if (s.count == 0) continue;
        const auto n = static_cast<double>(s.count);
        metrics.per_length.push_back({lengths[k], s.count, 100.0 * s.t_err_per_m / n,
                                      100.0 * kDegPerRad * s.r_err_per_m / n});
        total.count += s.count;
        total.t_err_per_m += s.t_err_per_m;
        total.r_err_per_m += s.r_err_per_m;
    }
    metrics.num_segments = total.count;
    // Mean over all segments, not over lengths: the devkit's per-sequence figure.
    const double n = total.count > 0 ? static_cast<double>(total.count) : kNaN;
    metrics.rte_percent = 100.0 * total.t_err_per_m / n;
    metrics.rre_deg_per_100m = 100.0 * kDegPerRad * total.r_err_per_m / n;
    return metrics;
}

RpeResult relative_pose_error(std::span<const Eigen::Isometry3d> gt_in,
                              std::span<const Eigen::Isometry3d> est_in, const RpeConfig& config) {
    config.validate();
    detail::check_matched_trajectories(gt_in, est_in, "relative_pose_error");
    const auto gt = rigid_poses(gt_in, "relative_pose_error", "ground-truth");
    const auto est = rigid_poses(est_in, "relative_pose_error", "estimated");
    const std::vector<double> dist = cumulative_distances_m(gt);
    RpeResult result;
    result.delta_m = config.delta_m;
    double sum_sq = 0.0, sum = 0.0, sum_rot_rad = 0.0;
    for (std::size_t i = 0; i < gt.size(); ++i) {
        const auto j_it = std::lower_bound(dist.begin() + static_cast<std::ptrdiff_t>(i),
                                           dist.end(), dist[i] + config.delta_m);
        if (j_it == dist.end()) break;  // later starts are even shorter of the end
        const MotionError error =
            motion_error(gt, est, i, static_cast<std::size_t>(j_it - dist.begin()));
        const double t = error.translation_m;
        sum_sq += t * t;
        sum += t;
        sum_rot_rad += error.rotation_rad;
        ++result.num_pairs;
    }
    const double n = result.num_pairs > 0 ? static_cast<double>(result.num_pairs) : kNaN;
    result.trans_rmse_m = std::sqrt(sum_sq / n);
    result.trans_mean_m = sum / n;
    result.rot_mean_deg = kDegPerRad * sum_rot_rad / n;
    return result;
}

TrajectoryMetrics evaluate_trajectory(std::span<const Eigen::Isometry3d> gt,
                                      std::span<const Eigen::Isometry3d> est,
                                      const TrajectoryMetricsConfig& config) {
    config.validate();
    detail::check_matched_trajectories(gt, est, "evaluate_trajectory");
    TrajectoryMetrics metrics;
    metrics.num_poses = gt.size();
    metrics.path_length_m = cumulative_distances_m(gt).back();
    metrics.kitti = kitti_metrics(gt, est, config.kitti);
    metrics.ate = absolute_trajectory_error(gt, est);
    metrics.rpe = relative_pose_error(gt, est, config.rpe);
    return metrics;
}

}  // namespace scantling
