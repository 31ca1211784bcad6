#include <scantling/perception/feature_map.hpp>

#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>

namespace scantling::perception {
namespace {

// Camera looking along world +x: optical z = world x, optical x = −world y, optical y = −world z.
Eigen::Isometry3d camera_looking_along_x(const Eigen::Vector3d& position) {
    Eigen::Matrix3d R_world_camera;
    R_world_camera.col(0) = -Eigen::Vector3d::UnitY();
    R_world_camera.col(1) = -Eigen::Vector3d::UnitZ();
    R_world_camera.col(2) = Eigen::Vector3d::UnitX();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R_world_camera;
    T.translation() = position;
    return T;
}

// A 5 × 5 grid of points 0.2 m apart on the plane x = 2 m (camera frame: depth 2 m).
std::vector<Eigen::Vector3d> grid_in_camera() {
    std::vector<Eigen::Vector3d> points;
    for (int i = -2; i <= 2; ++i) {
        for (int j = -2; j <= 2; ++j) points.emplace_back(0.2 * i, 0.2 * j, 2.0);
    }
    return points;
}

TEST(FeatureMap, ConfirmsPointsReobservedWithinTheWindowAndCountsEachOnce) {
    FeatureMap map;
    const Eigen::Isometry3d T = camera_looking_along_x(Eigen::Vector3d::Zero());
    const std::vector<Eigen::Vector3d> grid = grid_in_camera();
    FeatureFrameStats first = map.insert(grid, T);
    EXPECT_EQ(first.created, grid.size());
    EXPECT_EQ(map.num_confirmed(), 0u);
    for (std::size_t f = 1; f <= map.config().culling_window_frames; ++f) map.insert(grid, T);
    EXPECT_EQ(map.num_confirmed(), grid.size());
    EXPECT_EQ(map.num_candidates(), 0u);
    EXPECT_EQ(map.confirmed_cloud().points.size(), grid.size());
    // Summing the raw frames would give 4 × 25 points.
    EXPECT_EQ(map.points().size(), grid.size());
}

TEST(FeatureMap, CullsCandidatesSeenOnlyOnce) {
    FeatureMap map;
    const Eigen::Isometry3d T = camera_looking_along_x(Eigen::Vector3d::Zero());
    // Each frame sees a fresh grid shifted by 1 m: nothing is ever re-observed.
    for (int f = 0; f < 10; ++f) {
        std::vector<Eigen::Vector3d> grid = grid_in_camera();
        for (Eigen::Vector3d& p : grid) p.z() += 1.0 * f;
        map.insert(grid, T);
    }
    EXPECT_EQ(map.num_confirmed(), 0u);
    EXPECT_LE(map.num_candidates(), 25u * map.config().culling_window_frames);
}

TEST(FeatureMap, AveragesNoisyObservationsIntoOnePoint) {
    constexpr double kNoise_m = 0.005;      // well inside the 4 cm merge radius
    constexpr double kTolerance_m = 0.003;  // mean of 20 draws: σ / √20 ≈ 1.1 mm, 3σ margin
    FeatureMap map;
    const Eigen::Isometry3d T = camera_looking_along_x(Eigen::Vector3d::Zero());
    Rng rng(7);
    const Eigen::Vector3d truth_camera(0.1, -0.1, 2.0);
    for (int f = 0; f < 20; ++f) {
        const std::vector<Eigen::Vector3d> frame{truth_camera + rng.normal3(kNoise_m)};
        map.insert(frame, T);
    }
    ASSERT_EQ(map.num_confirmed(), 1u);
    const Eigen::Vector3d truth_world = T * truth_camera;
    EXPECT_LT((map.confirmed_cloud().points[0] - truth_world).norm(), kTolerance_m);
    EXPECT_EQ(map.points()[0].observations, 20u);
}

TEST(FeatureMap, DropsASecondFramePointOnTheSameMapPoint) {
    FeatureMap map;
    const Eigen::Isometry3d T = camera_looking_along_x(Eigen::Vector3d::Zero());
    const std::vector<Eigen::Vector3d> pair{{0.0, 0.0, 2.0}, {0.01, 0.0, 2.0}};
    const FeatureFrameStats stats = map.insert(pair, T);
    EXPECT_EQ(stats.created, 1u);
    EXPECT_EQ(stats.dropped, 1u);
    EXPECT_EQ(map.points().size(), 1u);
}

TEST(FeatureMap, FoundRatioCullsCandidatesVisibleButNotReobserved) {
    FeatureMapConfig config;
    config.culling_window_frames = 10;
    config.min_found_ratio = 0.5;
    FeatureMap map(config);
    const Eigen::Isometry3d T = camera_looking_along_x(Eigen::Vector3d::Zero());
    const std::vector<Eigen::Vector3d> one{{0.0, 0.0, 2.0}};
    map.insert(one, T);
    map.insert(std::span<const Eigen::Vector3d>{}, T);  // visible, not found: 1/2
    EXPECT_EQ(map.num_candidates(), 1u);
    map.insert(std::span<const Eigen::Vector3d>{}, T);  // 1/3 < 0.5
    EXPECT_EQ(map.num_candidates(), 0u);
    EXPECT_FALSE(map.points()[0].alive);
}

TEST(FeatureMap, CandidatesOutOfViewAreNotCulledByTheFoundRatio) {
    FeatureMapConfig config;
    config.culling_window_frames = 10;
    config.min_found_ratio = 0.5;
    FeatureMap map(config);
    const std::vector<Eigen::Vector3d> one{{0.0, 0.0, 2.0}};
    map.insert(one, camera_looking_along_x(Eigen::Vector3d::Zero()));
    // Camera 5 m past the point, looking away from it.
    const Eigen::Isometry3d away = camera_looking_along_x(Eigen::Vector3d(5.0, 0.0, 0.0));
    for (int f = 0; f < 5; ++f) map.insert(std::span<const Eigen::Vector3d>{}, away);
    EXPECT_EQ(map.num_candidates(), 1u);
    EXPECT_EQ(map.points()[0].visible, 1u);
}

TEST(FeatureMap, IsDeterministic) {
    auto run = [] {
        FeatureMap map;
        Rng rng(3);
        for (int f = 0; f < 30; ++f) {
            std::vector<Eigen::Vector3d> frame;
            for (int k = 0; k < 200; ++k) {
                frame.emplace_back(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 2.0);
            }
            map.insert(frame, camera_looking_along_x(Eigen::Vector3d(0.0, 0.01 * f, 0.0)));
        }
        return map.confirmed_cloud().points;
    };
    const std::vector<Eigen::Vector3d> a = run();
    const std::vector<Eigen::Vector3d> b = run();
    ASSERT_FALSE(a.empty());
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);
}

TEST(FeatureMap, RejectsBadConfigAndInput) {
    FeatureMapConfig config;
    config.merge_radius_m = 0.0;
    EXPECT_THROW(FeatureMap{config}, ConfigError);
    config = {};
    config.min_observations = 0;
    EXPECT_THROW(FeatureMap{config}, ConfigError);
    config = {};
    config.min_found_ratio = 1.5;
    EXPECT_THROW(FeatureMap{config}, ConfigError);
    config = {};
    config.max_depth_m = config.min_depth_m;
    EXPECT_THROW(FeatureMap{config}, ConfigError);
    try {
        config = {};
        config.culling_window_frames = 0;
        FeatureMap{config};
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("feature_map.culling_window_frames"),
                  std::string::npos);
    }
    FeatureMap map;
    const std::vector<Eigen::Vector3d> bad{{0.0, std::numeric_limits<double>::quiet_NaN(), 1.0}};
    EXPECT_THROW(map.insert(bad, Eigen::Isometry3d::Identity()), InputError);
}

}  // namespace
}  // namespace scantling::perception
