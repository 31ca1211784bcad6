#include <scantling/core/error.hpp>
#include <scantling/sim/range_finder.hpp>

#include "sensor_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace scantling::sim {
namespace {

using testing::add_box;
using testing::add_surface;
using testing::box_room;
using testing::TestScene;

constexpr double kExact_m = 1e-9;   // double-precision hit refinement
constexpr double kStdRelTol = 0.1;  // sample std of 4000 readings: ~1 % statistical error

const Eigen::Vector3d kLo(-2.0, -3.0, -2.0);
const Eigen::Vector3d kHi(5.0, 3.0, 2.5);

Eigen::Isometry3d at(const Eigen::Vector3d& position) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = position;
    return T;
}

template <typename Config>
Config noiseless(Config config) {
    config.range_sigma_m = 0.0;
    config.range_sigma_fraction = 0.0;
    return config;
}

TEST(RangeFinder, DownAndUpLookingSensorsReturnTheKnownHeights) {
    const TestScene scene(box_room(kLo, kHi));
    const RangeFinder down(noiseless(down_looking_lidar_lite_v3()));
    const RangeFinder up(noiseless(up_looking_teraranger_evo_60m()));
    Rng rng(1);
    const RangeMeasurement d = down.measure(scene.view(), at({1.0, 0.5, -0.3}), rng, 2.0);
    ASSERT_TRUE(d.valid);
    EXPECT_NEAR(d.range_m, 1.7, kExact_m);
    EXPECT_EQ(d.stamp_s, 2.0);
    const RangeMeasurement u = up.measure(scene.view(), at({1.0, 0.5, -0.3}), rng);
    ASSERT_TRUE(u.valid);
    EXPECT_NEAR(u.range_m, 2.8, kExact_m);  // the axis ray is the shortest of the cone
    EXPECT_EQ(up.rays_sensor().size(), 7u);
}

TEST(RangeFinder, NothingInRangeGivesAnInvalidReading) {
    const TestScene scene(box_room(kLo, kHi));
    const RangeFinder sonar(ultrasonic_hc_sr04());  // 4 m; the +x wall is 5 m away
    Rng rng(2);
    const RangeMeasurement m = sonar.measure(scene.view(), Eigen::Isometry3d::Identity(), rng);
    EXPECT_FALSE(m.valid);
    EXPECT_TRUE(std::isnan(m.range_m));
}

TEST(RangeFinder, UltrasonicConeReportsTheNearestEchoOffAxis) {
    World world = box_room(kLo, kHi);
    // A small obstacle 1 m ahead, 5–30 cm to the left: off the axis, inside the 7.5° cone.
    add_box(world, {1.0, 0.05, -0.2}, {1.2, 0.3, 0.2}, add_surface(world, "obstacle"));
    const TestScene scene(std::move(world));
    RangeFinderConfig axis_only = noiseless(ultrasonic_hc_sr04());
    axis_only.cone_rings = 0;
    Rng rng(3);
    EXPECT_FALSE(RangeFinder(axis_only).measure(scene.view(), at({0, 0, 0}), rng).valid);
    const RangeMeasurement m =
        RangeFinder(noiseless(ultrasonic_hc_sr04())).measure(scene.view(), at({0, 0, 0}), rng);
    ASSERT_TRUE(m.valid);
    EXPECT_GE(m.range_m, 1.0);
    EXPECT_LT(m.range_m, 1.0 / std::cos(7.5 * std::numbers::pi / 180.0) + kExact_m);
}

TEST(RangeFinder, NoiseMatchesTheDatasheetSigma) {
    const TestScene scene(box_room(kLo, kHi));
    const RangeFinder up(up_looking_teraranger_evo_60m());  // σ = max(4 cm, 1.5 %)
    Rng rng(4);
    double sum = 0.0, sum_sq = 0.0;
    const int n = 4000;
    for (int i = 0; i < n; ++i) {
        const double r = up.measure(scene.view(), at({0.0, 0.0, -1.5}), rng).range_m - 4.0;
        sum += r;
        sum_sq += r * r;
    }
    EXPECT_NEAR(sum / n, 0.0, 4.0 * 0.06 / std::sqrt(double(n)));
    EXPECT_NEAR(std::sqrt(sum_sq / n), 0.06, kStdRelTol * 0.06);  // 1.5 % of 4 m
}

TEST(RangeFinder, SameSeedGivesIdenticalReadings) {
    const TestScene scene(box_room(kLo, kHi));
    const RangeFinder down(down_looking_lidar_lite_v3());
    Rng a(5), b(5);
    for (int i = 0; i < 10; ++i) {
        EXPECT_EQ(down.measure(scene.view(), at({0, 0, 0}), a).range_m,
                  down.measure(scene.view(), at({0, 0, 0}), b).range_m);
    }
}

TEST(RangeFinder, BadConfigsThrowNamingTheField) {
    RangeFinderConfig c;
    c.max_range_m = 0.0;
    try {
        RangeFinder{c};
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("range_finder.max_range_m = 0"), std::string::npos);
    }
    c = RangeFinderConfig{};
    c.cone_rings = -1;
    EXPECT_THROW(RangeFinder{c}, ConfigError);
    c = RangeFinderConfig{};
    c.beam_half_angle_rad = 2.0;
    EXPECT_THROW(RangeFinder{c}, ConfigError);
    c = RangeFinderConfig{};
    c.range_sigma_m = -0.1;
    EXPECT_THROW(RangeFinder{c}, ConfigError);
}

}  // namespace
}  // namespace scantling::sim
