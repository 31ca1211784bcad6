// Column structure (SPEC §7 art. F) on ray-cast synthetic depth frames inside a round column.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/perception/column_structure.hpp>

namespace scantling::perception {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNoiseM = 0.005;  // per-axis position noise: the L515 at ~2 m
constexpr double kFloorZM = -1.0;  // the deck below the sensor
constexpr double kTopZM = 1.0;     // the wall's top by default
// ~5000 wall points with 5 mm noise over a ≥ 60° arc fix the circle to a few mm (1σ); the
// margins leave room for the seed (cylinder_ransac_test.cpp measures the same fit).
constexpr double kCentreTolM = 0.02;
constexpr double kRadiusTolM = 0.01;
// A plate of ~2000 points with 5 mm noise has a normal good to ~0.1° and an offset to ~1 mm;
// its distance from the axis also carries the centre's error.
constexpr double kNormalTolDeg = 1.0;
constexpr double kDowncomerTolM = 0.01;
constexpr double kDowncomerDistanceM = 1.05;  // the sim's: radius 1.5 m − downcomer width 0.45 m

/// A vertical chord plate: its horizontal direction from the axis and its z range.
struct PlateSpec {
    /// Of the direction from the axis to the plate: the chord then spans azimuths 29°–121°,
    /// leaving ~70° of wall and a 0.75 m wide piece of the plate in view.
    double azimuth_deg = 75.0;
    double distance_m = kDowncomerDistanceM;
    double z_min_m = kFloorZM;
    double z_max_m = kTopZM;
};

struct SceneSpec {
    double radius_m = 1.5;
    Eigen::Vector2d centre{0.3, -0.2};  ///< the axis, in the sensor's frame
    std::optional<PlateSpec> plate{};
    double top_z_m = kTopZM;  ///< the wall's top
    bool ceiling = false;     ///< a deck at top_z_m
    std::size_t rays = 8000;
    double outlier_ratio = 0.1;
    std::uint64_t seed = 1;
};

/// A ray from the origin; hits are ray parameters t (the ray is unit).
struct Ray {
    Eigen::Vector3d d;
    std::optional<double> hit;
    void offer(double t) {
        if (t > 0.0 && (!hit || t < *hit)) hit = t;
    }
};

void hit_wall(Ray& ray, const SceneSpec& s) {
    const Eigen::Vector2d o = -s.centre, d = ray.d.head<2>();
    const double a = d.squaredNorm(), b = 2.0 * o.dot(d),
                 c = o.squaredNorm() - s.radius_m * s.radius_m;
    const double t = (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);  // inside: the far root
    const double z = t * ray.d.z();
    if (z >= kFloorZM && z <= s.top_z_m) ray.offer(t);
}

void hit_horizontal(Ray& ray, double z_m) {
    if (ray.d.z() * z_m > 0.0) ray.offer(z_m / ray.d.z());
}

void hit_plate(Ray& ray, const SceneSpec& s, const PlateSpec& plate) {
    const double a = plate.azimuth_deg * kPi / 180.0;
    const Eigen::Vector2d n(std::cos(a), std::sin(a));
    const double t = (n.dot(s.centre) + plate.distance_m) / n.dot(ray.d.head<2>());
    const Eigen::Vector3d p = t * ray.d;
    if (p.z() >= plate.z_min_m && p.z() <= plate.z_max_m) ray.offer(t);  // chord: inside anyway
}

/// A depth camera at the origin, 0.36 m off the axis, looking along +x and tilted down
/// (bearings ±40°, elevations −50° to +20°: a little wider than an L515) ray-cast into the
/// column, plus outliers in its view. It sees ~100° of the wall, or ~55° beside the plate.
PointCloud make_scene(const SceneSpec& s) {
    Rng rng(s.seed);
    PointCloud cloud;
    for (std::size_t k = 0; k < s.rays; ++k) {
        const double bearing = rng.uniform(-40.0, 40.0) * kPi / 180.0;
        const double elevation = rng.uniform(-50.0, 20.0) * kPi / 180.0;
        Ray ray{Eigen::Vector3d(std::cos(elevation) * std::cos(bearing),
                                std::cos(elevation) * std::sin(bearing), std::sin(elevation)),
                std::nullopt};
        hit_wall(ray, s);
        hit_horizontal(ray, kFloorZM);
        if (s.ceiling) hit_horizontal(ray, s.top_z_m);
        if (s.plate) hit_plate(ray, s, *s.plate);
        if (ray.hit) cloud.points.push_back(*ray.hit * ray.d + rng.normal3(kNoiseM));
    }
    const auto outliers = static_cast<std::size_t>(
        std::llround(static_cast<double>(cloud.size()) * s.outlier_ratio / (1 - s.outlier_ratio)));
    for (std::size_t k = 0; k < outliers; ++k) {
        const double bearing = rng.uniform(-40.0, 40.0) * kPi / 180.0;
        const double range_m = rng.uniform(0.3, 2.5);
        cloud.points.emplace_back(range_m * std::cos(bearing), range_m * std::sin(bearing),
                                  rng.uniform(kFloorZM, s.top_z_m));
    }
    return cloud;
}

ColumnStructure detect(const SceneSpec& s, const ColumnStructureConfig& config = {}) {
    return detect_column_structure(make_scene(s), Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero(),
                                   config);
}

void expect_wall(const ColumnStructure& found, const SceneSpec& s) {
    ASSERT_TRUE(found.wall.has_value()) << found.status;
    EXPECT_LT((found.wall->centre.head<2>() - s.centre).norm(), kCentreTolM);
    EXPECT_NEAR(found.wall->radius_m, s.radius_m, kRadiusTolM);
    ASSERT_TRUE(found.axis_point.has_value());
    EXPECT_NEAR(found.axis_point->z(), 0.0, 1e-9);  // at the viewpoint's height
    EXPECT_LT((found.axis_point->head<2>() - s.centre).norm(), kCentreTolM);
}

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / kPi;
}

TEST(ColumnStructure, FindsWallAndFloorInANinetyDegreeViewWithTenPercentOutliers) {
    const SceneSpec s;
    const ColumnStructure found = detect(s);
    expect_wall(found, s);
    EXPECT_TRUE(found.diameter_ok) << found.status;
    ASSERT_TRUE(found.floor.has_value());
    EXPECT_LT(angle_deg(found.floor->normal, Eigen::Vector3d::UnitZ()), kNormalTolDeg);
    EXPECT_NEAR(found.floor->signed_distance(Eigen::Vector3d::Zero()), -kFloorZM, 0.005);
    EXPECT_FALSE(found.ceiling.has_value());
    EXPECT_FALSE(found.downcomer.has_value());
    EXPECT_FALSE(found.registrable());
    EXPECT_NE(found.status.find("no downcomer"), std::string::npos) << found.status;
    EXPECT_NE(found.status.find("no ceiling"), std::string::npos) << found.status;
}

TEST(ColumnStructure, FindsCeilingAboveTheViewpoint) {
    // Low enough for the camera's 20° upwards to reach it before the wall.
    const ColumnStructure found = detect({.top_z_m = 0.4, .ceiling = true, .seed = 2});
    ASSERT_TRUE(found.floor && found.ceiling) << found.status;
    EXPECT_LT(angle_deg(found.ceiling->normal, -Eigen::Vector3d::UnitZ()), kNormalTolDeg);
    EXPECT_NEAR(found.ceiling->centroid.z(), 0.4, 0.01);
    EXPECT_TRUE(found.diameter_ok) << found.status;
}

TEST(ColumnStructure, FindsDowncomerChordWithinOneDegreeAndOneCentimetre) {
    const SceneSpec s{.plate = PlateSpec{}, .seed = 3};
    const ColumnStructure found = detect(s);
    expect_wall(found, s);
    ASSERT_TRUE(found.downcomer.has_value()) << found.status;
    EXPECT_TRUE(found.registrable());
    EXPECT_EQ(found.downcomer_candidates, 1u);
    const double a = PlateSpec{}.azimuth_deg * kPi / 180.0;
    const Eigen::Vector3d axis_to_plate(std::cos(a), std::sin(a), 0.0);
    // The sensor is on the axis' side: the seen face looks back towards the axis.
    EXPECT_LT(angle_deg(found.downcomer_normal, -axis_to_plate), kNormalTolDeg);
    EXPECT_LT(angle_deg(found.downcomer->normal, -axis_to_plate), kNormalTolDeg);
    EXPECT_NEAR(found.downcomer_offset_m, -kDowncomerDistanceM, kDowncomerTolM);
    EXPECT_LT(angle_deg(found.downcomer_direction(), axis_to_plate), kNormalTolDeg);
    EXPECT_NEAR(found.downcomer_normal.z(), 0.0, 1e-12);
}

TEST(ColumnStructure, DiameterCheckFailsForATwoAndAHalfMetreColumn) {
    const SceneSpec s{.radius_m = 1.25, .plate = PlateSpec{.distance_m = 0.85}, .seed = 4};
    const ColumnStructure found = detect(s);
    expect_wall(found, s);  // the wall is fitted; it is just not this column
    EXPECT_FALSE(found.diameter_ok);
    EXPECT_FALSE(found.registrable());
    EXPECT_NE(found.status.find("NOT within"), std::string::npos) << found.status;
}

TEST(ColumnStructure, NoDowncomerWhenItIsBehindTheSensor) {
    const SceneSpec s{.plate = PlateSpec{.azimuth_deg = 180.0}, .seed = 5};
    const ColumnStructure found = detect(s);
    expect_wall(found, s);
    EXPECT_FALSE(found.downcomer.has_value());
    EXPECT_EQ(found.downcomer_candidates, 0u);
}

TEST(ColumnStructure, PlateAsLowAsABeamIsNoDowncomer) {
    // A chord inside the wall but 0.2 m high, like a support beam's face (here standing on the
    // deck, where the camera sees it).
    const SceneSpec s{.plate = PlateSpec{.z_min_m = kFloorZM, .z_max_m = kFloorZM + 0.2},
                      .seed = 6};
    const ColumnStructure found = detect(s);
    expect_wall(found, s);
    EXPECT_FALSE(found.downcomer.has_value()) << found.status;
}

TEST(ColumnStructure, KnownDiameterPinsTheAxisOfAShortArcBesideTheDowncomer) {
    // The plate hides all but ~16° of the wall: the free fit's centre and radius slide together
    // along the arc (~4 cm here, still within the diameter tolerance); the axis refitted with
    // the known radius does not. No outliers: with 10 % the short arc fails the diameter check.
    const SceneSpec s{
        .plate = PlateSpec{.azimuth_deg = 20.0}, .rays = 20000, .outlier_ratio = 0.0, .seed = 6};
    const ColumnStructure found = detect(s);
    ASSERT_TRUE(found.diameter_ok && found.axis_point) << found.status;
    EXPECT_LT((found.axis_point->head<2>() - s.centre).norm(), kCentreTolM / 2);
    ColumnStructureConfig published;
    published.axis_from_known_diameter = false;
    const ColumnStructure free = detect(s, published);
    ASSERT_TRUE(free.axis_point.has_value());
    EXPECT_LT((free.axis_point->head<2>() - free.wall->centre.head<2>()).norm(), 1e-12);
}

TEST(ColumnStructure, WorksInATiltedFrameWithUnnormalisedUp) {
    const SceneSpec s{.plate = PlateSpec{}, .seed = 7};
    const Eigen::Isometry3d T_new_old(
        Eigen::Translation3d(0.4, -1.0, 2.0) *
        Eigen::AngleAxisd(0.5, Eigen::Vector3d(1.0, 2.0, 0.5).normalized()));
    const PointCloud cloud = transformed(make_scene(s), T_new_old);
    const Eigen::Vector3d up = T_new_old.linear() * Eigen::Vector3d::UnitZ();
    const ColumnStructure found =
        detect_column_structure(cloud, 3.0 * up, T_new_old.translation(), {});
    ASSERT_TRUE(found.axis_point && found.downcomer) << found.status;
    const Eigen::Vector3d axis_old = T_new_old.inverse() * *found.axis_point;
    EXPECT_LT((axis_old.head<2>() - s.centre).norm(), kCentreTolM);
    EXPECT_NEAR(axis_old.z(), 0.0, 1e-9);
    EXPECT_LT(angle_deg(found.wall->axis, up), 1e-9);
    EXPECT_NEAR(found.downcomer_offset_m, -kDowncomerDistanceM, kDowncomerTolM);
    EXPECT_TRUE(found.diameter_ok);
}

TEST(ColumnStructure, SameSeedGivesIdenticalStructure) {
    const PointCloud cloud = make_scene({.plate = PlateSpec{}, .seed = 8});
    const auto a = detect_column_structure(cloud, Eigen::Vector3d::UnitZ(), {0, 0, 0});
    const auto b = detect_column_structure(cloud, Eigen::Vector3d::UnitZ(), {0, 0, 0});
    ASSERT_TRUE(a.wall && b.wall && a.downcomer && b.downcomer);
    EXPECT_EQ(a.wall->centre, b.wall->centre);
    EXPECT_EQ(a.wall->inliers, b.wall->inliers);
    EXPECT_EQ(a.downcomer->inliers, b.downcomer->inliers);
    EXPECT_EQ(a.status, b.status);
}

TEST(ColumnStructure, EmptyCloudFindsNothing) {
    const auto found = detect_column_structure({}, Eigen::Vector3d::UnitZ(), {0, 0, 0});
    EXPECT_FALSE(found.floor || found.ceiling || found.wall || found.downcomer);
    EXPECT_FALSE(found.diameter_ok);
    EXPECT_NE(found.status.find("empty"), std::string::npos) << found.status;
}

TEST(ColumnStructure, OnlyAFloorFindsNoWallAndSaysSo) {
    PointCloud cloud;
    Rng rng(9);
    for (int k = 0; k < 3000; ++k) {
        cloud.points.emplace_back(rng.uniform(0.5, 2.0), rng.uniform(-1, 1), kFloorZM);
    }
    const auto found = detect_column_structure(cloud, Eigen::Vector3d::UnitZ(), {0, 0, 0});
    EXPECT_TRUE(found.floor.has_value());
    EXPECT_FALSE(found.wall || found.downcomer);
    EXPECT_NE(found.status.find("no wall"), std::string::npos) << found.status;
}

TEST(ColumnStructure, ThrowsInputErrorForNonFiniteInput) {
    PointCloud cloud = make_scene({.rays = 500, .seed = 10});
    const Eigen::Vector3d up = Eigen::Vector3d::UnitZ(), origin = Eigen::Vector3d::Zero();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(detect_column_structure(cloud, Eigen::Vector3d::Zero(), origin), InputError);
    EXPECT_THROW(detect_column_structure(cloud, {0, nan, 1}, origin), InputError);
    EXPECT_THROW(detect_column_structure(cloud, up, {nan, 0, 0}), InputError);
    cloud.normals.resize(3);
    EXPECT_THROW(detect_column_structure(cloud, up, origin), InputError);
    cloud.normals.clear();
    cloud.points[7].y() = nan;
    EXPECT_THROW(detect_column_structure(cloud, up, origin), InputError);
}

void expect_config_error(const ColumnStructureConfig& config, const std::string& field) {
    try {
        config.validate();
        ADD_FAILURE() << "no ConfigError for " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("column." + field), std::string::npos) << e.what();
    }
    EXPECT_THROW(detect_column_structure({}, Eigen::Vector3d::UnitZ(), {0, 0, 0}, config),
                 ConfigError);
}

TEST(ColumnStructureConfig, RejectsImpossibleValuesNamingTheField) {
    EXPECT_NO_THROW(ColumnStructureConfig{}.validate());
    const auto with = [](auto edit) {
        ColumnStructureConfig c;
        edit(c);
        return c;
    };
    expect_config_error(with([](auto& c) { c.diameter_m = 0.0; }), "diameter_m");
    expect_config_error(with([](auto& c) { c.diameter_tolerance_m = 3.0; }),
                        "diameter_tolerance_m");
    expect_config_error(with([](auto& c) { c.vertical_tolerance_deg = NAN; }),
                        "vertical_tolerance_deg");
    expect_config_error(with([](auto& c) { c.vertical_tolerance_deg = 45.0; }),
                        "vertical_tolerance_deg");
    expect_config_error(with([](auto& c) { c.min_chord_depth_m = 1.5; }), "min_chord_depth_m");
    expect_config_error(with([](auto& c) { c.min_downcomer_height_m = -1.0; }),
                        "min_downcomer_height_m");
    expect_config_error(with([](auto& c) { c.planes.max_planes = 0; }), "planes.max_planes");
    expect_config_error(with([](auto& c) { c.cylinder.iterations = 0; }), "cylinder.iterations");
    // The wall search must reach every accepted diameter.
    expect_config_error(with([](auto& c) { c.cylinder.min_radius_m = 1.46; }),
                        "cylinder.min_radius_m");
    expect_config_error(with([](auto& c) { c.cylinder.max_radius_m = 1.54; }),
                        "cylinder.max_radius_m");
    try {
        with([](auto& c) { c.diameter_m = -1.0; }).validate("tower");
        ADD_FAILURE() << "no ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("tower.diameter_m"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace scantling::perception
