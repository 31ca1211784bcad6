#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/perception/cylinder_ransac.hpp>

namespace scantling::perception {
namespace {

constexpr double kNoiseM = 0.005;      // per-axis position noise of the synthetic surfaces
constexpr double kRadiusM = 1.5;       // a Ø 3 m round wall, seen from inside
constexpr double kFloorZM = -1.0;      // the floor, 1 m below the sensor
constexpr double kNormalNoise = 0.02;  // per-axis noise of the synthetic normals, ~1.1°
// 4000 wall points with 5 mm noise over a 90° arc fix the circle to < 1 mm (1σ); the floor's
// points within the 3 cm band pull it by < 1 mm. The margins leave room for the seed.
constexpr double kCentreTolM = 0.02;
constexpr double kRadiusTolM = 0.01;

struct SceneSpec {
    double arc_deg = 90.0;  ///< of the wall the sensor sees, centred on +x
    std::size_t wall_points = 4000;
    std::size_t floor_points = 1500;
    double outlier_ratio = 0.2;                                         ///< of the whole cloud
    Eigen::Quaterniond q_world_local = Eigen::Quaterniond::Identity();  ///< tilts the axis
    std::uint64_t seed = 1;
};

struct ColumnScene {
    PointCloud cloud;  ///< wall points first, then floor, then outliers
    Eigen::Vector3d axis;
    Eigen::Vector3d centre;  ///< axis point closest to the origin
};

/// A depth camera at the origin inside a vertical round wall (centre (−0.3, 0.2) in the local
/// frame) sees an arc of it from z = −1 to 1 m, the floor in front of it and outliers in its
/// view (clutter and flying pixels from 0.3 to 2 m, bearings a little beyond the arc's).
ColumnScene make_scene(const SceneSpec& spec) {
    Rng rng(spec.seed);
    const Eigen::Vector3d c_local(-0.3, 0.2, 0.0);
    const double half_arc_rad = 0.5 * spec.arc_deg * std::numbers::pi / 180.0;
    PointCloud local;
    for (std::size_t k = 0; k < spec.wall_points; ++k) {
        const double theta = rng.uniform(-half_arc_rad, half_arc_rad);
        const Eigen::Vector3d radial(std::cos(theta), std::sin(theta), 0.0);
        local.points.push_back(c_local + kRadiusM * radial +
                               rng.uniform(kFloorZM, 1.0) * Eigen::Vector3d::UnitZ() +
                               rng.normal3(kNoiseM));
        local.normals.push_back((-radial + rng.normal3(kNormalNoise)).normalized());
    }
    for (std::size_t k = 0; k < spec.floor_points; ++k) {
        const double theta = rng.uniform(-half_arc_rad, half_arc_rad);
        const double rho = kRadiusM * std::sqrt(rng.uniform());
        local.points.push_back(c_local +
                               rho * Eigen::Vector3d(std::cos(theta), std::sin(theta), 0) +
                               Eigen::Vector3d(0, 0, kFloorZM) + rng.normal3(kNoiseM));
        local.normals.push_back(
            (Eigen::Vector3d::UnitZ() + rng.normal3(kNormalNoise)).normalized());
    }
    const double inliers = static_cast<double>(spec.wall_points + spec.floor_points);
    const auto outliers = static_cast<std::size_t>(
        std::llround(inliers * spec.outlier_ratio / (1 - spec.outlier_ratio)));
    for (std::size_t k = 0; k < outliers; ++k) {
        const double bearing_rad = rng.uniform(-1.2 * half_arc_rad, 1.2 * half_arc_rad);
        const double range_m = rng.uniform(0.3, 2.0);
        local.points.emplace_back(range_m * std::cos(bearing_rad), range_m * std::sin(bearing_rad),
                                  rng.uniform(kFloorZM, 1.0));
        local.normals.push_back(rng.normal3(1.0).normalized());
    }
    ColumnScene s;
    for (const auto& p : local.points) s.cloud.points.push_back(spec.q_world_local * p);
    for (const auto& n : local.normals) s.cloud.normals.push_back(spec.q_world_local * n);
    s.axis = spec.q_world_local * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d on_axis = spec.q_world_local * c_local;
    s.centre = on_axis - on_axis.dot(s.axis) * s.axis;
    return s;
}

/// How many of the first `count` cloud indices (one surface of the scene) are inliers.
std::size_t inliers_below(const Cylinder& cyl, std::size_t first, std::size_t count) {
    return static_cast<std::size_t>(
        std::count_if(cyl.inliers.begin(), cyl.inliers.end(),
                      [&](std::size_t i) { return i >= first && i < first + count; }));
}

void expect_column(const std::optional<Cylinder>& cyl, const ColumnScene& s, double centre_tol_m,
                   double radius_tol_m) {
    ASSERT_TRUE(cyl.has_value());
    EXPECT_LT((cyl->centre - s.centre).norm(), centre_tol_m);
    EXPECT_NEAR(cyl->radius_m, kRadiusM, radius_tol_m);
    EXPECT_LT((cyl->axis - s.axis).norm(), 1e-12);
    EXPECT_NEAR(cyl->centre.dot(cyl->axis), 0.0, 1e-9);
    EXPECT_TRUE(std::is_sorted(cyl->inliers.begin(), cyl->inliers.end()));
    EXPECT_NEAR(cyl->rms_m, kNoiseM, 0.5 * kNoiseM);
}

TEST(FitCylinder, RecoversNinetyDegreeArcSeenFromInsideWithFloorAndTwentyPercentOutliers) {
    ColumnScene s = make_scene({});
    s.cloud.normals.clear();
    const auto cyl = fit_cylinder(s.cloud, s.axis);
    expect_column(cyl, s, kCentreTolM, kRadiusTolM);
    // Every wall point lies within 6σ of the circle; the floor's rim and outliers in the band
    // add ~2 %.
    EXPECT_GE(inliers_below(*cyl, 0, 4000), 3990u);
    EXPECT_LE(cyl->inliers.size(), 4200u);
}

TEST(FitCylinder, RecoversNinetyDegreeArcWithNormalsAndRejectsTheFloor) {
    const ColumnScene s = make_scene({.seed = 2});
    const auto cyl = fit_cylinder(s.cloud, s.axis);
    expect_column(cyl, s, kCentreTolM, kRadiusTolM);
    EXPECT_GE(inliers_below(*cyl, 0, 4000), 3990u);
    EXPECT_EQ(inliers_below(*cyl, 4000, 1500), 0u);  // floor normals are along the axis
}

TEST(FitCylinder, RecoversFortyDegreeArc) {
    // A 40° arc is a 1 m chord with a 9 cm sagitta: curvature, hence radius and the centre
    // along the bisector, are ~5× less certain than over 90° (σ_R ≈ 3 mm with 8000 points).
    for (const bool with_normals : {false, true}) {
        SCOPED_TRACE(with_normals ? "with normals" : "positions only");
        ColumnScene s = make_scene({.arc_deg = 40.0, .wall_points = 8000, .seed = 3});
        if (!with_normals) s.cloud.normals.clear();
        expect_column(fit_cylinder(s.cloud, s.axis), s, kCentreTolM, kRadiusTolM);
    }
}

TEST(FitCylinder, RecoversTiltedAxisGivenUnnormalised) {
    const Eigen::Quaterniond tilt(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 0).normalized()));
    for (const bool with_normals : {false, true}) {
        SCOPED_TRACE(with_normals ? "with normals" : "positions only");
        ColumnScene s = make_scene({.q_world_local = tilt, .seed = 4});
        if (!with_normals) s.cloud.normals.clear();
        expect_column(fit_cylinder(s.cloud, 2.5 * s.axis), s, kCentreTolM, kRadiusTolM);
    }
}

TEST(FitCylinder, FindsNoCylinderInAFloorSeenWithNormals) {
    // Projected along the axis the floor is a filled sector, which circles can cross; its
    // normals, along the axis, veto every point.
    const ColumnScene s = make_scene({.wall_points = 0, .floor_points = 4000, .seed = 5});
    EXPECT_FALSE(fit_cylinder(s.cloud, s.axis).has_value());
}

TEST(FitCylinder, FindsNoCylinderInAFlatWallAndFloor) {
    // A circle can hug a flat wall over a chord (R = 1.5 m covers 0.85 m of it within 3 cm),
    // but the refit straightens it towards a line, past max_radius_m.
    Rng rng(9);
    PointCloud cloud;
    for (int k = 0; k < 5000; ++k) {
        cloud.points.emplace_back(1.2 + rng.normal(0.0, kNoiseM), rng.uniform(-1.5, 1.5),
                                  rng.uniform(kFloorZM, 1.0));
        cloud.normals.push_back(
            (-Eigen::Vector3d::UnitX() + rng.normal3(kNormalNoise)).normalized());
    }
    for (int k = 0; k < 2000; ++k) {
        cloud.points.emplace_back(rng.uniform(0.3, 1.2), rng.uniform(-1.5, 1.5),
                                  kFloorZM + rng.normal(0.0, kNoiseM));
        cloud.normals.push_back(
            (Eigen::Vector3d::UnitZ() + rng.normal3(kNormalNoise)).normalized());
    }
    EXPECT_FALSE(fit_cylinder(cloud, Eigen::Vector3d::UnitZ()).has_value());
    cloud.normals.clear();
    EXPECT_FALSE(fit_cylinder(cloud, Eigen::Vector3d::UnitZ()).has_value());
}

TEST(FitCylinder, SameSeedGivesIdenticalCylinder) {
    const ColumnScene s = make_scene({.seed = 6});
    const auto a = fit_cylinder(s.cloud, s.axis);
    const auto b = fit_cylinder(s.cloud, s.axis);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->centre, b->centre);
    EXPECT_EQ(a->radius_m, b->radius_m);
    EXPECT_EQ(a->inliers, b->inliers);
    EXPECT_EQ(a->covariance, b->covariance);
}

TEST(FitCylinder, CovarianceMatchesTheScatterOverNoiseDraws) {
    // 30 clean 60° arcs: the spread of the radius and centre estimates must match the
    // covariance the refit reports (within the ±35 % a 30-sample standard deviation allows).
    constexpr int kDraws = 30;
    double sum_sq_radius = 0.0, sum_sq_centre = 0.0, var_radius = 0.0, var_centre = 0.0;
    for (int k = 0; k < kDraws; ++k) {
        const ColumnScene s = make_scene({.arc_deg = 60.0,
                                          .wall_points = 2000,
                                          .floor_points = 0,
                                          .outlier_ratio = 0.0,
                                          .seed = 100 + static_cast<std::uint64_t>(k)});
        const auto cyl = fit_cylinder(s.cloud, s.axis);
        ASSERT_TRUE(cyl.has_value());
        sum_sq_radius += std::pow(cyl->radius_m - kRadiusM, 2);
        sum_sq_centre += (cyl->centre - s.centre).squaredNorm();
        var_radius += cyl->covariance(2, 2);
        var_centre += cyl->covariance(0, 0) + cyl->covariance(1, 1);
        EXPECT_TRUE(cyl->covariance.isApprox(cyl->covariance.transpose()));
    }
    EXPECT_NEAR(std::sqrt(sum_sq_radius / var_radius), 1.0, 0.35);
    EXPECT_NEAR(std::sqrt(sum_sq_centre / var_centre), 1.0, 0.35);
}

TEST(FitCylinder, EmptyOrTooSmallCloudGivesNone) {
    EXPECT_FALSE(fit_cylinder(PointCloud{}, Eigen::Vector3d::UnitZ()).has_value());
    const ColumnScene s = make_scene({.wall_points = 150, .floor_points = 0, .outlier_ratio = 0});
    EXPECT_FALSE(fit_cylinder(s.cloud, s.axis).has_value());  // 150 < min_inliers = 200
}

TEST(FitCylinder, ThrowsInputErrorForNonFiniteCloudOrBadAxis) {
    ColumnScene s = make_scene({.seed = 7});
    EXPECT_THROW(fit_cylinder(s.cloud, Eigen::Vector3d::Zero()), InputError);
    EXPECT_THROW(fit_cylinder(s.cloud, Eigen::Vector3d(0, NAN, 1)), InputError);
    s.cloud.normals.pop_back();
    EXPECT_THROW(fit_cylinder(s.cloud, s.axis), InputError);
    s.cloud.normals.clear();
    s.cloud.points[3].z() = std::numeric_limits<double>::infinity();
    EXPECT_THROW(fit_cylinder(s.cloud, s.axis), InputError);
}

void expect_config_error(const CylinderRansacConfig& config, const std::string& field) {
    try {
        config.validate();
        ADD_FAILURE() << "no ConfigError for " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("cylinder_ransac." + field), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(fit_cylinder(PointCloud{}, Eigen::Vector3d::UnitZ(), config), ConfigError);
}

TEST(CylinderRansacConfig, RejectsImpossibleValuesNamingTheField) {
    EXPECT_NO_THROW(CylinderRansacConfig{}.validate());
    const auto with = [](auto edit) {
        CylinderRansacConfig c;
        edit(c);
        return c;
    };
    expect_config_error(with([](auto& c) { c.distance_threshold_m = 0.0; }),
                        "distance_threshold_m");
    expect_config_error(with([](auto& c) { c.normal_threshold_deg = -5.0; }),
                        "normal_threshold_deg");
    expect_config_error(with([](auto& c) { c.normal_threshold_deg = NAN; }),
                        "normal_threshold_deg");
    expect_config_error(with([](auto& c) { c.min_radius_m = 0.0; }), "min_radius_m");
    expect_config_error(with([](auto& c) { c.max_radius_m = 0.3; }), "max_radius_m");
    expect_config_error(with([](auto& c) { c.max_radius_m = INFINITY; }), "max_radius_m");
    expect_config_error(with([](auto& c) { c.min_inliers = 2; }), "min_inliers");
    expect_config_error(with([](auto& c) { c.iterations = -1; }), "iterations");
}

}  // namespace
}  // namespace scantling::perception
