#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/perception/stop_and_map.hpp>

namespace scantling::perception {
namespace {

// A plate (z = 0) with a bracket and two weld beads at right angles, which pin x, y and yaw
// down; a stop's 200 k rays from a LiDAR 0.3 m up, pitched 46° down, ranged with 3 mm noise.
constexpr double kNoiseM = 0.003;
constexpr double kMaxRangeM = 3.0;
constexpr std::size_t kPointsPerFrame = 20000;
constexpr int kFramesPerStop = 10;

struct Box {
    Eigen::Vector2d min_xy, max_xy;
    double height_m;
};

/// Entry distance of the ray o + t d into the box standing on the plate, or +inf (slabs).
double hit_box(const Box& b, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    const Eigen::Vector3d lo(b.min_xy.x(), b.min_xy.y(), 0.0);
    const Eigen::Vector3d hi(b.max_xy.x(), b.max_xy.y(), b.height_m);
    double t_in = 0.0, t_out = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
        if (std::abs(d[k]) < 1e-12) {
            if (o[k] < lo[k] || o[k] > hi[k]) return std::numeric_limits<double>::infinity();
            continue;
        }
        const double t0 = (lo[k] - o[k]) / d[k], t1 = (hi[k] - o[k]) / d[k];
        t_in = std::max(t_in, std::min(t0, t1));
        t_out = std::min(t_out, std::max(t0, t1));
    }
    return t_in <= t_out ? t_in : std::numeric_limits<double>::infinity();
}

/// Range along the ray to the plate (z = 0) or the nearest box, +inf for none within reach.
double cast(const std::vector<Box>& boxes, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    double t = d.z() < -1e-9 ? -o.z() / d.z() : std::numeric_limits<double>::infinity();
    for (const Box& b : boxes) t = std::min(t, hit_box(b, o, d));
    return t;
}

std::vector<Box> features() {
    return {{{1.00, 0.25}, {1.10, 0.35}, 0.06},    // bracket
            {{0.20, -0.42}, {1.80, -0.38}, 0.02},  // bead along x
            {{1.58, -0.40}, {1.62, 0.60}, 0.02}};  // bead along y
}

Eigen::Isometry3d pose(double x, double y, double yaw) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(x, y, 0.0);
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
}

Eigen::Isometry3d lidar_mount() {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0.1, 0.0, 0.3);
    T.linear() = Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitY()).toRotationMatrix();
    return T;
}

/// One frame of what the LiDAR at `T_world_body` (true) sees of the scene, LiDAR frame: rays
/// spread over its 70° cone, ranged with noise.
PointCloud frame(const std::vector<Box>& boxes, const Eigen::Isometry3d& T_world_body, Rng& rng) {
    const Eigen::Isometry3d T_world_lidar = T_world_body * lidar_mount();
    const double half_cone_rad = 35.0 * std::numbers::pi / 180.0;
    PointCloud cloud;
    while (cloud.size() < kPointsPerFrame) {
        const double polar = half_cone_rad * std::sqrt(rng.uniform(0.0, 1.0));
        const double azimuth = rng.uniform(-std::numbers::pi, std::numbers::pi);
        const Eigen::Vector3d d_lidar(std::cos(polar), std::sin(polar) * std::cos(azimuth),
                                      std::sin(polar) * std::sin(azimuth));
        const Eigen::Vector3d d = T_world_lidar.linear() * d_lidar;
        const double range_m = cast(boxes, T_world_lidar.translation(), d);
        if (!(range_m < kMaxRangeM)) continue;
        cloud.points.push_back(d_lidar * (range_m + rng.normal(0.0, kNoiseM)));
    }
    return cloud;
}

StopMap stop(StopMapper& mapper, const std::vector<Box>& boxes, const Eigen::Isometry3d& truth,
             const Eigen::Isometry3d& localisation, double t_s, Rng& rng) {
    mapper.begin(t_s, localisation);
    for (int i = 0; i < kFramesPerStop; ++i) mapper.add_frame(frame(boxes, truth, rng));
    return mapper.finish(t_s + 2.5);
}

double yaw_of(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

TEST(StopAndMap, TheIcpCorrectsTheLocalisationsErrorBetweenStops) {
    StopMapper mapper({}, lidar_mount());
    Rng rng(3);
    const std::vector<Box> boxes = features();
    const Eigen::Isometry3d truth_1 = pose(0.0, 0.0, 0.0);
    const StopMap first = stop(mapper, boxes, truth_1, truth_1, 10.0, rng);
    EXPECT_EQ(first.icp_status, "first stop");
    EXPECT_TRUE(first.T_world_body_map.isApprox(truth_1));
    // The robot moved 0.4 m and turned 0.03 rad; the localisation says 0.45 m, -0.03 m, 0.01.
    const Eigen::Isometry3d truth_2 = pose(0.4, 0.0, 0.03);
    const Eigen::Isometry3d loc_2 = pose(0.45, -0.03, 0.01);
    const StopMap second = stop(mapper, boxes, truth_2, loc_2, 20.0, rng);
    ASSERT_TRUE(second.icp_applied) << second.icp_status;
    const Eigen::Vector3d error = second.T_world_body_map.translation() - truth_2.translation();
    std::printf("map pose error %.4f m, yaw %.5f rad (localisation 0.058 m, 0.02 rad)\n",
                error.norm(), yaw_of(second.T_world_body_map) - 0.03);
    // Measured 0.0195 m and -0.024 rad: the features' sides give the position back to a third of
    // the localisation's error; the yaw, which 2 cm bead faces at ~1 m pin down only to about
    // their noise, is not improved (docs/results.md, crawler stop-and-map).
    EXPECT_LT(error.norm(), 0.03);
    EXPECT_NEAR(yaw_of(second.T_world_body_map), 0.03, 0.03);
    EXPECT_NEAR(second.T_world_body_map.translation().z(), 0.0, 1e-9);  // planar correction
}

TEST(StopAndMap, PlacesTheObstaclesInTheWorld) {
    StopMapper mapper({}, lidar_mount());
    Rng rng(5);
    const StopMap s = stop(mapper, features(), pose(0.0, 0.0, 0.0), pose(0.0, 0.0, 0.0), 0.0, rng);
    ASSERT_EQ(s.detection.status, SurfaceStatus::kOk);
    ASSERT_FALSE(s.obstacles.empty());
    // The bracket's cluster sits at its centre on the plate.
    double best_m = 1e9;
    for (const MappedObstacle& o : s.obstacles) {
        EXPECT_EQ(o.label, SurfaceLabel::kPositive);
        best_m = std::min(best_m, (o.centroid_world_m - Eigen::Vector3d(1.05, 0.30, 0.0)).norm());
    }
    EXPECT_LT(best_m, 0.04);  // the visible faces pull a 10 cm bracket's centroid
    EXPECT_EQ(s.num_frames, static_cast<std::size_t>(kFramesPerStop));
}

TEST(StopAndMap, ABarePlateLeavesTheLocalisationsMotion) {
    StopMapper mapper({}, lidar_mount());
    Rng rng(7);
    const std::vector<Box> bare;
    stop(mapper, bare, pose(0.0, 0.0, 0.0), pose(0.0, 0.0, 0.0), 0.0, rng);
    const Eigen::Isometry3d loc_2 = pose(0.45, -0.03, 0.01);
    const StopMap second = stop(mapper, bare, pose(0.4, 0.0, 0.03), loc_2, 5.0, rng);
    // A plane constrains none of x, y, yaw: the correction is refused, not made up.
    EXPECT_FALSE(second.icp_applied);
    EXPECT_NE(second.icp_status.find("too few obstacle points"), std::string::npos)
        << second.icp_status;
    EXPECT_TRUE(second.T_world_body_map.isApprox(loc_2, 1e-12));
    EXPECT_TRUE(second.obstacles.empty());
}

TEST(StopAndMap, WithoutCorrectionTheChainIsTheLocalisations) {
    StopAndMapConfig config;
    config.correct_pose = false;
    StopMapper mapper(config, lidar_mount());
    Rng rng(9);
    stop(mapper, features(), pose(0.0, 0.0, 0.0), pose(0.0, 0.0, 0.0), 0.0, rng);
    const StopMap second =
        stop(mapper, features(), pose(0.4, 0.0, 0.0), pose(0.45, 0.0, 0.0), 5.0, rng);
    EXPECT_EQ(second.icp_status, "off");
    EXPECT_TRUE(second.T_world_body_map.isApprox(pose(0.45, 0.0, 0.0), 1e-12));
    ASSERT_TRUE(mapper.last_map_pose().has_value());
}

TEST(StopAndMap, FramesOutsideAStopAreIgnoredAndTheCloudIsCapped) {
    StopAndMapConfig config;
    config.max_points = 25000;
    StopMapper mapper(config, lidar_mount());
    Rng rng(11);
    mapper.add_frame(frame(features(), pose(0, 0, 0), rng));  // no stop open
    EXPECT_FALSE(mapper.collecting());
    mapper.begin(0.0, pose(0, 0, 0));
    EXPECT_TRUE(mapper.collecting());
    for (int i = 0; i < 3; ++i) mapper.add_frame(frame(features(), pose(0, 0, 0), rng));
    const StopMap s = mapper.finish(1.0);
    EXPECT_EQ(s.num_frames, 3u);
    // The detection's voxel filter sees at most the cap.
    EXPECT_LE(s.detection.points.size(), 25000u);
    EXPECT_FALSE(mapper.collecting());
}

TEST(StopAndMap, AnEmptyStopIsAnOutcomeNotAnError) {
    StopMapper mapper({}, lidar_mount());
    mapper.begin(0.0, pose(0, 0, 0));
    const StopMap s = mapper.finish(3.0);
    EXPECT_EQ(s.detection.status, SurfaceStatus::kTooFewPoints);
    EXPECT_TRUE(s.obstacles.empty());
}

TEST(StopAndMap, MisuseAndBadConfigsAreClearErrors) {
    StopMapper mapper({}, lidar_mount());
    EXPECT_THROW(mapper.finish(1.0), InputError);
    mapper.begin(0.0, pose(0, 0, 0));
    EXPECT_THROW(mapper.begin(1.0, pose(0, 0, 0)), InputError);
    StopMapper other({}, lidar_mount());
    Eigen::Isometry3d nan_pose = pose(0, 0, 0);
    nan_pose.translation().x() = std::nan("");
    EXPECT_THROW(other.begin(0.0, nan_pose), InputError);
    EXPECT_THROW(StopMapper({}, nan_pose), InputError);
    StopAndMapConfig bad;
    bad.icp.max_translation_m = 0.0;
    try {
        StopMapper m(bad, lidar_mount());
        FAIL() << "expected a ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("stop_and_map.icp.max_translation_m"),
                  std::string::npos)
            << e.what();
    }
    bad = {};
    bad.max_points = 0;
    EXPECT_THROW(StopMapper(bad, lidar_mount()), ConfigError);
}

}  // namespace
}  // namespace scantling::perception
