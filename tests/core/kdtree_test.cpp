#include <scantling/core/error.hpp>
#include <scantling/core/kdtree.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

namespace scantling {
namespace {

// Squared distances are computed in a different order by the tree and by brute force.
constexpr double kDistanceTolM2 = 1e-12;

std::vector<Eigen::Vector3d> random_points(std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    std::vector<Eigen::Vector3d> points(n);
    for (auto& p : points) p = Eigen::Vector3d(u(rng), u(rng), u(rng));
    return points;
}

struct BruteNeighbor {
    double distance_sq_m2;
    std::size_t index;
    bool operator<(const BruteNeighbor& o) const {
        return distance_sq_m2 != o.distance_sq_m2 ? distance_sq_m2 < o.distance_sq_m2
                                                  : index < o.index;
    }
};

std::vector<BruteNeighbor> brute_sorted(const std::vector<Eigen::Vector3d>& points,
                                        const Eigen::Vector3d& q) {
    std::vector<BruteNeighbor> all(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) all[i] = {(points[i] - q).squaredNorm(), i};
    std::sort(all.begin(), all.end());
    return all;
}

TEST(KdTree, KnnMatchesBruteForceOnRandomPoints) {
    const auto points = random_points(2000, 1);
    const KdTree tree(points);
    constexpr std::size_t kK = 15;
    for (const auto& q : random_points(100, 2)) {
        const auto expected = brute_sorted(points, q);
        const NeighborList got = tree.knn(q, kK);
        ASSERT_EQ(got.size(), kK);
        for (std::size_t j = 0; j < kK; ++j) {
            EXPECT_EQ(got.indices[j], expected[j].index);
            EXPECT_NEAR(got.distances_sq_m2[j], expected[j].distance_sq_m2, kDistanceTolM2);
        }
    }
}

TEST(KdTree, KnnWithinIsKnnCutAtTheBoundAndKeepsAPointExactlyOnIt) {
    auto points = random_points(2000, 1);
    points.push_back(Eigen::Vector3d(30.0, 0.0, 0.0));  // exactly 1.5 m from the last query
    const KdTree tree(points);
    auto queries = random_points(200, 3);
    queries.push_back(Eigen::Vector3d(31.5, 0.0, 0.0));
    constexpr std::size_t kK = 5;
    std::vector<std::size_t> indices;
    std::vector<double> d2;
    std::size_t partial = 0, empty = 0;
    for (const auto& q : queries) {
        const NeighborList all = tree.knn(q, kK);
        std::size_t expected = 0;
        while (expected < kK && all.distances_sq_m2[expected] <= 1.5 * 1.5) ++expected;
        ASSERT_EQ(tree.knn_within(q, kK, 1.5, indices, d2), expected);
        ASSERT_EQ(indices.size(), expected);
        for (std::size_t j = 0; j < expected; ++j) {
            EXPECT_EQ(indices[j], all.indices[j]);
            EXPECT_EQ(d2[j], all.distances_sq_m2[j]);
        }
        partial += expected > 0 && expected < kK;
        empty += expected == 0;
    }
    // The bound cut some lists short and emptied others, the far query's included.
    EXPECT_GT(partial, 10U);
    EXPECT_GT(empty, 0U);
    EXPECT_EQ(tree.knn_within(queries.back(), kK, 1.5, indices, d2), 1U);
    EXPECT_EQ(indices[0], points.size() - 1);
    EXPECT_THROW(tree.knn_within(queries[0], kK, -1.0, indices, d2), ConfigError);
    EXPECT_THROW(tree.knn_within(queries[0], kK, std::nan(""), indices, d2), ConfigError);
    EXPECT_EQ(KdTree({}).knn_within(queries[0], kK, 1.0, indices, d2), 0U);
}

TEST(KdTree, KnnWithinAnInfiniteBoundIsKnnAndLeafPositionsNameTheSamePoints) {
    const auto points = random_points(2000, 5);
    const KdTree tree(points);
    constexpr std::size_t kK = 6;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::vector<std::size_t> indices, positions;
    std::vector<double> d2, leaf_d2;
    for (const auto& q : random_points(100, 6)) {
        const NeighborList all = tree.knn(q, kK);
        ASSERT_EQ(tree.knn_within(q, kK, kInf, indices, d2), kK);
        EXPECT_EQ(indices, all.indices);
        EXPECT_EQ(d2, all.distances_sq_m2);
        ASSERT_EQ(tree.knn_within_leaf(q, kK, 0.4, positions, leaf_d2),
                  tree.knn_within(q, kK, 0.4, indices, d2));
        EXPECT_EQ(leaf_d2, d2);
        for (std::size_t j = 0; j < positions.size(); ++j) {
            EXPECT_EQ(tree.leaf_points()[positions[j]], points[indices[j]]);
            EXPECT_EQ(tree.leaf_order()[positions[j]], indices[j]);
        }
    }
}

TEST(KdTree, RadiusMatchesBruteForceAndIsSortedByDistance) {
    const auto points = random_points(2000, 3);
    const KdTree tree(points);
    constexpr double kRadiusM = 2.5;
    for (const auto& q : random_points(100, 4)) {
        const auto all = brute_sorted(points, q);
        std::vector<std::size_t> expected;
        for (const auto& n : all) {
            if (n.distance_sq_m2 < kRadiusM * kRadiusM) expected.push_back(n.index);
        }
        const NeighborList got = tree.radius(q, kRadiusM);
        EXPECT_EQ(got.indices, expected);
        EXPECT_TRUE(std::is_sorted(got.distances_sq_m2.begin(), got.distances_sq_m2.end()));
    }
}

TEST(KdTree, NearestFindsTheClosestPoint) {
    const auto points = random_points(500, 5);
    const KdTree tree(points, KdTreeConfig{.leaf_max_size = 1});
    for (const auto& q : random_points(50, 6)) {
        const auto expected = brute_sorted(points, q).front();
        const auto got = tree.nearest(q);
        ASSERT_TRUE(got.has_value());
        EXPECT_EQ(got->index, expected.index);
        EXPECT_NEAR(got->distance_sq_m2, expected.distance_sq_m2, kDistanceTolM2);
    }
}

TEST(KdTree, KLargerThanSizeReturnsEveryPoint) {
    const auto points = random_points(7, 7);
    const KdTree tree(points);
    const NeighborList got = tree.knn(Eigen::Vector3d::Zero(), 50);
    ASSERT_EQ(got.size(), 7U);
    std::vector<std::size_t> sorted = got.indices;
    std::sort(sorted.begin(), sorted.end());
    std::vector<std::size_t> all(7);
    std::iota(all.begin(), all.end(), 0);
    EXPECT_EQ(sorted, all);
    EXPECT_TRUE(std::is_sorted(got.distances_sq_m2.begin(), got.distances_sq_m2.end()));
}

TEST(KdTree, DuplicatePointsAreAllFound) {
    const std::vector<Eigen::Vector3d> points(20, Eigen::Vector3d(1.0, 2.0, 3.0));
    const KdTree tree(points);
    const NeighborList got = tree.knn(Eigen::Vector3d(1.0, 2.0, 3.0), 5);
    ASSERT_EQ(got.size(), 5U);
    for (double d : got.distances_sq_m2) EXPECT_EQ(d, 0.0);
    std::vector<std::size_t> sorted = got.indices;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::unique(sorted.begin(), sorted.end()), sorted.end()) << "an index repeated";
    EXPECT_EQ(tree.radius(Eigen::Vector3d(1.0, 2.0, 3.5), 1.0).size(), 20U);
}

TEST(KdTree, EmptyTreeFindsNothing) {
    const KdTree tree({});
    EXPECT_TRUE(tree.empty());
    EXPECT_FALSE(tree.nearest(Eigen::Vector3d::Zero()).has_value());
    EXPECT_EQ(tree.knn(Eigen::Vector3d::Zero(), 3).size(), 0U);
    EXPECT_EQ(tree.radius(Eigen::Vector3d::Zero(), 1.0).size(), 0U);
    const std::vector<Eigen::Vector3d> queries(4, Eigen::Vector3d::Zero());
    const KnnBatchResult batch = tree.knn_batch(queries, 3);
    EXPECT_EQ(batch.k, 0U);
    EXPECT_TRUE(batch.indices.empty());
}

TEST(KdTree, BatchIsIdenticalForOneAndTwoThreadsAndMatchesSingleQueries) {
    const auto points = random_points(3000, 8);
    const auto queries = random_points(1500, 9);
    const KdTree tree(points);
    const KnnBatchResult one = tree.knn_batch(queries, 8, ParallelConfig{.num_threads = 1});
    const KnnBatchResult two = tree.knn_batch(queries, 8, ParallelConfig{.num_threads = 2});
    ASSERT_EQ(one.num_queries(), queries.size());
    EXPECT_EQ(one.indices, two.indices);
    EXPECT_EQ(one.distances_sq_m2, two.distances_sq_m2);
    const NeighborList single = tree.knn(queries[77], 8);
    EXPECT_TRUE(
        std::equal(single.indices.begin(), single.indices.end(), one.indices.begin() + 77 * 8));
}

TEST(KdTree, TreeStaysValidAfterMoveAndSourceVectorChange) {
    auto points = random_points(100, 10);
    KdTree tree(points);
    const Eigen::Vector3d target = points[42];
    points.clear();
    const KdTree moved(std::move(tree));
    const auto got = moved.nearest(target);
    ASSERT_TRUE(got.has_value());
    EXPECT_EQ(got->index, 42U);
}

TEST(KdTree, RejectsBadInput) {
    std::vector<Eigen::Vector3d> points = random_points(10, 11);
    points[3].y() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(KdTree{points}, InputError);
    EXPECT_THROW(KdTree(random_points(10, 12), KdTreeConfig{.leaf_max_size = 0}), ConfigError);
    const KdTree tree(random_points(10, 13));
    EXPECT_THROW(tree.radius(Eigen::Vector3d::Zero(), -1.0), ConfigError);
}

}  // namespace
}  // namespace scantling
