#include <scantling/core/error.hpp>
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

/// The devkit's pose_error: how far the estimated motion from i to j is from the true one.
Eigen::Isometry3d relative_error(std::span<const Eigen::Isometry3d> gt,
                                 std::span<const Eigen::Isometry3d> est, std::size_t i,
                                 std::size_t j) {
    const Eigen::Isometry3d delta_gt = gt[i].inverse() * gt[j];
    const Eigen::Isometry3d delta_est = est[i].inverse() * est[j];
    return delta_est.inverse() * delta_gt;
}

/// The devkit's rotationError: acos of the clamped ½(trace − 1). Kept instead of the atan2
/// form so that the figures are the devkit's (they differ only below ~1e-7 rad).
double devkit_rotation_angle_rad(const Eigen::Matrix3d& R) {
    return std::acos(std::clamp(0.5 * (R.trace() - 1.0), -1.0, 1.0));
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

KittiMetrics kitti_metrics(std::span<const Eigen::Isometry3d> gt,
                           std::span<const Eigen::Isometry3d> est,
                           const KittiMetricConfig& config) {
    config.validate();
    detail::check_matched_trajectories(gt, est, "kitti_metrics");
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
            const Eigen::Isometry3d error = relative_error(gt, est, first, last);
            ++sums[k].count;
            sums[k].t_err_per_m += error.translation().norm() / lengths[k];
            sums[k].r_err_per_m += devkit_rotation_angle_rad(error.linear()) / lengths[k];
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

RpeResult relative_pose_error(std::span<const Eigen::Isometry3d> gt,
                              std::span<const Eigen::Isometry3d> est, const RpeConfig& config) {
    config.validate();
    detail::check_matched_trajectories(gt, est, "relative_pose_error");
    const std::vector<double> dist = cumulative_distances_m(gt);
    RpeResult result;
    result.delta_m = config.delta_m;
    double sum_sq = 0.0, sum = 0.0, sum_rot_rad = 0.0;
    for (std::size_t i = 0; i < gt.size(); ++i) {
        const auto j_it = std::lower_bound(dist.begin() + static_cast<std::ptrdiff_t>(i),
                                           dist.end(), dist[i] + config.delta_m);
        if (j_it == dist.end()) break;  // later starts are even shorter of the end
        const Eigen::Isometry3d error =
            relative_error(gt, est, i, static_cast<std::size_t>(j_it - dist.begin()));
        const double t = error.translation().norm();
        sum_sq += t * t;
        sum += t;
        sum_rot_rad += devkit_rotation_angle_rad(error.linear());
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
