#include <scantling/core/error.hpp>
#include <scantling/core/kdtree.hpp>
#include <scantling/core/outlier_removal.hpp>

#include <cmath>
#include <span>
#include <utility>

#include <fmt/format.h>

namespace scantling {
namespace {

constexpr std::size_t kGrain = 512;  // points per task: amortises scheduling

void check_input(const PointCloud& cloud, std::string_view what) {
    check_consistent(cloud, what);
    check_finite(cloud, what);
}

OutlierRemovalResult keep_where(const PointCloud& cloud, const std::vector<char>& keep) {
    OutlierRemovalResult result;
    for (std::size_t i = 0; i < keep.size(); ++i) {
        if (keep[i] != 0) result.inlier_indices.push_back(i);
    }
    result.inliers = select(cloud, result.inlier_indices);
    result.num_removed = cloud.size() - result.inlier_indices.size();
    return result;
}

/// Mean distance (m) from each point to its k nearest other points.
std::vector<double> mean_neighbor_distances(const KdTree& tree, std::size_t k,
                                            const ParallelConfig& parallel) {
    const auto& points = tree.points();
    const std::span<const std::size_t> order = tree.leaf_order();  // cache-friendly visit order
    std::vector<double> scores(points.size());
    parallel_for(parallel, points.size(), kGrain, [&](std::size_t begin, std::size_t end) {
        std::vector<std::size_t> idx;
        std::vector<double> dist_sq;
        for (std::size_t t = begin; t < end; ++t) {
            const std::size_t i = order[t];
            // k + 1 because the nearest hit is the point itself (or a duplicate at distance 0).
            const std::size_t found = tree.knn(points[i], k + 1, idx, dist_sq);
            double sum = 0.0;
            for (std::size_t j = 1; j < found; ++j) sum += std::sqrt(dist_sq[j]);
            scores[i] = sum / static_cast<double>(found - 1);
        }
    });
    return scores;
}

/// Mean and sample standard deviation, summed in index order (deterministic).
std::pair<double, double> mean_and_std(const std::vector<double>& values) {
    double sum = 0.0;
    for (double v : values) sum += v;
    const double mean = sum / static_cast<double>(values.size());
    double sq = 0.0;
    for (double v : values) sq += (v - mean) * (v - mean);
    const double denom = values.size() > 1 ? static_cast<double>(values.size() - 1) : 1.0;
    return {mean, std::sqrt(sq / denom)};
}

}  // namespace

void StatisticalOutlierConfig::validate(std::string_view prefix) const {
    if (num_neighbors < 1) {
        throw ConfigError(
            fmt::format("{}.num_neighbors = {}, expected >= 1", prefix, num_neighbors));
    }
    if (!(std_ratio > 0.0) || !std::isfinite(std_ratio)) {
        throw ConfigError(fmt::format("{}.std_ratio = {}, expected finite > 0", prefix, std_ratio));
    }
    parallel.validate(fmt::format("{}.parallel", prefix));
}

void RadiusOutlierConfig::validate(std::string_view prefix) const {
    if (!(radius_m > 0.0) || !std::isfinite(radius_m)) {
        throw ConfigError(fmt::format("{}.radius_m = {}, expected finite > 0", prefix, radius_m));
    }
    if (min_neighbors < 1) {
        throw ConfigError(
            fmt::format("{}.min_neighbors = {}, expected >= 1", prefix, min_neighbors));
    }
    parallel.validate(fmt::format("{}.parallel", prefix));
}

OutlierRemovalResult statistical_outlier_removal(const PointCloud& cloud,
                                                 const StatisticalOutlierConfig& config) {
    config.validate();
    check_input(cloud, "statistical_outlier_removal");
    if (cloud.size() < 2) return keep_where(cloud, std::vector<char>(cloud.size(), 1));
    const KdTree tree(cloud.points);
    const std::vector<double> scores = mean_neighbor_distances(
        tree, static_cast<std::size_t>(config.num_neighbors), config.parallel);
    const auto [mean, std_dev] = mean_and_std(scores);
    const double threshold = mean + config.std_ratio * std_dev;
    std::vector<char> keep(cloud.size());
    for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = scores[i] <= threshold ? 1 : 0;
    return keep_where(cloud, keep);
}

OutlierRemovalResult radius_outlier_removal(const PointCloud& cloud,
                                            const RadiusOutlierConfig& config) {
    config.validate();
    check_input(cloud, "radius_outlier_removal");
    const KdTree tree(cloud.points);
    std::vector<char> keep(cloud.size());
    parallel_for(config.parallel, cloud.size(), kGrain, [&](std::size_t begin, std::size_t end) {
        std::vector<std::size_t> idx;
        std::vector<double> dist_sq;
        for (std::size_t i = begin; i < end; ++i) {
            const std::size_t found = tree.radius(cloud.points[i], config.radius_m, idx, dist_sq);
            // `found` counts the point itself.
            keep[i] = found > static_cast<std::size_t>(config.min_neighbors) ? 1 : 0;
        }
    });
    return keep_where(cloud, keep);
}

}  // namespace scantling
