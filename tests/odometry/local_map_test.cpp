#include <gtest/gtest.h>

#include <algorithm>
#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/odometry/local_map.hpp>

namespace scantling::odometry {
namespace {

std::vector<Eigen::Vector3d> random_points(std::size_t n, double extent, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Eigen::Vector3d> pts(n);
    for (auto& p : pts) {
        p = Eigen::Vector3d(rng.uniform(-extent, extent), rng.uniform(-extent, extent),
                            rng.uniform(-2.0, 2.0));
    }
    return pts;
}

TEST(LocalMap, KnnMergesCellsAndRecentSweepsLikeBruteForce) {
    mapping::CellMapConfig map_config;
    map_config.max_points_per_cell = 100000;  // no thinning: every point stays
    mapping::CellMap map(map_config);
    const auto old_points = random_points(3000, 20.0, 1);
    map.insert(old_points);
    LocalMapConfig config;
    config.radius_m = 100.0;
    LocalMap local(config);
    const auto sweep = random_points(500, 20.0, 2);
    local.update(map, Eigen::Vector3d::Zero(), sweep);
    ASSERT_EQ(local.num_cell_points(), old_points.size());
    ASSERT_EQ(local.num_recent_points(), sweep.size());

    std::vector<Eigen::Vector3d> all = old_points;
    all.insert(all.end(), sweep.begin(), sweep.end());
    Rng rng(3);
    std::vector<Eigen::Vector3d> found;
    std::vector<double> d2;
    for (int q = 0; q < 50; ++q) {
        const Eigen::Vector3d query(rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-2, 2));
        ASSERT_EQ(local.knn(query, 5, found, d2), 5U);
        std::vector<double> brute;
        for (const auto& p : all) brute.push_back((p - query).squaredNorm());
        std::sort(brute.begin(), brute.end());
        for (int i = 0; i < 5; ++i) {
            EXPECT_NEAR(d2[i], brute[i], 1e-6);  // cells store float coordinates
            EXPECT_NEAR((found[i] - query).squaredNorm(), d2[i], 1e-6);
        }
    }
}

TEST(LocalMap, KnnWithinEqualsKnnInsideTheBound) {
    mapping::CellMap map;
    map.insert(random_points(3000, 20.0, 1));
    LocalMapConfig config;
    config.radius_m = 100.0;
    LocalMap local(config);
    local.update(map, Eigen::Vector3d::Zero(), random_points(500, 20.0, 2));
    Rng rng(4);
    std::vector<Eigen::Vector3d> found, bounded;
    std::vector<double> d2, bounded_d2;
    std::size_t cut = 0;
    for (int q = 0; q < 200; ++q) {
        const Eigen::Vector3d query(rng.uniform(-25, 25), rng.uniform(-25, 25), rng.uniform(-4, 4));
        local.knn(query, 5, found, d2);
        const std::size_t n = local.knn_within(query, 5, 1.0, bounded, bounded_d2);
        const auto inside = static_cast<std::size_t>(
            std::count_if(d2.begin(), d2.end(), [](double d) { return d <= 1.0; }));
        ASSERT_EQ(n, inside);
        for (std::size_t i = 0; i < n; ++i) {
            EXPECT_EQ(bounded[i], found[i]);
            EXPECT_EQ(bounded_d2[i], d2[i]);
        }
        cut += n < 5;
    }
    EXPECT_GT(cut, 20U);  // the bound mattered for a good share of the queries
}

TEST(LocalMap, KeepsOnlyTheLastSweepsAndRebuildsCellsAfterMoving) {
    mapping::CellMap map;
    LocalMapConfig config;
    config.num_recent_sweeps = 3;
    config.rebuild_distance_m = 2.0;
    LocalMap local(config);
    for (int i = 0; i < 5; ++i) {
        local.update(map, Eigen::Vector3d(0.5 * i, 0, 0),
                     std::vector<Eigen::Vector3d>(10 + i, Eigen::Vector3d(i, 0, 0)));
    }
    // Sweeps 2, 3, 4 remain: 12 + 13 + 14 points.
    EXPECT_EQ(local.num_recent_points(), 39U);
    // Gathered at x = 0 (first call) and x = 2.0 (moved 2 m): two rebuilds.
    EXPECT_EQ(local.num_cell_rebuilds(), 2U);
}

TEST(LocalMap, EmptyMapFindsNothingAndBadConfigNamesTheField) {
    LocalMap local;
    std::vector<Eigen::Vector3d> found;
    std::vector<double> d2;
    EXPECT_EQ(local.knn(Eigen::Vector3d::Zero(), 5, found, d2), 0U);
    LocalMapConfig bad;
    bad.radius_m = -1.0;
    try {
        LocalMap l(bad);
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("local_map.radius_m"), std::string::npos);
    }
}

}  // namespace
}  // namespace scantling::odometry
