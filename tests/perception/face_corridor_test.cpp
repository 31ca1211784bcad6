#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/perception/face_corridor.hpp>

namespace scantling::perception {
namespace {

// Synthetic stops. The scene is built in the face's own frame (x' along the corridor, y'
// across it, z the face normal), then turned by a yaw and shifted sideways into the cloud
// frame, where the crawler stands: it is never perfectly aligned with its stiffeners.
constexpr double kNoiseM = 0.02;            // σ along z: a rosette LiDAR's range noise at grazing
constexpr double kPointsPerM2 = 25000.0;    // ~10 returns per 2 cm cell on the face
constexpr double kMinCloudXM = 0.1;         // the sensor sees nothing nearer (its cone)
constexpr double kSceneLengthM = 1.3;       // x' extent: covers the 1 m window at any yaw here
constexpr double kCentreToleranceM = 0.01;  // the mission steers on the centre line
constexpr double kDirectionToleranceDeg = 0.5;
constexpr double kWidthToleranceM = 0.02;  // one cell

struct Placement {
    double yaw_deg = 0.0;  ///< the face frame's x' axis, from the cloud's x
    double shift_m = 0.0;  ///< the face frame's origin, on the cloud's y axis
};

/// A plane segment of the scene: x' in [x0_m, x1_m], (y', z) from (y0_m, z0_m) to (y1_m, z1_m)
/// (a horizontal strip of face or plate, or a vertical wall).
struct Strip {
    double y0_m = 0.0, z0_m = 0.0, y1_m = 0.0, z1_m = 0.0;
    double x0_m = 0.0, x1_m = kSceneLengthM;
};

/// A horizontal strip at height z_m between y0_m and y1_m (the face, or the plate below it).
Strip horizontal(double y0_m, double y1_m, double z_m) {
    return {
        .y0_m = y0_m, .z0_m = z_m, .y1_m = y1_m, .z1_m = z_m, .x0_m = 0.0, .x1_m = kSceneLengthM};
}

/// A vertical wall at y_m from z0_m up to z1_m.
Strip vertical(double y_m, double z0_m, double z1_m) {
    return {
        .y0_m = y_m, .z0_m = z0_m, .y1_m = y_m, .z1_m = z1_m, .x0_m = 0.0, .x1_m = kSceneLengthM};
}

/// The strip cut to x' in [x0_m, x1_m].
Strip cut(Strip s, double x0_m, double x1_m) {
    s.x0_m = x0_m;
    s.x1_m = x1_m;
    return s;
}

Eigen::Matrix3d yaw(double deg) {
    return Eigen::AngleAxisd(deg * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ())
        .toRotationMatrix();
}

Eigen::Vector3d to_cloud(const Placement& placement, const Eigen::Vector3d& p_face) {
    return yaw(placement.yaw_deg) * p_face + Eigen::Vector3d(0.0, placement.shift_m, 0.0);
}

/// Uniform points over each strip at kPointsPerM2, range noise along z, cut at kMinCloudXM.
PointCloud make_scene(const Placement& placement, const std::vector<Strip>& strips,
                      std::uint64_t seed) {
    Rng rng(seed);
    PointCloud cloud;
    for (const Strip& s : strips) {
        const double area_m2 = (s.x1_m - s.x0_m) * std::hypot(s.y1_m - s.y0_m, s.z1_m - s.z0_m);
        const auto n = static_cast<std::size_t>(kPointsPerM2 * area_m2);
        for (std::size_t i = 0; i < n; ++i) {
            const double t = rng.uniform();
            const Eigen::Vector3d p_face(rng.uniform(s.x0_m, s.x1_m),
                                         s.y0_m + t * (s.y1_m - s.y0_m),
                                         s.z0_m + t * (s.z1_m - s.z0_m) + rng.normal(0.0, kNoiseM));
            const Eigen::Vector3d p = to_cloud(placement, p_face);
            if (p.x() >= kMinCloudXM) cloud.points.push_back(p);
        }
    }
    return cloud;
}

/// Between two stiffeners 0.8 m apart: the plate and the two webs rising 0.3 m (to the height
/// of a LiDAR looking forward, which sees their inner sides and nothing beyond).
std::vector<Strip> frame_bay(double half_width_m) {
    return {horizontal(-half_width_m, half_width_m, 0.0), vertical(half_width_m, 0.0, 0.3),
            vertical(-half_width_m, 0.0, 0.3)};
}

/// The perpendicular distance of the corridor's origin from the true centre line y' = centre.
double centre_error_m(const FaceCorridor& c, const Placement& placement, double centre_m) {
    const Eigen::Vector3d p0 = to_cloud(placement, Eigen::Vector3d(0.0, centre_m, 0.0));
    const Eigen::Vector3d d = yaw(placement.yaw_deg) * Eigen::Vector3d::UnitX();
    return std::abs(d.cross(c.origin_m - p0).z());
}

double direction_error_deg(const FaceCorridor& c, const Placement& placement) {
    const Eigen::Vector3d d = yaw(placement.yaw_deg) * Eigen::Vector3d::UnitX();
    return std::acos(std::min(1.0, d.dot(c.direction))) * 180.0 / std::numbers::pi;
}

void expect_corridor(const FaceCorridor& c, const Placement& placement, double centre_m,
                     double width_m) {
    ASSERT_TRUE(c.found) << c.status;
    EXPECT_EQ(c.status, "ok");
    EXPECT_LT(centre_error_m(c, placement, centre_m), kCentreToleranceM);
    EXPECT_LT(direction_error_deg(c, placement), kDirectionToleranceDeg);
    EXPECT_NEAR(c.width_m, width_m, kWidthToleranceM);
    EXPECT_NEAR(c.left_offset_m, 0.5 * width_m, kWidthToleranceM);
    EXPECT_NEAR(c.right_offset_m, -0.5 * width_m, kWidthToleranceM);
    EXPECT_NEAR(c.direction.norm(), 1.0, 1e-12);
    EXPECT_EQ(c.direction.z(), 0.0);
    EXPECT_EQ(c.origin_m.z(), 0.0);
    EXPECT_GE(c.rows_used, FaceCorridorConfig{}.min_rows);
    EXPECT_LT(c.boundary_rms_m, FaceCorridorConfig{}.max_boundary_residual_m);
    EXPECT_EQ(c.points_dropped, 0u);
}

void expect_same(const FaceCorridor& a, const FaceCorridor& b) {
    EXPECT_EQ(a.found, b.found);
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.origin_m, b.origin_m);
    EXPECT_EQ(a.direction, b.direction);
    EXPECT_EQ(a.width_m, b.width_m);
    EXPECT_EQ(a.left_offset_m, b.left_offset_m);
    EXPECT_EQ(a.right_offset_m, b.right_offset_m);
    EXPECT_EQ(a.left_bound, b.left_bound);
    EXPECT_EQ(a.right_bound, b.right_bound);
    EXPECT_EQ(a.rows_used, b.rows_used);
    EXPECT_EQ(a.boundary_rms_m, b.boundary_rms_m);
}

const Placement kBayPlacement{.yaw_deg = 4.0, .shift_m = 0.05};

TEST(FaceCorridor, FindsThePlateBetweenTwoStiffenerWebsAsWallBoundedCorridor) {
    const FaceCorridor c = extract_face_corridor(make_scene(kBayPlacement, frame_bay(0.4), 1));
    expect_corridor(c, kBayPlacement, 0.0, 0.8);
    EXPECT_EQ(c.left_bound, CorridorBound::kWall);
    EXPECT_EQ(c.right_bound, CorridorBound::kWall);
    // 43 rows of 2 cm in [0.15, 1.0] m; a few lose a side to the noise (a 2 cm σ puts 13 % of
    // the face's returns past the 3 cm tolerance) or to the fit's residual limit.
    EXPECT_GE(c.rows_used, 35u);
}

TEST(FaceCorridor, FindsAStiffenerTopFaceAsEdgeBoundedCorridor) {
    const Placement placement{.yaw_deg = -3.0, .shift_m = -0.02};
    const std::vector<Strip> flange{horizontal(-0.1, 0.1, 0.0), horizontal(0.1, 1.2, -0.3),
                                    horizontal(-1.2, -0.1, -0.3)};
    const FaceCorridor c = extract_face_corridor(make_scene(placement, flange, 2));
    expect_corridor(c, placement, 0.0, 0.2);
    EXPECT_EQ(c.left_bound, CorridorBound::kEdge);
    EXPECT_EQ(c.right_bound, CorridorBound::kEdge);
}

TEST(FaceCorridor, FindsTheTopFaceEdgesWhereTheFlangeShadowsThePlateBelow) {
    // A LiDAR 0.3 m above the 0.2 m flange sees the plate 0.3 m below only past |y'| = 0.2 m:
    // the face ends in a 5-cell gap, longer than max_gap_cells, before the drop.
    const Placement placement{.yaw_deg = 2.0, .shift_m = 0.01};
    const std::vector<Strip> flange{horizontal(-0.1, 0.1, 0.0), horizontal(0.2, 1.2, -0.3),
                                    horizontal(-1.2, -0.2, -0.3)};
    const FaceCorridor c = extract_face_corridor(make_scene(placement, flange, 3));
    expect_corridor(c, placement, 0.0, 0.2);
    EXPECT_EQ(c.left_bound, CorridorBound::kEdge);
    EXPECT_EQ(c.right_bound, CorridorBound::kEdge);
}

TEST(FaceCorridor, FindsAWebSideBoundedByThePlateOnOneSideAndTheWebTopOnTheOther) {
    const Placement placement{.yaw_deg = -2.0, .shift_m = 0.0};
    const std::vector<Strip> web{horizontal(-0.15, 0.15, 0.0), vertical(-0.15, 0.0, 0.5)};
    const FaceCorridor c = extract_face_corridor(make_scene(placement, web, 4));
    expect_corridor(c, placement, 0.0, 0.3);
    EXPECT_EQ(c.left_bound, CorridorBound::kEdge);
    EXPECT_EQ(c.right_bound, CorridorBound::kWall);
}

TEST(FaceCorridor, DropsTheRowsWhereABoltBesideTheWebCutsTheFaceShort) {
    // A 6 cm × 10 cm block 5 cm high against the left web, hiding the plate under it: 3 rows
    // end 10 cm early, 7 cm beyond max_boundary_residual_m.
    std::vector<Strip> strips = frame_bay(0.4);
    strips[0] = cut(horizontal(-0.4, 0.4, 0.0), 0.0, 0.5);
    strips.push_back(cut(horizontal(-0.4, 0.4, 0.0), 0.56, kSceneLengthM));
    strips.push_back(cut(horizontal(-0.4, 0.3, 0.0), 0.5, 0.56));
    strips.push_back(cut(horizontal(0.3, 0.4, 0.05), 0.5, 0.56));
    strips.push_back(cut(vertical(0.3, 0.0, 0.05), 0.5, 0.56));
    const FaceCorridor c = extract_face_corridor(make_scene(kBayPlacement, strips, 6));
    expect_corridor(c, kBayPlacement, 0.0, 0.8);
    // The block spans cloud x 0.47–0.54 m: rows [0.49, 0.51] and [0.51, 0.53] lie wholly on it,
    // so at most 41 of the 43 rows can be used.
    EXPECT_LE(c.rows_used, 41u);
    EXPECT_EQ(c.left_bound, CorridorBound::kWall);
}

TEST(FaceCorridor, ReportsNotFoundWhenOneSideIsOpenWithinTheHalfWidth) {
    const std::vector<Strip> open{horizontal(-0.4, 1.4, 0.0), vertical(-0.4, 0.0, 0.3)};
    const FaceCorridor c = extract_face_corridor(make_scene(kBayPlacement, open, 5));
    EXPECT_FALSE(c.found);
    EXPECT_EQ(c.rows_used, 0u);
    EXPECT_EQ(c.left_bound, CorridorBound::kNone);
    // A few rows may see a left "boundary" in a noise cell (10 returns with σ = 2 cm: ~1 cell
    // in 3000 has its median beyond the 3 cm tolerance), never 10.
    EXPECT_EQ(c.status.rfind("only ", 0), 0u) << c.status;
    EXPECT_NE(c.status.find(" rows have both boundaries"), std::string::npos) << c.status;
    EXPECT_NE(c.status.find("expected >= 10"), std::string::npos) << c.status;
}

TEST(FaceCorridor, ReportsNotFoundForAnEmptyCloud) {
    const FaceCorridor c = extract_face_corridor(PointCloud{});
    EXPECT_FALSE(c.found);
    EXPECT_NE(c.status.find("no finite points"), std::string::npos) << c.status;
    EXPECT_EQ(c.points_dropped, 0u);
}

TEST(FaceCorridor, SkipsAndCountsNonFinitePointsWithoutChangingTheResult) {
    const PointCloud cloud = make_scene(kBayPlacement, frame_bay(0.4), 1);
    PointCloud dirty;
    constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
    constexpr double kInf = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (i % 100 == 0) dirty.points.emplace_back(0.5, kNan, 0.0);
        if (i % 1000 == 0) dirty.points.emplace_back(kInf, 0.0, 0.0);
        dirty.points.push_back(cloud.points[i]);
    }
    const std::size_t num_bad = dirty.size() - cloud.size();
    ASSERT_GT(num_bad, 100u);
    const FaceCorridor clean = extract_face_corridor(cloud);
    const FaceCorridor c = extract_face_corridor(dirty);
    ASSERT_TRUE(clean.found) << clean.status;
    EXPECT_EQ(c.points_dropped, num_bad);
    expect_same(c, clean);

    PointCloud only_nan;
    only_nan.points.assign(5, Eigen::Vector3d::Constant(kNan));
    const FaceCorridor none = extract_face_corridor(only_nan);
    EXPECT_FALSE(none.found);
    EXPECT_EQ(none.points_dropped, 5u);
}

TEST(FaceCorridor, GivesTheSameResultBitForBitForShuffledPoints) {
    const PointCloud cloud = make_scene(kBayPlacement, frame_bay(0.4), 1);
    PointCloud shuffled = cloud;
    Rng rng(21);
    rng.shuffle(std::span<Eigen::Vector3d>(shuffled.points));
    ASSERT_NE(shuffled.points, cloud.points);
    const FaceCorridor a = extract_face_corridor(cloud);
    ASSERT_TRUE(a.found) << a.status;
    expect_same(extract_face_corridor(shuffled), a);
}

void expect_config_error(const FaceCorridorConfig& config, const std::string& field) {
    try {
        config.validate();
        ADD_FAILURE() << "no ConfigError for " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("face_corridor." + field + " ="), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(extract_face_corridor(PointCloud{}, config), ConfigError) << field;
}

TEST(FaceCorridor, RejectsEachInvalidConfigFieldByName) {
    EXPECT_NO_THROW(FaceCorridorConfig{}.validate());
    const auto with = [](auto set) {
        FaceCorridorConfig c;
        set(c);
        return c;
    };
    expect_config_error(with([](auto& c) { c.cell_size_m = 0.0; }), "cell_size_m");
    expect_config_error(with([](auto& c) { c.cell_size_m = 1e-6; }),
                        "cell_size_m");  // 1.7e12 cells
    expect_config_error(with([](auto& c) { c.face_tolerance_m = -0.01; }), "face_tolerance_m");
    expect_config_error(with([](auto& c) { c.min_x_m = std::nan(""); }), "min_x_m");
    expect_config_error(with([](auto& c) { c.max_x_m = c.min_x_m; }), "max_x_m");
    expect_config_error(with([](auto& c) { c.max_half_width_m = 0.02; }), "max_half_width_m");
    expect_config_error(with([](auto& c) { c.min_rows = 0; }), "min_rows");
    expect_config_error(with([](auto& c) { c.max_boundary_residual_m = 0.0; }),
                        "max_boundary_residual_m");
}

TEST(FaceCorridor, NamesEachBoundKind) {
    EXPECT_STREQ(to_string(CorridorBound::kNone), "none");
    EXPECT_STREQ(to_string(CorridorBound::kWall), "wall");
    EXPECT_STREQ(to_string(CorridorBound::kEdge), "edge");
}

}  // namespace
}  // namespace scantling::perception
