#pragma once
/// @file Removal of isolated points (spray, dust, multipath returns) by neighbour statistics.
///
/// Cost: one k-d tree build, O(n log n), plus one neighbour query per point (parallel).
/// Thread-safety: pure functions of their arguments.
/// @note Deterministic: 1 and N threads keep the same points (the global statistics are summed
/// in a fixed order).

#include <cstddef>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>

namespace scantling {

struct StatisticalOutlierConfig {
    /// Neighbours (the point itself excluded) whose mean distance scores a point, >= 1.
    int num_neighbors = 20;
    /// A point is removed when its score exceeds mean + std_ratio × standard deviation of all
    /// scores, > 0. Smaller removes more; 2 removes roughly the worst 2–5 % of a clean scan.
    double std_ratio = 2.0;
    ParallelConfig parallel;  ///< threads for the neighbour queries

    /// Throws ConfigError naming the field ("outliers.std_ratio = 0, expected > 0").
    void validate(std::string_view prefix = "outliers") const;
};

struct RadiusOutlierConfig {
    /// Neighbourhood radius in metres, > 0.
    double radius_m = 0.5;
    /// A point needs at least this many other points strictly within `radius_m` to stay, >= 1.
    int min_neighbors = 5;
    ParallelConfig parallel;  ///< threads for the neighbour queries

    /// Throws ConfigError naming the field ("outliers.radius_m = -1, expected > 0").
    void validate(std::string_view prefix = "outliers") const;
};

struct OutlierRemovalResult {
    PointCloud inliers;                       ///< kept points, every field carried, input order
    std::vector<std::size_t> inlier_indices;  ///< their indices in the input, ascending
    std::size_t num_removed = 0;              ///< input size - inliers.size()
};

/// Statistical outlier removal (Rusu et al. 2008): scores each point by the mean distance to
/// its `num_neighbors` nearest neighbours and removes scores above mean + std_ratio × std.
/// With fewer than num_neighbors + 1 points every other point is a neighbour; a single point is
/// kept (nothing to compare it with). An empty cloud gives an empty result.
/// Throws InputError on a non-finite or inconsistent cloud, ConfigError on a bad config.
OutlierRemovalResult statistical_outlier_removal(const PointCloud& cloud,
                                                 const StatisticalOutlierConfig& config = {});

/// Radius outlier removal: keeps points with at least `min_neighbors` other points strictly
/// within `radius_m`. An empty cloud gives an empty result.
/// Throws InputError on a non-finite or inconsistent cloud, ConfigError on a bad config.
OutlierRemovalResult radius_outlier_removal(const PointCloud& cloud,
                                            const RadiusOutlierConfig& config = {});

}  // namespace scantling
