#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/perception/surface_obstacles.hpp>

namespace scantling::perception {
namespace {

// A stop of ~2 s of a rosette LiDAR (~100 k points/s) spread over the 2 m disc around the robot:
// ~16 k points/m², so a 10 mm bead 1 m long gets ~160 points.
constexpr std::size_t kNumPoints = 200000;
constexpr double kViewRadiusM = 2.0;
constexpr double kSensorHeightM = 0.3;  // the LiDAR above the surface: sets the convex horizon
constexpr double kNoiseM = 0.003;       // σ along z, the upper end of the SPEC's 2–3 mm
constexpr double kTankRadiusM = 2.5;    // a small storage tank's wall

enum class Shape { kPlate, kTiltedPlate, kConcave, kConvex };
enum class Truth : std::uint8_t { kSurface, kBead, kBolt, kBracket, kHole, kEdge, kCount };

constexpr double kTiltDeg = 15.0;

struct SceneSpec {
    Shape shape = Shape::kPlate;
    Truth obstacle = Truth::kSurface;  ///< the one obstacle class present (kSurface: none)
    std::size_t num_points = kNumPoints;
    std::uint64_t seed = 7;
};

struct Scene {
    PointCloud cloud;
    std::vector<Truth> truth;  ///< per point: what the point lies on
};

double surface_z_m(Shape shape, double x_m) {
    switch (shape) {
        case Shape::kPlate:
            return 0.0;
        case Shape::kTiltedPlate:
            return std::tan(kTiltDeg * std::numbers::pi / 180.0) * x_m;
        case Shape::kConcave:
            return kTankRadiusM - std::sqrt(kTankRadiusM * kTankRadiusM - x_m * x_m);
        case Shape::kConvex:
            return std::sqrt(kTankRadiusM * kTankRadiusM - x_m * x_m) - kTankRadiusM;
    }
    return 0.0;
}

/// |x| the sensor sees of the surface: a convex wall drops out of view past the tangent from
/// the sensor, x = R·sqrt(1 − (R/(R + h))²) (1.13 m for R = 2.5 m, h = 0.3 m).
double visible_half_width_m(Shape shape) {
    if (shape != Shape::kConvex) return kViewRadiusM;
    const double r = kTankRadiusM / (kTankRadiusM + kSensorHeightM);
    return kTankRadiusM * std::sqrt(1.0 - r * r);
}

double distance_to_segment_m(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                             const Eigen::Vector2d& b) {
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    return (p - (a + t * (b - a))).norm();
}

// Obstacles, all within the convex wall's visible strip |x| < 1.13 m.
// Weld beads: ridges 10 mm wide, 15 mm high, one along the wall's axis, one across its curve.
const std::array<std::array<Eigen::Vector2d, 2>, 2> kBeads{
    {{Eigen::Vector2d(0.5, -1.5), Eigen::Vector2d(0.5, 1.5)},
     {Eigen::Vector2d(-0.9, -0.6), Eigen::Vector2d(0.9, -0.6)}}};
constexpr double kBeadHalfWidthM = 0.005, kBeadHeightM = 0.015;
// Bolts: Ø 20 mm, 20 mm high, on a 0.8 m circle.
constexpr double kBoltRadiusM = 0.01, kBoltHeightM = 0.02, kBoltCircleM = 0.8;
constexpr int kNumBolts = 8;
// A bracket: 100 × 50 mm, 50 mm high.
const Eigen::Vector2d kBracketCentre(0.7, 0.4), kBracketHalf(0.05, 0.025);
constexpr double kBracketHeightM = 0.05;
// A hole, Ø 0.24 m, seen through: its points lie 0.1–0.3 m below the surface.
const Eigen::Vector2d kHoleCentre(0.6, -0.3);
constexpr double kHoleRadiusM = 0.12;
// A plate edge: past y = 1.2 m the surface falls away at 0.15 m + 30 %.
constexpr double kEdgeY = 1.2;

struct Hit {
    Truth truth = Truth::kSurface;
    double above_m = 0.0;  ///< above the surface (negative: below)
};

Hit obstacle_at(Truth obstacle, const Eigen::Vector2d& p, Rng& rng) {
    switch (obstacle) {
        case Truth::kBead:
            for (const auto& b : kBeads) {
                if (distance_to_segment_m(p, b[0], b[1]) <= kBeadHalfWidthM)
                    return {Truth::kBead, kBeadHeightM};
            }
            break;
        case Truth::kBolt:
            for (int k = 0; k < kNumBolts; ++k) {
                const double a = 2.0 * std::numbers::pi * k / kNumBolts;
                const Eigen::Vector2d c(kBoltCircleM * std::cos(a), kBoltCircleM * std::sin(a));
                if ((p - c).norm() <= kBoltRadiusM) return {Truth::kBolt, kBoltHeightM};
            }
            break;
        case Truth::kBracket:
            if (((p - kBracketCentre).cwiseAbs() - kBracketHalf).maxCoeff() <= 0.0)
                return {Truth::kBracket, kBracketHeightM};
            break;
        case Truth::kHole:
            if ((p - kHoleCentre).norm() <= kHoleRadiusM)
                return {Truth::kHole, -rng.uniform(0.1, 0.3)};
            break;
        case Truth::kEdge:
            if (p.y() > kEdgeY) return {Truth::kEdge, -0.15 - 0.3 * (p.y() - kEdgeY)};
            break;
        default:
            break;
    }
    return {};
}

/// Points uniform over the visible part of the 2 m disc, z = surface + obstacle + noise.
Scene make_scene(const SceneSpec& spec) {
    Rng rng(spec.seed);
    Scene scene;
    const double half_width_m = visible_half_width_m(spec.shape);
    while (scene.cloud.size() < spec.num_points) {
        const Eigen::Vector2d p(rng.uniform(-kViewRadiusM, kViewRadiusM),
                                rng.uniform(-kViewRadiusM, kViewRadiusM));
        if (p.norm() > kViewRadiusM || std::abs(p.x()) > half_width_m) continue;
        const Hit hit = obstacle_at(spec.obstacle, p, rng);
        const double z = surface_z_m(spec.shape, p.x()) + hit.above_m + rng.normal(0.0, kNoiseM);
        scene.cloud.points.emplace_back(p.x(), p.y(), z);
        scene.truth.push_back(hit.truth);
    }
    return scene;
}

struct VoxelKeyHash {
    std::size_t operator()(const Eigen::Vector3i& k) const {
        return std::hash<long long>()((static_cast<long long>(k.x()) * 73856093) ^
                                      (static_cast<long long>(k.y()) * 19349663) ^
                                      (static_cast<long long>(k.z()) * 83492791));
    }
};

Eigen::Vector3i voxel_key(const Eigen::Vector3d& p, double voxel_m) {
    return (p / voxel_m).array().floor().cast<int>();
}

/// Ground truth of each voxelised point: the most common truth of the raw points in its voxel
/// (the voxel grid's key is floor(p / size), and a centroid stays in its voxel); ties go to the
/// obstacle.
std::vector<Truth> voxel_truth(const Scene& scene, const SurfaceObstacles& result, double voxel_m) {
    using Counts = std::array<int, static_cast<std::size_t>(Truth::kCount)>;
    std::unordered_map<Eigen::Vector3i, Counts, VoxelKeyHash> counts;
    for (std::size_t i = 0; i < scene.cloud.size(); ++i) {
        auto [it, fresh] = counts.try_emplace(voxel_key(scene.cloud.points[i], voxel_m), Counts{});
        ++it->second[static_cast<std::size_t>(scene.truth[i])];
    }
    std::vector<Truth> truth;
    for (const auto& p : result.points.points) {
        const Counts& c = counts.at(voxel_key(p, voxel_m));
        const auto best = std::max_element(c.rbegin(), c.rend()) - c.rbegin();
        truth.push_back(static_cast<Truth>(c.size() - 1 - static_cast<std::size_t>(best)));
    }
    return truth;
}

SurfaceLabel expected_label(Truth t) {
    if (t == Truth::kSurface) return SurfaceLabel::kFree;
    return t == Truth::kHole || t == Truth::kEdge ? SurfaceLabel::kNegative
                                                  : SurfaceLabel::kPositive;
}

struct Score {
    double precision = 0.0, recall = 0.0;
    std::size_t truth = 0, predicted = 0;
};

/// Per voxelised point: recall over the points of class `t`, precision over the points given
/// `t`'s label (a scene holds one obstacle class, so that label is that class's).
Score score(const std::vector<Truth>& truth, const SurfaceObstacles& result, Truth t) {
    Score s;
    std::size_t hits = 0;
    for (std::size_t i = 0; i < truth.size(); ++i) {
        const bool is_t = truth[i] == t;
        const bool said_t = result.labels[i] == expected_label(t);
        s.truth += is_t ? 1 : 0;
        s.predicted += said_t ? 1 : 0;
        hits += is_t && said_t ? 1 : 0;
    }
    s.recall = s.truth ? static_cast<double>(hits) / s.truth : 0.0;
    s.precision = s.predicted ? static_cast<double>(hits) / s.predicted : 0.0;
    return s;
}

const char* shape_name(Shape s) {
    constexpr std::array names{"Plate", "TiltedPlate", "Concave", "Convex"};
    return names[static_cast<std::size_t>(s)];
}
const char* truth_name(Truth t) {
    constexpr std::array names{"Surface", "Bead", "Bolt", "Bracket", "Hole", "Edge"};
    return names[static_cast<std::size_t>(t)];
}

constexpr double kMinRecall = 0.95, kMinPrecision = 0.9;
// A 15 mm bead against a 12 mm threshold in 3 mm noise: a point clears it with P(N > −1σ) =
// 84 %, so per point the bead's recall is physics, not a defect: 0.78–0.84 measured on the four
// surfaces; the bound leaves ~5 points of margin. The crawler still sees every bead along its
// whole length (SeesEveryWeldBeadAlongItsWholeLength).
constexpr double kMinBeadRecall = 0.73;
// Free surface: measured 0.999–1.000 both ways (the misses are the 3.3σ noise tail).
constexpr double kMinFreeScore = 0.995;

double min_recall(Truth t) { return t == Truth::kBead ? kMinBeadRecall : kMinRecall; }

struct ClassCase {
    Shape shape;
    Truth obstacle;
};

class SurfaceObstaclesClassTest : public ::testing::TestWithParam<ClassCase> {};

TEST_P(SurfaceObstaclesClassTest, MeasuresPrecisionAndRecall) {
    const auto [shape, obstacle] = GetParam();
    const Scene scene = make_scene({shape, obstacle});
    const SurfaceObstaclesConfig config;
    const SurfaceObstacles result = detect_surface_obstacles(scene.cloud, config);
    ASSERT_EQ(result.status, SurfaceStatus::kOk);
    const auto truth = voxel_truth(scene, result, config.voxel_size_m);
    const Score obs = score(truth, result, obstacle);
    const Score free = score(truth, result, Truth::kSurface);
    std::printf(
        "%-12s %-8s obstacle P %.3f R %.3f (%zu true, %zu said) | free P %.3f R %.3f | "
        "rms %.4f xx %.4f zz %.4f\n",
        shape_name(shape), truth_name(obstacle), obs.precision, obs.recall, obs.truth,
        obs.predicted, free.precision, free.recall, result.inlier_rms_m, result.surface.xx,
        result.surface.zz);
    EXPECT_GE(obs.recall, min_recall(obstacle));
    EXPECT_GE(obs.precision, kMinPrecision);
    EXPECT_GE(free.recall, kMinFreeScore);
    EXPECT_GE(free.precision, kMinFreeScore);
}

std::vector<ClassCase> all_cases() {
    std::vector<ClassCase> cases;
    for (Shape s : {Shape::kPlate, Shape::kTiltedPlate, Shape::kConcave, Shape::kConvex}) {
        for (Truth t : {Truth::kBead, Truth::kBolt, Truth::kBracket, Truth::kHole, Truth::kEdge})
            cases.push_back({s, t});
    }
    return cases;
}

INSTANTIATE_TEST_SUITE_P(SurfaceObstacles, SurfaceObstaclesClassTest,
                         ::testing::ValuesIn(all_cases()),
                         [](const ::testing::TestParamInfo<ClassCase>& param_info) {
                             return std::string(shape_name(param_info.param.shape)) +
                                    truth_name(param_info.param.obstacle);
                         });

Scene plate_scene(Truth obstacle = Truth::kSurface, std::size_t n = kNumPoints) {
    return make_scene({Shape::kPlate, obstacle, n});
}

/// Fraction of the beads' centre lines (sampled every 1 cm) with a positive cell within one cell.
double bead_coverage(const SurfaceGrid& grid) {
    std::size_t seen = 0, total = 0;
    for (const auto& b : kBeads) {
        const int steps = static_cast<int>((b[1] - b[0]).norm() / 0.01);
        for (int k = 0; k <= steps; ++k) {
            const Eigen::Vector2d p = b[0] + (b[1] - b[0]) * k / steps;
            bool positive = false;
            for (double dy : {-1.0, 0.0, 1.0}) {
                for (double dx : {-1.0, 0.0, 1.0}) {
                    const Eigen::Vector2d q = p + grid.cell_size_m * Eigen::Vector2d(dx, dy);
                    positive |= grid.label_at(q) == SurfaceLabel::kPositive;
                }
            }
            seen += positive ? 1 : 0;
            ++total;
        }
    }
    return static_cast<double>(seen) / static_cast<double>(total);
}

// Measured 0.983–1.000: the gaps are 2 cm stretches where noise kept every point under 12 mm.
constexpr double kMinBeadCoverage = 0.95;

TEST(SurfaceObstacles, SeesEveryWeldBeadAlongItsWholeLength) {
    for (Shape shape : {Shape::kPlate, Shape::kTiltedPlate, Shape::kConcave, Shape::kConvex}) {
        const auto result = detect_surface_obstacles(make_scene({shape, Truth::kBead}).cloud);
        EXPECT_GE(bead_coverage(result.grid), kMinBeadCoverage) << shape_name(shape);
    }
}

// Least squares over ~1e5 points with 3 mm noise fixes the curvature to ~1e-4 /m; the convex
// side spans only ±1.13 m (its horizon), where g z² and a x² are hard to tell apart, and gives
// a = −0.1985 (0.75 % off). g is the weak coefficient there (−0.232 for −0.2).
constexpr double kCurvatureTolPerM = 0.005;
constexpr double kZzTolPerM = 0.05;
constexpr double kFlatTol = 0.002;  // slopes (dimensionless), cross terms (1/m), offset (m)

TEST(SurfaceObstacles, FitsTheTankWallsLocalExpansion) {
    for (Shape shape : {Shape::kConcave, Shape::kConvex}) {
        const double sign = shape == Shape::kConcave ? 1.0 : -1.0;
        const auto result = detect_surface_obstacles(make_scene({shape, Truth::kBolt}).cloud);
        ASSERT_EQ(result.status, SurfaceStatus::kOk);
        const QuadricSurface& s = result.surface;
        // x² + (z ∓ R)² = R² is z = ±(x² + z²)/(2R): curvature 1/(2R) across the axis, 0 along.
        EXPECT_NEAR(s.xx, sign / (2.0 * kTankRadiusM), kCurvatureTolPerM) << shape_name(shape);
        EXPECT_NEAR(s.zz, sign / (2.0 * kTankRadiusM), kZzTolPerM) << shape_name(shape);
        EXPECT_NEAR(s.yy, 0.0, kFlatTol);
        EXPECT_NEAR(s.xy, 0.0, kFlatTol);
        EXPECT_NEAR(s.x_slope, 0.0, kFlatTol);
        EXPECT_NEAR(s.y_slope, 0.0, kFlatTol);
        EXPECT_NEAR(s.offset_m, 0.0, kFlatTol);
        EXPECT_NEAR(result.inlier_rms_m, kNoiseM, 0.0005);  // the noise, truncated at 3.3σ
    }
}

TEST(SurfaceObstacles, FitsAPlateTiltedFifteenDegrees) {
    const auto result = detect_surface_obstacles(make_scene({Shape::kTiltedPlate}).cloud);
    ASSERT_EQ(result.status, SurfaceStatus::kOk);
    EXPECT_NEAR(result.surface.x_slope, std::tan(kTiltDeg * std::numbers::pi / 180.0), kFlatTol);
    EXPECT_NEAR(result.surface.y_slope, 0.0, kFlatTol);
    EXPECT_NEAR(result.surface.offset_m, 0.0, kFlatTol);
    // Vertical noise of σ is σ cos 15° along the normal, the distance that is measured.
    EXPECT_NEAR(result.inlier_rms_m, kNoiseM * std::cos(kTiltDeg * std::numbers::pi / 180.0),
                0.0005);
    EXPECT_GE(static_cast<double>(result.num_inliers), 0.99 * result.points.size());
}

void expect_same(const SurfaceObstacles& a, const SurfaceObstacles& b) {
    EXPECT_EQ(a.surface.xx, b.surface.xx);
    EXPECT_EQ(a.surface.zz, b.surface.zz);
    EXPECT_EQ(a.surface.offset_m, b.surface.offset_m);
    EXPECT_EQ(a.labels, b.labels);
    EXPECT_EQ(a.grid.cells, b.grid.cells);
    EXPECT_EQ(a.clusters.size(), b.clusters.size());
}

TEST(SurfaceObstacles, IsDeterministicForASeedAndAnyThreadCount) {
    const Scene scene = make_scene({Shape::kConcave, Truth::kBracket});
    SurfaceObstaclesConfig serial;
    serial.parallel.num_threads = 1;
    SurfaceObstaclesConfig parallel;
    parallel.parallel.num_threads = 2;
    const auto a = detect_surface_obstacles(scene.cloud, serial);
    expect_same(a, detect_surface_obstacles(scene.cloud, serial));
    expect_same(a, detect_surface_obstacles(scene.cloud, parallel));
    // Another seed draws other hypotheses (and could not tell a seed-blind implementation).
    SurfaceObstaclesConfig other = serial;
    other.seed = 99;
    EXPECT_NE(a.surface.xx, detect_surface_obstacles(scene.cloud, other).surface.xx);
}

TEST(SurfaceObstacles, ReportsAnEmptyCloudAsTooFewPoints) {
    const auto result = detect_surface_obstacles(PointCloud{});
    EXPECT_EQ(result.status, SurfaceStatus::kTooFewPoints);
    EXPECT_TRUE(result.labels.empty());
    EXPECT_TRUE(result.clusters.empty());
    EXPECT_TRUE(std::all_of(result.grid.cells.begin(), result.grid.cells.end(),
                            [](SurfaceLabel l) { return l == SurfaceLabel::kUnknown; }));
}

TEST(SurfaceObstacles, SkipsAndCountsNonFinitePoints) {
    constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
    PointCloud only_nan;
    only_nan.points.assign(50, Eigen::Vector3d(kNan, 0.0, 0.0));
    const auto none = detect_surface_obstacles(only_nan);
    EXPECT_EQ(none.status, SurfaceStatus::kTooFewPoints);
    EXPECT_EQ(none.num_non_finite, 50u);

    const Scene scene = make_scene({Shape::kPlate, Truth::kBolt});
    PointCloud with_nan = scene.cloud;
    for (int k = 0; k < 1000; ++k) {
        with_nan.points.emplace_back(kNan, 1.0, 0.0);
        with_nan.points.emplace_back(0.5, std::numeric_limits<double>::infinity(), 0.0);
    }
    const auto clean = detect_surface_obstacles(scene.cloud);
    const auto dirty = detect_surface_obstacles(with_nan);
    EXPECT_EQ(dirty.num_non_finite, 2000u);
    expect_same(clean, dirty);
}

TEST(SurfaceObstacles, CountsPointsBeyondTheRange) {
    const Scene scene = plate_scene();
    SurfaceObstaclesConfig config;
    config.max_range_m = 1.0;
    const auto far =
        std::count_if(scene.cloud.points.begin(), scene.cloud.points.end(),
                      [](const Eigen::Vector3d& p) { return p.head<2>().norm() > 1.0; });
    const auto result = detect_surface_obstacles(scene.cloud, config);
    EXPECT_EQ(result.num_out_of_range, static_cast<std::size_t>(far));
    EXPECT_EQ(result.status, SurfaceStatus::kOk);
    EXPECT_EQ(result.grid.cells_per_side, 100);
}

TEST(SurfaceObstacles, ReportsNoSurfaceWhenNoQuadricFitsThePoints) {
    // A vertical wall through the robot: every point is on the line y = 0 in x-y, so no six of
    // them define a height field.
    Rng rng(3);
    PointCloud wall;
    for (int k = 0; k < 5000; ++k) wall.points.emplace_back(rng.uniform(-1, 1), 0.0, rng.uniform());
    const auto result = detect_surface_obstacles(wall);
    EXPECT_EQ(result.status, SurfaceStatus::kNoSurface);
    EXPECT_EQ(result.labels.size(), result.points.size());
    EXPECT_TRUE(std::all_of(result.labels.begin(), result.labels.end(),
                            [](SurfaceLabel l) { return l == SurfaceLabel::kUncertain; }));
}

TEST(SurfaceObstacles, RejectsACloudWithMismatchedFields) {
    PointCloud cloud = plate_scene(Truth::kSurface, 1000).cloud;
    cloud.normals.resize(10);
    EXPECT_THROW(detect_surface_obstacles(cloud), InputError);
}

TEST(SurfaceObstacles, FindsOneClusterAtTheBracketAndOneAtTheHole) {
    const auto bracket = detect_surface_obstacles(plate_scene(Truth::kBracket).cloud);
    ASSERT_EQ(bracket.clusters.size(), 1u);
    const ObstacleCluster& b = bracket.clusters[0];
    EXPECT_EQ(b.label, SurfaceLabel::kPositive);
    EXPECT_LT((b.centroid_xy_m - kBracketCentre).norm(), 0.02);
    const double cell = bracket.grid.cell_size_m;
    EXPECT_TRUE((b.min_xy_m.array() <= (kBracketCentre - kBracketHalf).array() + cell).all());
    EXPECT_TRUE((b.max_xy_m.array() >= (kBracketCentre + kBracketHalf).array() - cell).all());

    const auto hole = detect_surface_obstacles(plate_scene(Truth::kHole).cloud);
    ASSERT_EQ(hole.clusters.size(), 1u);
    EXPECT_EQ(hole.clusters[0].label, SurfaceLabel::kNegative);
    EXPECT_LT((hole.clusters[0].centroid_xy_m - kHoleCentre).norm(), 0.02);
    const double area_m2 = std::numbers::pi * kHoleRadiusM * kHoleRadiusM;
    EXPECT_NEAR(hole.clusters[0].num_cells * cell * cell, area_m2, 0.2 * area_m2);
}

TEST(SurfaceObstacles, MarksAnEnclosedRegionWithoutReturnsAsNegative) {
    // A hole whose far side returns nothing: no point within 0.1 m of (−0.5, 0.5).
    const Eigen::Vector2d centre(-0.5, 0.5);
    const Scene scene = plate_scene();
    PointCloud cloud;
    for (const auto& p : scene.cloud.points) {
        if ((p.head<2>() - centre).norm() > 0.1) cloud.points.push_back(p);
    }
    const auto marked = detect_surface_obstacles(cloud);
    EXPECT_EQ(marked.grid.label_at(centre), SurfaceLabel::kNegative);
    ASSERT_EQ(marked.clusters.size(), 1u);
    EXPECT_LT((marked.clusters[0].centroid_xy_m - centre).norm(), 0.02);

    SurfaceObstaclesConfig config;
    config.enclosed_unknown_is_negative = false;
    const auto unmarked = detect_surface_obstacles(cloud, config);
    EXPECT_EQ(unmarked.grid.label_at(centre), SurfaceLabel::kUnknown);
    EXPECT_TRUE(unmarked.clusters.empty());
    // The unknown beyond the view (corners of the grid) is not enclosed: never negative.
    EXPECT_EQ(marked.grid.label_at(Eigen::Vector2d(2.9, 2.9)), SurfaceLabel::kUnknown);
}

TEST(SurfaceObstacles, MissingReturnsWhereTheSensorLooksAreNegative) {
    // The plate ends at x = 1 (no point beyond), a 5 cm box stands at x = 0.5 with no return
    // in its shadow behind it, and nothing comes back from x < -1.5 (behind the sensor).
    const Scene scene = plate_scene();
    PointCloud cloud;
    for (const auto& p : scene.cloud.points) {
        const bool beyond_edge = p.x() > 1.0 || p.x() < -1.5;
        const bool box = p.x() >= 0.5 && p.x() <= 0.6 && std::abs(p.y()) <= 0.05;
        const bool shadow = p.x() > 0.6 && p.x() <= 0.9 && std::abs(p.y()) <= 0.05;
        if (beyond_edge || shadow) continue;
        cloud.points.emplace_back(p.x(), p.y(), box ? 0.05 : p.z());
    }
    // A LiDAR 0.3 m up at the origin, pitched 25° down, 70° cone.
    ExpectedView view;
    view.T_body_sensor.translation() = Eigen::Vector3d(0.0, 0.0, 0.3);
    view.T_body_sensor.linear() =
        Eigen::AngleAxisd(25.0 * std::numbers::pi / 180.0, Eigen::Vector3d::UnitY())
            .toRotationMatrix();
    view.half_fov_rad = 35.0 * std::numbers::pi / 180.0;
    SurfaceObstaclesConfig config;
    config.enclosed_unknown_is_negative = false;  // the missing-returns rule alone
    config.min_cluster_cells = 2;  // a 2 cm cell the random sampling left empty is no hole
    const auto without = detect_surface_obstacles(cloud, config);
    const auto with = detect_surface_obstacles(cloud, config, view);
    // Beyond the edge, in the cone and within 1.5 m: negative, where it was unknown.
    EXPECT_EQ(without.grid.label_at({1.2, 0.0}), SurfaceLabel::kUnknown);
    EXPECT_EQ(with.grid.label_at({1.2, 0.3}), SurfaceLabel::kNegative);
    EXPECT_EQ(with.grid.label_at({1.2, 0.5}), SurfaceLabel::kNegative);
    // Beyond 1.5 m from the sensor, or outside the cone (behind it): not expected, unknown.
    EXPECT_EQ(with.grid.label_at({1.7, 0.0}), SurfaceLabel::kUnknown);
    EXPECT_EQ(with.grid.label_at({1.2, 1.3}), SurfaceLabel::kUnknown);
    EXPECT_EQ(with.grid.label_at({-1.7, 0.0}), SurfaceLabel::kUnknown);
    // The box's shadow is not a hole: the box is in the way.
    EXPECT_EQ(with.grid.label_at({0.5 + 0.055, 0.0}), SurfaceLabel::kPositive);
    EXPECT_EQ(with.grid.label_at({0.75, 0.0}), SurfaceLabel::kUnknown);
    // The band beyond the edge, cut in two by the box's shadow, its near side at x = 1.
    std::size_t negatives = 0;
    for (const auto& c : with.clusters) {
        if (c.label != SurfaceLabel::kNegative) continue;
        ++negatives;
        EXPECT_NEAR(c.min_xy_m.x(), 1.0, 0.03);
        EXPECT_GT(c.num_cells, 400u);
    }
    EXPECT_EQ(negatives, 2u);
    // A bad view is refused.
    view.half_fov_rad = 0.0;
    EXPECT_THROW(detect_surface_obstacles(cloud, config, view), InputError);
}

// ---- column_median ------------------------------------------------------------------------

/// Fraction of the points labelled positive or negative.
double obstacle_fraction(const SurfaceObstacles& result) {
    const auto n = std::count_if(result.labels.begin(), result.labels.end(), [](SurfaceLabel l) {
        return l == SurfaceLabel::kPositive || l == SurfaceLabel::kNegative;
    });
    return static_cast<double>(n) / static_cast<double>(result.labels.size());
}

/// The cluster whose extent holds p, if any.
const ObstacleCluster* cluster_at(const SurfaceObstacles& result, const Eigen::Vector2d& p) {
    for (const auto& c : result.clusters) {
        if ((p.array() >= c.min_xy_m.array()).all() && (p.array() <= c.max_xy_m.array()).all())
            return &c;
    }
    return nullptr;
}

// The patch under a LiDAR standing 0.3 m above a plate: steep rays, whose 2 cm range noise is
// (nearly) along z, and ~60 returns per 1 cm column (100 k points on 0.4 × 0.4 m).
constexpr double kSteepNoiseM = 0.02;
constexpr double kPatchHalfM = 0.2;
constexpr std::size_t kPatchPoints = 100000;
// A 25 mm high bracket (or bolt head) of 60 × 40 mm in it.
const Eigen::Vector2d kLowBracketCentre(0.08, -0.05), kLowBracketHalf(0.03, 0.02);
constexpr double kLowBracketHeightM = 0.025;

PointCloud steep_noise_patch(bool with_bracket) {
    Rng rng(11);
    PointCloud cloud;
    for (std::size_t k = 0; k < kPatchPoints; ++k) {
        const double x = rng.uniform(-kPatchHalfM, kPatchHalfM);
        const double y = rng.uniform(-kPatchHalfM, kPatchHalfM);
        const bool on_bracket =
            with_bracket &&
            ((Eigen::Vector2d(x, y) - kLowBracketCentre).cwiseAbs() - kLowBracketHalf).maxCoeff() <=
                0.0;
        const double z = (on_bracket ? kLowBracketHeightM : 0.0) + rng.normal(0.0, kSteepNoiseM);
        cloud.points.emplace_back(x, y, z);
    }
    return cloud;
}

SurfaceObstaclesConfig column_median_config() {
    SurfaceObstaclesConfig config;
    config.column_median = true;
    return config;
}

// Measured: 77 % of the 15 800 voxels are obstacles, 0 of the 1 600 column medians.
TEST(SurfaceObstacles, ColumnMedianRemovesTheObstaclesOfASteepRangeNoise) {
    const PointCloud cloud = steep_noise_patch(false);
    const auto voxels = detect_surface_obstacles(cloud);
    const auto columns = detect_surface_obstacles(cloud, column_median_config());
    ASSERT_EQ(voxels.status, SurfaceStatus::kOk);
    ASSERT_EQ(columns.status, SurfaceStatus::kOk);
    std::printf(
        "steep noise: voxels %zu, obstacles %.4f, clusters %zu | columns %zu, obstacles "
        "%.5f, clusters %zu\n",
        voxels.points.size(), obstacle_fraction(voxels), voxels.clusters.size(),
        columns.points.size(), obstacle_fraction(columns), columns.clusters.size());
    // One point per 1 cm column of the 0.4 m square.
    EXPECT_EQ(columns.points.size(), 1600u);
    EXPECT_GT(obstacle_fraction(voxels), 0.05);
    EXPECT_LT(obstacle_fraction(columns), 0.005);
    EXPECT_TRUE(columns.clusters.empty());
}

TEST(SurfaceObstacles, ColumnMedianStillFindsALowBracketInASteepRangeNoise) {
    const auto result = detect_surface_obstacles(steep_noise_patch(true), column_median_config());
    ASSERT_EQ(result.status, SurfaceStatus::kOk);
    std::printf("low bracket: clusters %zu, first %zu cells at (%.3f, %.3f)\n",
                result.clusters.size(),
                result.clusters.empty() ? std::size_t{0} : result.clusters[0].num_cells,
                result.clusters.empty() ? 0.0 : result.clusters[0].centroid_xy_m.x(),
                result.clusters.empty() ? 0.0 : result.clusters[0].centroid_xy_m.y());
    ASSERT_EQ(result.clusters.size(), 1u);
    const ObstacleCluster& c = result.clusters[0];
    EXPECT_EQ(c.label, SurfaceLabel::kPositive);
    EXPECT_LT((c.centroid_xy_m - kLowBracketCentre).norm(), 0.01);
    // 60 × 40 mm are 3 × 2 whole cells of 2 cm; the columns across its edges may add a ring.
    EXPECT_GE(c.num_cells, 6u);
    EXPECT_LE(c.num_cells, 20u);
    EXPECT_EQ(result.grid.label_at(kLowBracketCentre), SurfaceLabel::kPositive);
}

TEST(SurfaceObstacles, ColumnMedianKeepsOnePointPerColumnAtItsMedianHeight) {
    // 20 × 20 columns of 1 cm, five returns each: four near the plate, one 9 cm up (a mixed
    // return): the median is the third height, 1 mm; a mean would be 19 mm up.
    constexpr std::array<double, 5> kHeights{0.003, -0.002, 0.09, 0.001, 0.0};
    Rng rng(4);
    PointCloud cloud;
    for (int iy = 0; iy < 20; ++iy) {
        for (int ix = 0; ix < 20; ++ix) {
            for (const double z : kHeights) {
                const double x = 0.01 * (ix + rng.uniform(0.1, 0.9));
                const double y = 0.01 * (iy + rng.uniform(0.1, 0.9));
                cloud.points.emplace_back(x, y, z);
            }
        }
    }
    const auto result = detect_surface_obstacles(cloud, column_median_config());
    ASSERT_EQ(result.points.size(), 400u);
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        const Eigen::Vector3d& p = result.points.points[i];
        EXPECT_EQ(p.z(), 0.001) << i;
        // x, y: the mean of the column's points, so inside the column.
        const double col_x = std::floor(p.x() / 0.01), col_y = std::floor(p.y() / 0.01);
        EXPECT_GE(p.x() - 0.01 * col_x, 0.001) << i;
        EXPECT_LE(p.x() - 0.01 * col_x, 0.009) << i;
        EXPECT_GE(p.y() - 0.01 * col_y, 0.001) << i;
        EXPECT_LE(p.y() - 0.01 * col_y, 0.009) << i;
    }
    ASSERT_EQ(result.status, SurfaceStatus::kOk);
    EXPECT_NEAR(result.surface.offset_m, 0.001, 1e-6);
    EXPECT_TRUE(result.clusters.empty());
}

TEST(SurfaceObstacles, ColumnMedianIsDeterministicAndIndependentOfThePointOrder) {
    const PointCloud cloud = steep_noise_patch(true);
    PointCloud shuffled = cloud;
    Rng rng(21);
    rng.shuffle(std::span<Eigen::Vector3d>(shuffled.points));
    ASSERT_NE(shuffled.points, cloud.points);
    const auto config = column_median_config();
    const auto a = detect_surface_obstacles(cloud, config);
    const auto again = detect_surface_obstacles(cloud, config);
    const auto reordered = detect_surface_obstacles(shuffled, config);
    EXPECT_EQ(a.points.points, again.points.points);
    expect_same(a, again);
    EXPECT_EQ(a.points.points, reordered.points.points);
    expect_same(a, reordered);
}

// ---- min_cluster_cells --------------------------------------------------------------------

TEST(SurfaceObstacles, MinClusterCellsDropsASingleCellSpikeButNotTheBracket) {
    Scene scene = plate_scene(Truth::kBracket, 100000);
    // Five returns 3 cm up inside the 2 cm cell [−0.50, −0.48]² (a spray of spurious returns).
    const Eigen::Vector2d spike(-0.49, -0.49);
    for (const Eigen::Vector2d& d :
         {Eigen::Vector2d(-0.004, -0.004), Eigen::Vector2d(0.004, -0.004),
          Eigen::Vector2d(-0.004, 0.004), Eigen::Vector2d(0.004, 0.004),
          Eigen::Vector2d(0.001, 0.002)}) {
        scene.cloud.points.emplace_back(spike.x() + d.x(), spike.y() + d.y(), 0.03);
    }
    SurfaceObstaclesConfig config;
    config.min_obstacle_support = 1;
    config.min_cluster_cells = 1;
    const auto kept = detect_surface_obstacles(scene.cloud, config);
    config.min_cluster_cells = 3;
    const auto dropped = detect_surface_obstacles(scene.cloud, config);
    std::printf("min_cluster_cells: 1 -> %zu clusters, 3 -> %zu clusters\n", kept.clusters.size(),
                dropped.clusters.size());

    EXPECT_EQ(kept.grid.label_at(spike), SurfaceLabel::kPositive);
    const ObstacleCluster* spike_cluster = cluster_at(kept, spike);
    ASSERT_NE(spike_cluster, nullptr);
    EXPECT_EQ(spike_cluster->label, SurfaceLabel::kPositive);
    EXPECT_EQ(spike_cluster->num_cells, 1u);

    EXPECT_EQ(dropped.grid.label_at(spike), SurfaceLabel::kUncertain);
    EXPECT_EQ(cluster_at(dropped, spike), nullptr);
    EXPECT_LT(dropped.clusters.size(), kept.clusters.size());
    for (const auto& c : dropped.clusters) EXPECT_GE(c.num_cells, 3u);
    // The grid holds no obstacle cell outside a cluster.
    std::size_t obstacle_cells = 0, cluster_cells = 0;
    for (const SurfaceLabel l : dropped.grid.cells) {
        obstacle_cells += l == SurfaceLabel::kPositive || l == SurfaceLabel::kNegative ? 1 : 0;
    }
    for (const auto& c : dropped.clusters) cluster_cells += c.num_cells;
    EXPECT_EQ(obstacle_cells, cluster_cells);
    const ObstacleCluster* bracket = cluster_at(dropped, kBracketCentre);
    ASSERT_NE(bracket, nullptr);
    EXPECT_EQ(bracket->label, SurfaceLabel::kPositive);
    EXPECT_GE(bracket->num_cells, 15u);  // 100 × 50 mm: 5 × 2.5 cells and more
    const ObstacleCluster* bracket_kept = cluster_at(kept, kBracketCentre);
    ASSERT_NE(bracket_kept, nullptr);
    EXPECT_EQ(bracket->num_cells, bracket_kept->num_cells);
}

// ---- rim_cells ----------------------------------------------------------------------------

// A footprint that ends at x = 1 m, as the view of a LiDAR tilted down does: the last 2 cm
// (one cell) before the end get returns 2 cm up, as range noise gives at the near rim.
constexpr double kRimEdgeX = 1.0, kRimBandM = 0.02, kRimBiasM = 0.02;
constexpr std::size_t kRimPoints = 100000;
// A box 30 mm high in the middle, and one whose last cell (x in [0.94, 0.96)) is 3 cells
// (Chebyshev) from the first cell without points (x in [1.00, 1.02)).
const Eigen::Vector2d kMidBoxCentre(0.0, 0.3), kMidBoxHalf(0.05, 0.03);
const Eigen::Vector2d kEdgeBoxCentre(0.93, -0.17), kEdgeBoxHalf(0.03, 0.03);
constexpr double kBoxHeightM = 0.03;
// Holes without returns: a disc inside, and a box whose last cell is 2 cells from the end of
// the view (only the band at x >= 0.98 closes it).
const Eigen::Vector2d kInnerHoleCentre(-0.5, 0.5);
constexpr double kInnerHoleRadiusM = 0.1;
const Eigen::Vector2d kEdgeHoleCentre(0.91, -0.5), kEdgeHoleHalf(0.07, 0.06);

bool in_box(const Eigen::Vector2d& p, const Eigen::Vector2d& centre, const Eigen::Vector2d& half) {
    return ((p - centre).cwiseAbs() - half).maxCoeff() < 0.0;
}

PointCloud rim_cloud(bool with_holes) {
    Rng rng(5);
    PointCloud cloud;
    while (cloud.size() < kRimPoints) {
        const double x = rng.uniform(-1.0, kRimEdgeX);
        const double y = rng.uniform(-1.0, 1.0);
        const Eigen::Vector2d p(x, y);
        if (with_holes && ((p - kInnerHoleCentre).norm() <= kInnerHoleRadiusM ||
                           in_box(p, kEdgeHoleCentre, kEdgeHoleHalf))) {
            continue;
        }
        double z = rng.normal(0.0, kNoiseM);
        if (x >= kRimEdgeX - kRimBandM) z += kRimBiasM;
        if (in_box(p, kMidBoxCentre, kMidBoxHalf) || in_box(p, kEdgeBoxCentre, kEdgeBoxHalf))
            z += kBoxHeightM;
        cloud.points.emplace_back(x, y, z);
    }
    return cloud;
}

std::size_t positive_points_in_band(const SurfaceObstacles& result) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        n += result.points.points[i].x() >= kRimEdgeX - kRimBandM &&
                     result.labels[i] == SurfaceLabel::kPositive
                 ? 1
                 : 0;
    }
    return n;
}

TEST(SurfaceObstacles, RimCellsRemovesTheBiasedRimButNotTheObstaclesInside) {
    const PointCloud cloud = rim_cloud(false);
    SurfaceObstaclesConfig config;
    config.rim_cells = 0;
    const auto off = detect_surface_obstacles(cloud, config);
    config.rim_cells = 2;
    const auto on = detect_surface_obstacles(cloud, config);
    config.rim_cells = 3;
    const auto wide = detect_surface_obstacles(cloud, config);
    ASSERT_EQ(off.status, SurfaceStatus::kOk);
    ASSERT_EQ(on.status, SurfaceStatus::kOk);
    std::printf("rim: off %zu clusters, %zu band points positive | on %zu clusters, %zu\n",
                off.clusters.size(), positive_points_in_band(off), on.clusters.size(),
                positive_points_in_band(on));

    // Off: the band is a positive cluster one cell wide along the whole edge (y in [−1, 1)).
    const ObstacleCluster* rim = cluster_at(off, Eigen::Vector2d(0.99, 0.0));
    ASSERT_NE(rim, nullptr);
    EXPECT_EQ(rim->label, SurfaceLabel::kPositive);
    EXPECT_GE(rim->num_cells, 90u);
    EXPECT_NEAR(rim->min_xy_m.x(), kRimEdgeX - kRimBandM, 1e-9);
    EXPECT_NEAR(rim->max_xy_m.x(), kRimEdgeX, 1e-9);
    EXPECT_GT(positive_points_in_band(off), 100u);

    // On: nothing at the rim, cells and points alike; the boxes are whole.
    for (const auto& c : on.clusters) EXPECT_LT(c.max_xy_m.x(), kRimEdgeX - kRimBandM);
    EXPECT_EQ(on.grid.label_at(Eigen::Vector2d(0.99, 0.0)), SurfaceLabel::kUncertain);
    EXPECT_EQ(positive_points_in_band(on), 0u);
    ASSERT_EQ(on.clusters.size(), 2u);
    const ObstacleCluster* mid = cluster_at(on, kMidBoxCentre);
    ASSERT_NE(mid, nullptr);
    EXPECT_EQ(mid->label, SurfaceLabel::kPositive);
    EXPECT_LT((mid->centroid_xy_m - kMidBoxCentre).norm(), 0.01);
    EXPECT_EQ(mid->num_cells, cluster_at(off, kMidBoxCentre)->num_cells);
    const ObstacleCluster* edge_box = cluster_at(on, kEdgeBoxCentre);
    ASSERT_NE(edge_box, nullptr);
    EXPECT_NEAR(edge_box->max_xy_m.x(), 0.96, 1e-9);  // 3 cells from the unknown: kept
    // One more cell of rim takes the box's last column (and only it).
    const ObstacleCluster* edge_box_wide = cluster_at(wide, kEdgeBoxCentre);
    ASSERT_NE(edge_box_wide, nullptr);
    EXPECT_NEAR(edge_box_wide->max_xy_m.x(), 0.94, 1e-9);
    EXPECT_EQ(wide.grid.label_at(Eigen::Vector2d(0.95, -0.17)), SurfaceLabel::kUncertain);
}

TEST(SurfaceObstacles, RimCellsKeepsEnclosedHolesNegative) {
    SurfaceObstaclesConfig config;
    config.rim_cells = 2;
    const auto result = detect_surface_obstacles(rim_cloud(true), config);
    ASSERT_EQ(result.status, SurfaceStatus::kOk);
    const double cell = result.grid.cell_size_m;

    EXPECT_EQ(result.grid.label_at(kInnerHoleCentre), SurfaceLabel::kNegative);
    const ObstacleCluster* inner = cluster_at(result, kInnerHoleCentre);
    ASSERT_NE(inner, nullptr);
    EXPECT_EQ(inner->label, SurfaceLabel::kNegative);
    EXPECT_LT((inner->centroid_xy_m - kInnerHoleCentre).norm(), 0.02);
    const double inner_area_m2 = std::numbers::pi * kInnerHoleRadiusM * kInnerHoleRadiusM;
    EXPECT_NEAR(inner->num_cells * cell * cell, inner_area_m2, 0.3 * inner_area_m2);

    // The box hole is 7 × 6 cells, its last column 2 cells from the end of the view: marked
    // after the erosion, it is whole.
    const ObstacleCluster* edge = cluster_at(result, kEdgeHoleCentre);
    ASSERT_NE(edge, nullptr);
    EXPECT_EQ(edge->label, SurfaceLabel::kNegative);
    EXPECT_EQ(edge->num_cells, 42u);
    EXPECT_EQ(result.grid.label_at(Eigen::Vector2d(0.97, -0.5)), SurfaceLabel::kNegative);
}

TEST(SurfaceObstacles, RimCellsCountsTheGridBorderAsUnknown) {
    // A 1 m range makes a grid of 100 cells that ends at x = 1 m, where the biased band is: at
    // y = 0 its cell's neighbours all hold points, only the grid's border is next to it.
    SurfaceObstaclesConfig config;
    config.max_range_m = 1.0;
    const PointCloud cloud = rim_cloud(false);
    const auto off = detect_surface_obstacles(cloud, config);
    config.rim_cells = 1;
    const auto on = detect_surface_obstacles(cloud, config);
    ASSERT_EQ(on.grid.cells_per_side, 100);
    const Eigen::Vector2d band(0.99, 0.01);
    for (const double dy : {-0.02, 0.0, 0.02}) {
        EXPECT_NE(on.grid.label_at(band + Eigen::Vector2d(0.0, dy)), SurfaceLabel::kUnknown);
        EXPECT_NE(on.grid.label_at(band + Eigen::Vector2d(-0.02, dy)), SurfaceLabel::kUnknown);
    }
    EXPECT_EQ(off.grid.label_at(band), SurfaceLabel::kPositive);
    EXPECT_EQ(on.grid.label_at(band), SurfaceLabel::kUncertain);
}

TEST(SurfaceObstacles, ConfigErrorsNameTheField) {
    using Mutator = void (*)(SurfaceObstaclesConfig&);
    const std::vector<std::pair<std::string, Mutator>> cases{
        {"voxel_size_m", [](SurfaceObstaclesConfig& c) { c.voxel_size_m = 0.0; }},
        {"max_range_m", [](SurfaceObstaclesConfig& c) { c.max_range_m = -1.0; }},
        {"inlier_threshold_m",
         [](SurfaceObstaclesConfig& c) { c.inlier_threshold_m = std::nan(""); }},
        {"obstacle_threshold_m", [](SurfaceObstaclesConfig& c) { c.obstacle_threshold_m = 0.005; }},
        {"iterations", [](SurfaceObstaclesConfig& c) { c.iterations = 0; }},
        {"min_points", [](SurfaceObstaclesConfig& c) { c.min_points = 5; }},
        {"min_radius_m", [](SurfaceObstaclesConfig& c) { c.min_radius_m = 0.0; }},
        {"max_tilt_deg", [](SurfaceObstaclesConfig& c) { c.max_tilt_deg = 90.0; }},
        {"cell_size_m", [](SurfaceObstaclesConfig& c) { c.cell_size_m = -0.02; }},
        {"cell_size_m", [](SurfaceObstaclesConfig& c) { c.cell_size_m = 1e-5; }},
        {"min_obstacle_support", [](SurfaceObstaclesConfig& c) { c.min_obstacle_support = 0; }},
        {"min_enclosed_unknown_cells",
         [](SurfaceObstaclesConfig& c) { c.min_enclosed_unknown_cells = 0; }},
        {"min_cluster_cells", [](SurfaceObstaclesConfig& c) { c.min_cluster_cells = 0; }},
        {"rim_cells", [](SurfaceObstaclesConfig& c) { c.rim_cells = -1; }},
        {"rim_cells", [](SurfaceObstaclesConfig& c) { c.rim_cells = 51; }},
        {"parallel.num_threads", [](SurfaceObstaclesConfig& c) { c.parallel.num_threads = -1; }},
    };
    EXPECT_NO_THROW(SurfaceObstaclesConfig{}.validate());
    SurfaceObstaclesConfig bounds;  // the ends of the allowed ranges
    bounds.min_cluster_cells = 1;
    bounds.rim_cells = 0;
    EXPECT_NO_THROW(bounds.validate());
    bounds.rim_cells = 50;
    EXPECT_NO_THROW(bounds.validate());
    for (const auto& [field, mutate] : cases) {
        SurfaceObstaclesConfig config;
        mutate(config);
        try {
            detect_surface_obstacles(PointCloud{}, config);
            ADD_FAILURE() << field << ": no ConfigError";
        } catch (const ConfigError& e) {
            EXPECT_NE(std::string(e.what()).find("surface_obstacles." + field), std::string::npos)
                << e.what();
        }
    }
    SurfaceObstaclesConfig config;
    config.iterations = 0;
    EXPECT_THROW(config.validate("crawler.obstacles"), ConfigError);
    try {
        config.validate("crawler.obstacles");
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("crawler.obstacles.iterations"), std::string::npos);
    }
}

}  // namespace
}  // namespace scantling::perception
