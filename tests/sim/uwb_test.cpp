#include <scantling/core/error.hpp>
#include <scantling/sim/uwb.hpp>

#include "sensor_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace scantling::sim {
namespace {

using testing::add_box;
using testing::add_surface;
using testing::box_room;
using testing::TestScene;

constexpr double kExact_m = 1e-12;
const Eigen::Vector3d kLo(-2.0, -3.0, -2.0);
const Eigen::Vector3d kHi(5.0, 3.0, 2.5);
const Eigen::Vector3d kTag(1.0, 0.0, 0.0);

UwbConfig four_anchors() {
    UwbConfig config;
    config.anchors = {{10, {4.9, 2.9, 2.4}},
                      {11, {-1.9, 2.9, 2.4}},
                      {12, {4.9, -2.9, 0.0}},
                      {13, {-1.9, -2.9, 0.0}}};
    return config;
}

// The room with a box on the segment from the tag to anchor 10.
World room_with_occluder() {
    World world = box_room(kLo, kHi);
    const Eigen::Vector3d mid = 0.5 * (kTag + Eigen::Vector3d(4.9, 2.9, 2.4));
    add_box(world, mid - Eigen::Vector3d::Constant(0.3), mid + Eigen::Vector3d::Constant(0.3),
            add_surface(world, "occluder"));
    return world;
}

Eigen::Isometry3d at(const Eigen::Vector3d& p) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = p;
    return T;
}

TEST(Uwb, LineOfSightRangesEqualTheDistances) {
    const TestScene scene(box_room(kLo, kHi));
    const UwbTag tag(noiseless(four_anchors()));
    Rng rng(1);
    const UwbMeasurement m = tag.measure(scene.view(), at(kTag), rng, 3.0);
    EXPECT_EQ(m.stamp_s, 3.0);
    ASSERT_EQ(m.ranges.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        const UwbAnchor& anchor = tag.config().anchors[i];
        EXPECT_EQ(m.ranges[i].anchor_id, anchor.id);
        EXPECT_TRUE(m.ranges[i].valid);
        EXPECT_TRUE(m.ranges[i].line_of_sight);
        EXPECT_NEAR(m.ranges[i].range_m, (anchor.position_world - kTag).norm(), kExact_m);
    }
}

TEST(Uwb, AnOccluderMakesTheRangeNlosAndBiasedLong) {
    const TestScene scene(room_with_occluder());
    UwbConfig config = noiseless(four_anchors());
    config.nlos_bias_mean_m = 0.5;
    const UwbTag tag(config);
    Rng rng(2);
    const double true_m = (Eigen::Vector3d(4.9, 2.9, 2.4) - kTag).norm();
    const int n = 4000;
    double excess_sum = 0.0;
    for (int k = 0; k < n; ++k) {
        const UwbMeasurement m = tag.measure(scene.view(), at(kTag), rng);
        ASSERT_FALSE(m.ranges[0].line_of_sight);
        ASSERT_TRUE(m.ranges[0].valid);
        EXPECT_GE(m.ranges[0].range_m, true_m);
        excess_sum += m.ranges[0].range_m - true_m;
        EXPECT_TRUE(m.ranges[1].line_of_sight);
        EXPECT_NEAR(m.ranges[1].range_m, (Eigen::Vector3d(-1.9, 2.9, 2.4) - kTag).norm(), kExact_m);
    }
    // Exponential excess, mean 0.5 m, std 0.5 m: 4σ of the mean of n ≈ 0.032 m.
    EXPECT_NEAR(excess_sum / n, 0.5, 4.0 * 0.5 / std::sqrt(n));
}

TEST(Uwb, NoiseDropoutsOutliersAndRangeLimitFollowTheConfig) {
    const TestScene scene(box_room(kLo, kHi));
    UwbConfig config = noiseless(four_anchors());
    config.range_sigma_m = 0.05;
    config.dropout_probability = 0.1;
    config.max_range_m = 5.0;  // anchor 10 is 5.1 m away
    const UwbTag tag(config);
    Rng rng(3);
    const int n = 4000;
    int lost = 0;
    double sq = 0.0;
    const double true_m = (Eigen::Vector3d(4.9, -2.9, 0.0) - kTag).norm();
    for (int k = 0; k < n; ++k) {
        const UwbMeasurement m = tag.measure(scene.view(), at(kTag), rng);
        EXPECT_FALSE(m.ranges[0].valid);
        EXPECT_TRUE(std::isnan(m.ranges[0].range_m));
        if (!m.ranges[2].valid) ++lost;
        if (m.ranges[2].valid) sq += std::pow(m.ranges[2].range_m - true_m, 2);
    }
    EXPECT_NEAR(lost, 0.1 * n, 4.0 * std::sqrt(0.1 * 0.9 * n));  // binomial 4σ
    EXPECT_NEAR(std::sqrt(sq / (n - lost)), 0.05, 4.0 * 0.05 / std::sqrt(2.0 * (n - lost)));

    config = noiseless(four_anchors());
    config.outlier_probability = 1.0;
    const UwbMeasurement m = UwbTag(config).measure(scene.view(), at(kTag), rng);
    for (const UwbRange& r : m.ranges) {
        EXPECT_TRUE(r.outlier);
        EXPECT_GE(r.range_m, 0.0);
        EXPECT_LT(r.range_m, config.max_range_m);
    }
}

TEST(Uwb, SameSeedGivesIdenticalRanges) {
    const TestScene scene(room_with_occluder());
    const UwbTag tag(four_anchors());
    Rng a(4), b(4);
    for (int k = 0; k < 50; ++k) {
        const UwbMeasurement ma = tag.measure(scene.view(), at(kTag), a);
        const UwbMeasurement mb = tag.measure(scene.view(), at(kTag), b);
        for (std::size_t i = 0; i < ma.ranges.size(); ++i) {
            EXPECT_EQ(ma.ranges[i].valid, mb.ranges[i].valid);
            if (ma.ranges[i].valid) {
                EXPECT_EQ(ma.ranges[i].range_m, mb.ranges[i].range_m);
            }
        }
    }
}

TEST(Uwb, BadConfigsThrowNamingTheField) {
    UwbConfig c;
    try {
        UwbTag tag(c);
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("uwb.anchors is empty"), std::string::npos);
    }
    c = four_anchors();
    c.anchors[2].id = 10;
    try {
        UwbTag tag(c);
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("uwb.anchors[2].id = 10"), std::string::npos);
    }
    c = four_anchors();
    c.anchors[1].position_world.x() = std::nan("");
    EXPECT_THROW(UwbTag{c}, ConfigError);
    c = four_anchors();
    c.nlos_dropout_probability = 1.5;
    EXPECT_THROW(UwbTag{c}, ConfigError);
    const TestScene scene(box_room(kLo, kHi));
    Rng rng(5);
    Eigen::Isometry3d bad = at(kTag);
    bad.translation().x() = std::nan("");
    EXPECT_THROW(UwbTag(four_anchors()).measure(scene.view(), bad, rng), InputError);
}

}  // namespace
}  // namespace scantling::sim
