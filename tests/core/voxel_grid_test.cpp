#include <scantling/core/error.hpp>
#include <scantling/core/voxel_grid.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

namespace scantling {
namespace {

// Centroids of the same points summed in another order differ by a few ulps of ~10 m values.
constexpr double kCentroidTolM = 1e-12;

PointCloud random_cloud(std::size_t n, unsigned seed, double half_extent_m = 5.0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-half_extent_m, half_extent_m);
    PointCloud cloud;
    for (std::size_t i = 0; i < n; ++i) cloud.points.emplace_back(u(rng), u(rng), u(rng));
    return cloud;
}

VoxelGridConfig config_with(double voxel_size_m, int num_threads = 0) {
    VoxelGridConfig config;
    config.voxel_size_m = voxel_size_m;
    config.parallel.num_threads = num_threads;
    return config;
}

TEST(VoxelGrid, ProducesCentroidPerVoxelOrderedByVoxel) {
    PointCloud cloud;
    cloud.points = {{1.5, 0.5, 0.5}, {0.1, 0.1, 0.1}, {0.3, 0.5, 0.7}, {-0.5, 0.2, 0.2}};
    const PointCloud down = voxel_downsample(cloud, 1.0);
    ASSERT_EQ(down.size(), 3U);
    EXPECT_TRUE(down.points[0].isApprox(Eigen::Vector3d(-0.5, 0.2, 0.2)));
    EXPECT_TRUE(down.points[1].isApprox(Eigen::Vector3d(0.2, 0.3, 0.4)));
    EXPECT_TRUE(down.points[2].isApprox(Eigen::Vector3d(1.5, 0.5, 0.5)));
}

TEST(VoxelGrid, HundredPointsAlongOneMetreGiveTenVoxels) {
    PointCloud cloud;
    for (int i = 0; i < 100; ++i) cloud.points.emplace_back(0.01 * i, 0.0, 0.0);
    EXPECT_EQ(voxel_downsample(cloud, 0.1).size(), 10U);
}

TEST(VoxelGrid, AveragesEveryFieldAsDocumented) {
    PointCloud cloud;
    cloud.points = {{0.1, 0.1, 0.1}, {0.2, 0.2, 0.2}, {0.3, 0.3, 0.3}, {5.5, 0.5, 0.5}};
    cloud.normals = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}};
    cloud.covariances = {Eigen::Matrix3d::Identity(), 2 * Eigen::Matrix3d::Identity(),
                         3 * Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Zero()};
    cloud.intensities = {1.0F, 2.0F, 6.0F, 7.0F};
    cloud.rings = {5, 3, 5, 9};
    cloud.times_s = {0.0F, 0.03F, 0.06F, 0.09F};
    cloud.colors = {Rgb8(10, 20, 0), Rgb8(11, 20, 0), Rgb8(11, 21, 255), Rgb8(1, 2, 3)};
    cloud.stamp_s = 42.0;
    const PointCloud down = voxel_downsample(cloud, 1.0);
    ASSERT_EQ(down.size(), 2U);
    EXPECT_TRUE(down.points[0].isApprox(Eigen::Vector3d(0.2, 0.2, 0.2)));
    EXPECT_TRUE(down.normals[0].isApprox(Eigen::Vector3d::Ones().normalized()));
    EXPECT_TRUE(down.covariances[0].isApprox(2 * Eigen::Matrix3d::Identity()));
    EXPECT_FLOAT_EQ(down.intensities[0], 3.0F);
    EXPECT_EQ(down.rings[0], 5);
    EXPECT_FLOAT_EQ(down.times_s[0], 0.03F);
    EXPECT_EQ(down.colors[0], Rgb8(11, 20, 85));  // (32+1)/3 = 11 (rounded), 61/3 = 20, 85
    EXPECT_EQ(down.normals[1], Eigen::Vector3d(0, 0, -1));
    EXPECT_EQ(down.rings[1], 9);
    EXPECT_EQ(down.stamp_s, 42.0);
}

TEST(VoxelGrid, RingTieGoesToLowestAndOpposedNormalsKeepFirst) {
    PointCloud cloud;
    cloud.points = {{0.1, 0.1, 0.1}, {0.2, 0.2, 0.2}};
    cloud.normals = {{0, 0, 1}, {0, 0, -1}};
    cloud.rings = {7, 2};
    const PointCloud down = voxel_downsample(cloud, 1.0);
    ASSERT_EQ(down.size(), 1U);
    EXPECT_EQ(down.rings[0], 2);
    EXPECT_EQ(down.normals[0], Eigen::Vector3d(0, 0, 1));
}

// 70,000 points: several radix-sort chunks, whose counts and offsets must compose.
TEST(VoxelGrid, MatchesBruteForceMapOfFlooredIndices) {
    const PointCloud cloud = random_cloud(70000, 1);
    constexpr double kVoxelM = 0.7;
    std::map<std::tuple<long, long, long>, std::pair<Eigen::Vector3d, int>> expected;
    for (const auto& p : cloud.points) {
        const auto key = std::tuple(static_cast<long>(std::floor(p.x() / kVoxelM)),
                                    static_cast<long>(std::floor(p.y() / kVoxelM)),
                                    static_cast<long>(std::floor(p.z() / kVoxelM)));
        auto& [sum, count] = expected.try_emplace(key, Eigen::Vector3d::Zero(), 0).first->second;
        sum += p;
        ++count;
    }
    const PointCloud down = voxel_downsample(cloud, kVoxelM);
    ASSERT_EQ(down.size(), expected.size());
    std::size_t i = 0;
    for (const auto& [key, acc] : expected) {
        const Eigen::Vector3d centroid = acc.first / acc.second;
        EXPECT_LT((down.points[i++] - centroid).norm(), kCentroidTolM);
    }
}

TEST(VoxelGrid, OneAndTwoThreadsAreBitIdentical) {
    PointCloud cloud = random_cloud(60000, 2);
    cloud.intensities.assign(cloud.size(), 0.0F);
    for (std::size_t i = 0; i < cloud.size(); ++i) cloud.intensities[i] = 0.001F * (i % 997);
    const PointCloud one = voxel_downsample(cloud, config_with(0.3, 1));
    const PointCloud two = voxel_downsample(cloud, config_with(0.3, 2));
    EXPECT_EQ(one.points, two.points);
    EXPECT_EQ(one.intensities, two.intensities);
}

TEST(VoxelGrid, ShuffledInputGivesTheSameVoxels) {
    const PointCloud cloud = random_cloud(5000, 3);
    PointCloud shuffled = cloud;
    std::mt19937 rng(4);
    std::shuffle(shuffled.points.begin(), shuffled.points.end(), rng);
    const PointCloud a = voxel_downsample(cloud, 0.5);
    const PointCloud b = voxel_downsample(shuffled, 0.5);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_LT((a.points[i] - b.points[i]).norm(), kCentroidTolM);
    }
}

TEST(VoxelGrid, GridIsAnchoredAtTheOrigin) {
    PointCloud cloud;
    cloud.points = {{-0.05, 0.0, 0.0}, {0.05, 0.0, 0.0}};
    EXPECT_EQ(voxel_downsample(cloud, 0.1).size(), 2U);
}

TEST(VoxelGrid, HugeExtentRelativeToVoxelIsHandled) {
    PointCloud cloud;
    // 1e10 voxels per axis: 34 bits each, more than a 64-bit packed key holds.
    constexpr double kFar = 1e7 + 4e-4;  // 0.4 voxel past a boundary: no rounding ambiguity
    cloud.points = {{kFar, kFar, kFar}, {0.0, 0.0, 0.0}, {kFar, kFar, kFar + 2e-4}, {0, 0, 5e-3}};
    const PointCloud down = voxel_downsample(cloud, 1e-3);
    ASSERT_EQ(down.size(), 3U);
    EXPECT_EQ(down.points[0], Eigen::Vector3d(0.0, 0.0, 0.0));
    EXPECT_EQ(down.points[1], Eigen::Vector3d(0.0, 0.0, 5e-3));
    EXPECT_NEAR(down.points[2].z(), kFar + 1e-4, 1e-8);
    // Exactly 64 key bits: y needs 32, z 31 and the point index 1 (x needs none).
    PointCloud tight;
    tight.points = {{0.5, 4294967295.5, 2147483647.5}, {0.5, 0.5, 0.5}};
    const PointCloud tight_down = voxel_downsample(tight, 1.0);
    ASSERT_EQ(tight_down.size(), 2U);
    EXPECT_EQ(tight_down.points[0], tight.points[1]);
    EXPECT_EQ(tight_down.points[1], tight.points[0]);
    // Indices past int64 cannot be represented: refused with a clear error, never wrapped.
    PointCloud absurd;
    absurd.points = {{1.0, 0.0, 0.0}};
    EXPECT_THROW(voxel_downsample(absurd, 1e-300), InputError);
}

TEST(VoxelGrid, EmptyCloudGivesEmptyCloud) {
    PointCloud cloud;
    cloud.stamp_s = 3.0;
    const PointCloud down = voxel_downsample(cloud, 0.1);
    EXPECT_TRUE(down.empty());
    EXPECT_EQ(down.stamp_s, 3.0);
}

TEST(VoxelGrid, RejectsBadConfigAndInput) {
    const PointCloud cloud = random_cloud(10, 5);
    EXPECT_THROW(voxel_downsample(cloud, 0.0), ConfigError);
    EXPECT_THROW(voxel_downsample(cloud, -0.1), ConfigError);
    EXPECT_THROW(voxel_downsample(cloud, std::numeric_limits<double>::quiet_NaN()), ConfigError);
    EXPECT_THROW(voxel_downsample(cloud, std::numeric_limits<double>::infinity()), ConfigError);
    EXPECT_THROW(voxel_downsample(cloud, config_with(0.1, -1)), ConfigError);
    PointCloud nan_cloud = cloud;
    nan_cloud.points[4].x() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(voxel_downsample(nan_cloud, 0.1), InputError);
    PointCloud inconsistent = cloud;
    inconsistent.intensities = {1.0F};
    EXPECT_THROW(voxel_downsample(inconsistent, 0.1), InputError);
}

}  // namespace
}  // namespace scantling
