#include <scantling/core/error.hpp>
#include <scantling/sim/rosette_lidar.hpp>

#include "sensor_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>

namespace scantling::sim {
namespace {

using testing::box_exit_range;
using testing::box_room;
using testing::noiseless;
using testing::TestScene;

constexpr double kExact_m = 1e-9;  // double-precision hit refinement at room scale
constexpr double kDeg = std::numbers::pi / 180.0;

const Eigen::Vector3d kLo(-3.0, -4.0, -2.5);
const Eigen::Vector3d kHi(6.0, 4.5, 3.0);

RosetteLidarConfig noiseless_mid70() {
    RosetteLidarConfig config = livox_mid70();
    config.returns = noiseless(config.returns);
    return config;
}

// Beam directions over [t0, t0 + duration) binned into 0.25° cells of the (polar, azimuth)
// disc: about the beam divergence of the Mid-70 (0.28° x 0.03°).
std::set<std::pair<int, int>> covered_cells(const RosetteLidar& lidar, double t0,
                                            double duration_s) {
    constexpr double kCell_rad = 0.25 * kDeg;
    std::set<std::pair<int, int>> cells;
    const int n = static_cast<int>(std::lround(duration_s * lidar.config().point_rate_hz));
    for (int k = 0; k < n; ++k) {
        const Eigen::Vector3d d = lidar.beam_direction(t0 + k / lidar.config().point_rate_hz);
        const double polar = std::acos(d.x());
        const double azimuth = std::atan2(d.z(), d.y());
        cells.emplace(static_cast<int>(std::floor(polar * std::cos(azimuth) / kCell_rad)),
                      static_cast<int>(std::floor(polar * std::sin(azimuth) / kCell_rad)));
    }
    return cells;
}

TEST(RosetteLidar, FrameHasOnePointPerFiringWithinTheCircularFieldOfView) {
    const TestScene scene(box_room(kLo, kHi));
    const RosetteLidar lidar(noiseless_mid70());
    Rng rng(1);
    const PointCloud cloud = lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng, 3.0);
    ASSERT_EQ(cloud.size(), 10000u);  // 100 kHz / 10 Hz, closed room
    EXPECT_EQ(cloud.stamp_s, 3.0);
    EXPECT_FALSE(cloud.has_rings());
    double max_polar = 0.0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3d& p = cloud.points[i];
        const Eigen::Vector3d d = p.normalized();
        ASSERT_NEAR(p.norm(), box_exit_range(Eigen::Vector3d::Zero(), d, kLo, kHi), kExact_m);
        ASSERT_FLOAT_EQ(cloud.times_s[i], static_cast<float>(i * 1e-5));
        max_polar = std::max(max_polar, std::acos(std::min(1.0, d.x())));
    }
    EXPECT_LE(max_polar, 35.2 * kDeg + 1e-9);
    EXPECT_GT(max_polar, 35.0 * kDeg);  // the pattern reaches the edge of the FOV
}

TEST(RosetteLidar, CoverageGrowsWithIntegrationTime) {
    const RosetteLidar lidar;
    const auto one_frame = covered_cells(lidar, 0.0, 0.1);
    const auto next_frame = covered_cells(lidar, 0.1, 0.1);
    const auto one_second = covered_cells(lidar, 0.0, 1.0);
    // Measured with the defaults: 14 % of the disc's cells after 0.1 s, 46 % after 1 s, and
    // consecutive frames share 27 % of their cells.
    EXPECT_GT(one_second.size(), 3 * one_frame.size());
    std::size_t shared = 0;
    for (const auto& cell : next_frame) shared += one_frame.count(cell);
    EXPECT_LT(shared, one_frame.size() / 2);
}

TEST(RosetteLidar, RangeNoiseMatchesTheModel) {
    const TestScene scene(box_room(kLo, kHi));
    RosetteLidarConfig config = livox_mid70();
    config.returns.dropout_probability = 0.0;
    const RosetteLidar lidar(config);
    Rng rng(2);
    double sum = 0.0, sum_sq = 0.0;
    std::size_t n = 0;
    for (int frame = 0; frame < 3; ++frame) {
        const PointCloud cloud =
            lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng, 0.1 * frame);
        for (const Eigen::Vector3d& p : cloud.points) {
            const double r = p.norm() - box_exit_range({0, 0, 0}, p.normalized(), kLo, kHi);
            sum += r;
            sum_sq += r * r;
            ++n;
        }
    }
    const double sigma_m = config.returns.sigma_m;
    EXPECT_NEAR(sum / n, 0.0, 4.0 * sigma_m / std::sqrt(static_cast<double>(n)));
    EXPECT_NEAR(std::sqrt(sum_sq / n), sigma_m, 0.1 * sigma_m);
}

TEST(RosetteLidar, MovingScanExpressesPointsInTheirFiringFrame) {
    const TestScene scene(box_room(kLo, kHi));
    const RosetteLidar lidar(noiseless_mid70());
    const double speed_mps = 1.5;  // towards the +x wall the sensor looks at
    const PoseAtTime pose_at = [&](double t) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation().x() = speed_mps * t;
        return T;
    };
    Rng a(3), b(3);
    const PointCloud still = lidar.scan(scene.view(), pose_at(0.0), a, 0.0);
    const PointCloud moving = lidar.scan_moving(scene.view(), pose_at, 0.0, b);
    ASSERT_EQ(still.size(), moving.size());
    int checked = 0;
    for (std::size_t i = 0; i < still.size(); ++i) {
        if (std::abs(still.points[i].x() - kHi.x()) > 1e-9) continue;
        ++checked;
        ASSERT_NEAR(moving.points[i].x(), kHi.x() - speed_mps * i * 1e-5, kExact_m);
    }
    EXPECT_GT(checked, 5000);
}

TEST(RosetteLidar, OneAndTwoThreadsGiveIdenticalClouds) {
    const TestScene scene(box_room(kLo, kHi));
    const RosetteLidar lidar;
    Rng a(4), b(4);
    const PointCloud one = lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), a, 0.0, {1});
    const PointCloud two = lidar.scan(scene.view(), Eigen::Isometry3d::Identity(), b, 0.0, {2});
    EXPECT_EQ(one.points, two.points);
    EXPECT_EQ(one.times_s, two.times_s);
}

TEST(RosetteLidar, BadConfigsThrowNamingTheField) {
    RosetteLidarConfig c;
    c.fov_rad = 4.0;
    EXPECT_THROW(c.validate(), ConfigError);
    try {
        c.validate();
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("rosette_lidar.fov_rad = 4"), std::string::npos);
    }
    c = RosetteLidarConfig{};
    c.frame_rate_hz = 2e5;
    EXPECT_THROW(RosetteLidar{c}, ConfigError);
    c = RosetteLidarConfig{};
    c.prism_b_hz = 0.0;
    EXPECT_THROW(RosetteLidar{c}, ConfigError);
    c = RosetteLidarConfig{};
    c.returns.weak_dropout_probability = 1.5;
    EXPECT_THROW(RosetteLidar{c}, ConfigError);
}

}  // namespace
}  // namespace scantling::sim
