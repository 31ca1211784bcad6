#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/perception/plane_ransac.hpp>

namespace scantling::perception {
namespace {

constexpr double kNoiseM = 0.005;  // per-axis position noise of the synthetic surfaces
// PCA on ≥ 2000 points with 5 mm noise over 2–3 m planes is good to ~0.05° and < 1 mm; the
// strips of neighbouring planes within the 2 cm band add a small bias.
constexpr double kNormalTolDeg = 1.0;
constexpr double kOffsetTolM = 0.005;
// Without normals a plane also takes the 2 cm strip of each neighbour (~1 % of it) and the
// outliers in its slab (~1 %); with normals both are rejected.
constexpr double kCountTolPositionsOnly = 0.03;
constexpr double kCountTolWithNormals = 0.01;
constexpr double kNormalNoiseRad = 0.01;  // per-axis noise of the synthetic normals, ~0.6°

struct TruePlane {
    Eigen::Vector3d normal;  ///< facing the origin (the sensor)
    double offset_m;
    std::size_t count;
};

struct Scene {
    PointCloud cloud;
    std::vector<TruePlane> planes;  ///< largest first
};

/// `count` points uniform on the rectangle corner + s·u + t·v (s, t ∈ [0, 1]), with noise;
/// normals are the true normal with noise, of either sign when `flip_signs`.
void add_rectangle(Scene& scene, Rng& rng, const Eigen::Vector3d& corner, const Eigen::Vector3d& u,
                   const Eigen::Vector3d& v, std::size_t count, bool flip_signs) {
    Eigen::Vector3d n = u.cross(v).normalized();
    if (n.dot(-corner) < 0.0) n = -n;
    scene.planes.push_back({n, -n.dot(corner), count});
    for (std::size_t k = 0; k < count; ++k) {
        const Eigen::Vector3d p = corner + rng.uniform() * u + rng.uniform() * v;
        scene.cloud.points.push_back(p + rng.normal3(kNoiseM));
        const double sign = flip_signs && rng.uniform() < 0.5 ? -1.0 : 1.0;
        scene.cloud.normals.push_back(sign * (n + rng.normal3(kNormalNoiseRad)).normalized());
    }
}

/// Uniform points with random normals in the box [lo, hi].
void add_outliers(Scene& scene, Rng& rng, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                  std::size_t count) {
    for (std::size_t k = 0; k < count; ++k) {
        scene.cloud.points.emplace_back(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()),
                                        rng.uniform(lo.z(), hi.z()));
        scene.cloud.normals.push_back(rng.normal3(1.0).normalized());
    }
}

/// A room corner seen from the origin: floor z = −1 (4000 points), wall x = 3 (3000), wall
/// y = 1.5 (2000), and 2250 outliers (20 %) in the room's box.
Scene box_corner(std::uint64_t seed, bool flip_signs = false) {
    Rng rng(seed);
    Scene s;
    const Eigen::Vector3d lo(0.0, -1.5, -1.0);
    add_rectangle(s, rng, lo, {3, 0, 0}, {0, 3, 0}, 4000, flip_signs);
    add_rectangle(s, rng, {3.0, -1.5, -1.0}, {0, 3, 0}, {0, 0, 2}, 3000, flip_signs);
    add_rectangle(s, rng, {0.0, 1.5, -1.0}, {3, 0, 0}, {0, 0, 2}, 2000, flip_signs);
    add_outliers(s, rng, lo, {3.0, 1.5, 1.0}, 2250);
    return s;
}

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 /
           std::numbers::pi;
}

/// Found planes match the truth in order: normal, offset, inlier count, sorted inliers.
void expect_planes(const std::vector<Plane>& found, const std::vector<TruePlane>& truth,
                   double count_tol) {
    ASSERT_EQ(found.size(), truth.size());
    for (std::size_t k = 0; k < truth.size(); ++k) {
        SCOPED_TRACE("plane " + std::to_string(k));
        EXPECT_LT(angle_deg(found[k].normal, truth[k].normal), kNormalTolDeg);
        EXPECT_NEAR(found[k].offset_m, truth[k].offset_m, kOffsetTolM);
        const double count = static_cast<double>(truth[k].count);
        EXPECT_NEAR(static_cast<double>(found[k].inliers.size()), count, count_tol * count);
        EXPECT_TRUE(std::is_sorted(found[k].inliers.begin(), found[k].inliers.end()));
        EXPECT_NEAR(found[k].rms_m, kNoiseM, 0.5 * kNoiseM);
        EXPECT_LT(std::abs(found[k].signed_distance(found[k].centroid)), 1e-9);
    }
}

TEST(SegmentPlanes, FindsThreeOrthogonalPlanesOfABoxCornerWithTwentyPercentOutliers) {
    Scene s = box_corner(1);
    s.cloud.normals.clear();
    expect_planes(segment_planes(s.cloud), s.planes, kCountTolPositionsOnly);
}

TEST(SegmentPlanes, FindsTheSamePlanesWithNormalsOfEitherSignAndRejectsTheNeighboursStrips) {
    const Scene s = box_corner(2, /*flip_signs=*/true);
    expect_planes(segment_planes(s.cloud), s.planes, kCountTolWithNormals);
}

TEST(SegmentPlanes, SeparatesTwoParallelPlanesTenCentimetresApart) {
    Rng rng(3);
    Scene s;
    add_rectangle(s, rng, {0.0, -1.0, -1.0}, {2, 0, 0}, {0, 2, 0}, 3000, false);
    add_rectangle(s, rng, {0.0, -1.0, -0.9}, {2, 0, 0}, {0, 2, 0}, 2000, false);
    add_outliers(s, rng, {0.0, -1.0, -1.2}, {2.0, 1.0, -0.7}, 500);
    s.cloud.normals.clear();
    // Outliers fill a 0.5 m slab: each 4 cm band takes ~8 % of them (40 points, ≤ 2 %).
    expect_planes(segment_planes(s.cloud), s.planes, kCountTolPositionsOnly);
}

TEST(SegmentPlanes, FindsNoPlaneInUniformNoise) {
    Scene s;
    Rng rng(4);
    // A 4 cm slab of a 2 m cube holds ~2 % of 1000 points, far below min_inliers = 100.
    add_outliers(s, rng, Eigen::Vector3d::Constant(-1.0), Eigen::Vector3d::Constant(1.0), 1000);
    EXPECT_TRUE(segment_planes(s.cloud).empty());
    s.cloud.normals.clear();
    EXPECT_TRUE(segment_planes(s.cloud).empty());
}

TEST(SegmentPlanes, StopsAtMaxPlanesKeepingTheLargest) {
    Scene s = box_corner(5);
    s.cloud.normals.clear();
    PlaneRansacConfig config;
    config.max_planes = 2;
    s.planes.resize(2);
    expect_planes(segment_planes(s.cloud, config), s.planes, kCountTolPositionsOnly);
}

TEST(SegmentPlanes, SameSeedGivesIdenticalPlanesAndAnotherSeedTheSamePlanes) {
    Scene s = box_corner(6);
    s.cloud.normals.clear();
    const auto a = segment_planes(s.cloud);
    const auto b = segment_planes(s.cloud);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].normal, b[k].normal);
        EXPECT_EQ(a[k].offset_m, b[k].offset_m);
        EXPECT_EQ(a[k].inliers, b[k].inliers);
    }
    PlaneRansacConfig other;
    other.seed = 77;
    expect_planes(segment_planes(s.cloud, other), s.planes, kCountTolPositionsOnly);
}

TEST(SegmentPlanes, EmptyCloudGivesNoPlanes) { EXPECT_TRUE(segment_planes(PointCloud{}).empty()); }

TEST(SegmentPlanes, ThrowsInputErrorForNonFiniteOrInconsistentCloud) {
    Scene s = box_corner(7);
    s.cloud.points[17].y() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(segment_planes(s.cloud), InputError);
    s.cloud.points[17].y() = 0.0;
    s.cloud.normals.pop_back();
    EXPECT_THROW(segment_planes(s.cloud), InputError);
}

/// The config error names "<prefix>.<field>".
void expect_config_error(const PlaneRansacConfig& config, const std::string& field) {
    try {
        config.validate();
        ADD_FAILURE() << "no ConfigError for " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("plane_ransac." + field), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(segment_planes(PointCloud{}, config), ConfigError);
}

TEST(PlaneRansacConfig, RejectsImpossibleValuesNamingTheField) {
    EXPECT_NO_THROW(PlaneRansacConfig{}.validate());
    const auto with = [](auto edit) {
        PlaneRansacConfig c;
        edit(c);
        return c;
    };
    expect_config_error(with([](auto& c) { c.distance_threshold_m = -1.0; }),
                        "distance_threshold_m");
    expect_config_error(with([](auto& c) { c.distance_threshold_m = NAN; }),
                        "distance_threshold_m");
    expect_config_error(with([](auto& c) { c.normal_threshold_deg = 0.0; }),
                        "normal_threshold_deg");
    expect_config_error(with([](auto& c) { c.normal_threshold_deg = 91.0; }),
                        "normal_threshold_deg");
    expect_config_error(with([](auto& c) { c.min_inliers = 2; }), "min_inliers");
    expect_config_error(with([](auto& c) { c.max_planes = 0; }), "max_planes");
    expect_config_error(with([](auto& c) { c.iterations = 0; }), "iterations");
}

TEST(PlaneRansacConfig, MessageUsesTheGivenPrefix) {
    PlaneRansacConfig c;
    c.distance_threshold_m = -1.0;
    try {
        c.validate("detector.planes");
        FAIL() << "no ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "detector.planes.distance_threshold_m = -1, expected finite > 0");
    }
}

TEST(FitPlane, RecoversAnExactPlaneAndOrientsItsNormalTowardsThePointGiven) {
    const Eigen::Vector3d n(1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0);  // n·p = 2 on the plane
    const Eigen::Vector3d a = n.unitOrthogonal();
    const Eigen::Vector3d b = n.cross(a);
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 5; ++i) points.push_back(2.0 * n + (i - 2) * a + (i * i % 3) * b);
    const Plane away = fit_plane(points);  // towards the origin, on the negative side of n
    EXPECT_LT(angle_deg(away.normal, -n), 1e-6);
    EXPECT_NEAR(away.offset_m, 2.0, 1e-12);
    EXPECT_NEAR(away.rms_m, 0.0, 1e-12);
    const Plane towards = fit_plane(points, Eigen::Vector3d(5, 5, 5));
    EXPECT_LT(angle_deg(towards.normal, n), 1e-6);
    EXPECT_NEAR(towards.offset_m, -2.0, 1e-12);
    EXPECT_EQ(towards.inliers.size(), points.size());
}

TEST(FitPlane, RmsEqualsTheNoiseAlongTheNormal) {
    Rng rng(8);
    std::vector<Eigen::Vector3d> points;
    for (int k = 0; k < 20000; ++k) {
        points.emplace_back(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.normal(0.0, kNoiseM));
    }
    const Plane p = fit_plane(points);
    // 20000 samples estimate σ to ±0.5 %; 3 % allows for the fitted plane absorbing a little.
    EXPECT_NEAR(p.rms_m, kNoiseM, 0.03 * kNoiseM);
    EXPECT_LT(angle_deg(p.normal, Eigen::Vector3d::UnitZ()), 0.05);
}

TEST(FitPlane, ThrowsForFewerThanThreeCollinearOrNonFinitePoints) {
    EXPECT_THROW(fit_plane({{0, 0, 0}, {1, 0, 0}}), InputError);
    EXPECT_THROW(fit_plane({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {-3, -3, -3}}), InputError);
    EXPECT_THROW(fit_plane({{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}), InputError);
    EXPECT_THROW(fit_plane({{0, 0, 0}, {1, 0, 0}, {0, NAN, 0}}), InputError);
}

}  // namespace
}  // namespace scantling::perception
