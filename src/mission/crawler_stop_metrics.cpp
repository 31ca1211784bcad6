// The crawler's stop-and-map scored on the truth (detail/crawler_stop_metrics.hpp).
#include "detail/crawler_stop_metrics.hpp"

#include <algorithm>
#include <cmath>

namespace scantling::mission::detail {
namespace {

using perception::SurfaceLabel;

constexpr double kAxisStepM = 0.01;

/// The obstacle's axis in the body frame's x-y plane, a point every kAxisStepM.
std::vector<Eigen::Vector2d> axis_samples(const sim::ObstacleTruth& o,
                                          const Eigen::Isometry3d& T_body_world) {
    const Eigen::Vector2d a = (T_body_world * o.a_world_m).head<2>();
    const Eigen::Vector2d b = (T_body_world * o.b_world_m).head<2>();
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / kAxisStepM)));
    std::vector<Eigen::Vector2d> samples;
    for (int i = 0; i <= n; ++i) samples.push_back(a + (b - a) * (static_cast<double>(i) / n));
    return samples;
}

double box_distance_m(const Eigen::Vector2d& p, const perception::ObstacleCluster& c) {
    const Eigen::Vector2d below = (c.min_xy_m - p).cwiseMax(0.0);
    const Eigen::Vector2d above = (p - c.max_xy_m).cwiseMax(0.0);
    return (below + above).norm();
}

bool matches(const std::vector<Eigen::Vector2d>& axis, double radius_m,
             const perception::ObstacleCluster& c) {
    for (const Eigen::Vector2d& p : axis) {
        if (box_distance_m(p, c) <= radius_m + kMatchToleranceM) return true;
    }
    return false;
}

SurfaceLabel sign_of(const sim::ObstacleTruth& o) {
    return o.positive() ? SurfaceLabel::kPositive : SurfaceLabel::kNegative;
}

bool in_view(const std::vector<Eigen::Vector2d>& axis, const perception::SurfaceGrid& grid) {
    return std::any_of(axis.begin(), axis.end(), [&](const Eigen::Vector2d& p) {
        return grid.label_at(p) != SurfaceLabel::kUnknown;
    });
}

}  // namespace

void StopMetrics::add(const perception::StopMap& stop, const Eigen::Isometry3d& T_world_body_true) {
    const Eigen::Vector3d p_true = T_world_body_true.translation();
    const double map_error_m = (stop.T_world_body_map.translation() - p_true).norm();
    const double pf_error_m = (stop.T_world_body_localisation.translation() - p_true).norm();
    ++sums_.stops;
    sums_.stops_icp_applied += stop.icp_applied;
    map_sq_sum_ += map_error_m * map_error_m;
    pf_sq_sum_ += pf_error_m * pf_error_m;
    sums_.map_error_max_m = std::max(sums_.map_error_max_m, map_error_m);
    sums_.pf_error_max_m = std::max(sums_.pf_error_max_m, pf_error_m);
    const auto& clusters = stop.detection.clusters;
    if (stop.detection.status != perception::SurfaceStatus::kOk) return;
    const Eigen::Isometry3d T_body_world = T_world_body_true.inverse();
    std::vector<bool> right(clusters.size(), false);
    for (const sim::ObstacleTruth& o : truths_) {
        const std::vector<Eigen::Vector2d> axis = axis_samples(o, T_body_world);
        bool found = false;
        for (std::size_t c = 0; c < clusters.size(); ++c) {
            if (clusters[c].label != sign_of(o) || !matches(axis, o.radius_m, clusters[c]))
                continue;
            right[c] = true;
            found = true;
        }
        if (!in_view(axis, stop.detection.grid)) continue;
        CrawlerClassScore& score = sums_.classes.at(static_cast<std::size_t>(o.kind));
        ++score.in_view;
        score.found += found;
    }
    for (std::size_t c = 0; c < clusters.size(); ++c) {
        const bool positive = clusters[c].label == SurfaceLabel::kPositive;
        (positive ? sums_.positive_clusters : sums_.negative_clusters) += 1;
        (positive ? sums_.positive_right : sums_.negative_right) += right[c];
    }
}

CrawlerStopScores StopMetrics::scores() const {
    CrawlerStopScores s = sums_;
    if (s.stops > 0) {
        s.map_error_rms_m = std::sqrt(map_sq_sum_ / static_cast<double>(s.stops));
        s.pf_error_rms_m = std::sqrt(pf_sq_sum_ / static_cast<double>(s.stops));
    }
    return s;
}

}  // namespace scantling::mission::detail
