#include <scantling/core/error.hpp>
#include <scantling/core/outlier_removal.hpp>

#include <limits>
#include <numeric>

#include <gtest/gtest.h>

namespace scantling {
namespace {

/// A 30 × 30 grid (0.1 m spacing) in z = 0, then isolated points metres away from it and from
/// each other, at indices 900.. .
PointCloud plane_with_outliers() {
    PointCloud cloud;
    for (int i = 0; i < 30; ++i) {
        for (int j = 0; j < 30; ++j) cloud.points.emplace_back(0.1 * i, 0.1 * j, 0.0);
    }
    cloud.points.emplace_back(1.5, 1.5, 6.0);
    cloud.points.emplace_back(-8.0, 1.0, 0.0);
    cloud.points.emplace_back(12.0, -9.0, 3.0);
    cloud.points.emplace_back(1.0, 1.0, -7.0);
    cloud.intensities.resize(cloud.size());
    std::iota(cloud.intensities.begin(), cloud.intensities.end(), 0.0F);
    cloud.stamp_s = 7.0;
    return cloud;
}

std::vector<std::size_t> plane_indices() {
    std::vector<std::size_t> indices(900);
    std::iota(indices.begin(), indices.end(), std::size_t{0});
    return indices;
}

TEST(StatisticalOutlierRemoval, RemovesExactlyTheIsolatedPoints) {
    const PointCloud cloud = plane_with_outliers();
    const OutlierRemovalResult result = statistical_outlier_removal(cloud);
    EXPECT_EQ(result.inlier_indices, plane_indices());
    EXPECT_EQ(result.num_removed, 4U);
    ASSERT_EQ(result.inliers.size(), 900U);
    EXPECT_EQ(result.inliers.intensities[899], 899.0F);  // fields are carried
    EXPECT_EQ(result.inliers.stamp_s, 7.0);
}

TEST(StatisticalOutlierRemoval, OneAndTwoThreadsKeepTheSamePoints) {
    // The bare grid: its border points score higher than the interior, so a tight ratio trims
    // them and the comparison is not trivially "keep everything".
    const PointCloud cloud = select(plane_with_outliers(), plane_indices());
    StatisticalOutlierConfig config;
    config.std_ratio = 0.5;
    config.parallel.num_threads = 1;
    const auto one = statistical_outlier_removal(cloud, config);
    config.parallel.num_threads = 2;
    const auto two = statistical_outlier_removal(cloud, config);
    EXPECT_EQ(one.inlier_indices, two.inlier_indices);
    EXPECT_GT(one.num_removed, 0U);
}

TEST(StatisticalOutlierRemoval, TinyCloudsAreKept) {
    PointCloud single;
    single.points = {{1.0, 2.0, 3.0}};
    EXPECT_EQ(statistical_outlier_removal(single).inliers.size(), 1U);
    EXPECT_TRUE(statistical_outlier_removal(PointCloud{}).inliers.empty());
}

TEST(RadiusOutlierRemoval, RemovesExactlyTheIsolatedPoints) {
    const PointCloud cloud = plane_with_outliers();
    RadiusOutlierConfig config;
    config.radius_m = 0.25;
    config.min_neighbors = 7;  // a grid corner has exactly 7 other points within 0.25 m
    const OutlierRemovalResult result = radius_outlier_removal(cloud, config);
    EXPECT_EQ(result.inlier_indices, plane_indices());
    EXPECT_EQ(result.num_removed, 4U);
    config.min_neighbors = 8;  // now the four corners go too
    EXPECT_EQ(radius_outlier_removal(cloud, config).num_removed, 8U);
}

TEST(OutlierRemoval, RejectsBadConfigAndInput) {
    PointCloud cloud = plane_with_outliers();
    StatisticalOutlierConfig bad_k;
    bad_k.num_neighbors = 0;
    EXPECT_THROW(statistical_outlier_removal(cloud, bad_k), ConfigError);
    StatisticalOutlierConfig bad_ratio;
    bad_ratio.std_ratio = 0.0;
    EXPECT_THROW(statistical_outlier_removal(cloud, bad_ratio), ConfigError);
    RadiusOutlierConfig bad_radius;
    bad_radius.radius_m = -1.0;
    EXPECT_THROW(radius_outlier_removal(cloud, bad_radius), ConfigError);
    RadiusOutlierConfig bad_min;
    bad_min.min_neighbors = 0;
    EXPECT_THROW(radius_outlier_removal(cloud, bad_min), ConfigError);
    cloud.points[3].x() = std::numeric_limits<double>::infinity();
    EXPECT_THROW(statistical_outlier_removal(cloud), InputError);
    EXPECT_THROW(radius_outlier_removal(cloud), InputError);
}

}  // namespace
}  // namespace scantling
