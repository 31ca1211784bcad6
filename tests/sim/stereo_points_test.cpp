#include <scantling/core/error.hpp>
#include <scantling/sim/stereo_points.hpp>

#include "sensor_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace scantling::sim {
namespace {

using testing::add_box;
using testing::add_surface;
using testing::plate_at_z;
using testing::TestScene;

constexpr double kStdRelTol = 0.1;  // brief: noise std within 10 % of the model

StereoPointsConfig noiseless_stereo() {
    StereoPointsConfig config;
    config.disparity_sigma_px = 0.0;
    return config;
}

TEST(StereoPoints, UntexturedSurfaceGivesNoPoints) {
    const TestScene scene(plate_at_z(2.0, 100.0, false));
    const StereoPoints stereo;
    Rng rng(1);
    EXPECT_TRUE(stereo.scan(scene.view(), Eigen::Isometry3d::Identity(), rng).empty());
}

TEST(StereoPoints, TexturedSurfaceGivesSparsePointsOnIt) {
    const TestScene scene(plate_at_z(2.0, 100.0, true));
    const StereoPoints stereo(noiseless_stereo());
    Rng rng(2);
    const PointCloud cloud = stereo.scan(scene.view(), Eigen::Isometry3d::Identity(), rng, 5.0);
    // 21 x 20 cells of 40 px; the left ~14 px column (f b / z) is outside the right image.
    EXPECT_LE(cloud.size(), 420u);
    EXPECT_GE(cloud.size(), 400u);
    EXPECT_EQ(cloud.stamp_s, 5.0);
    for (const Eigen::Vector3d& p : cloud.points) {
        ASSERT_NEAR(p.z(), 2.0, 1e-9);
        const auto pixel = stereo.config().intrinsics.project(p);
        ASSERT_TRUE(pixel.has_value());
        const Eigen::Vector3d p_right = p - Eigen::Vector3d(stereo.config().baseline_m, 0, 0);
        ASSERT_TRUE(stereo.config().intrinsics.project(p_right).has_value());
    }
}

TEST(StereoPoints, DepthNoiseGrowsWithDepthSquared) {
    const StereoPoints stereo;
    const double fb = stereo.config().intrinsics.fx * stereo.config().baseline_m;
    EXPECT_NEAR(stereo.depth_sigma_m(3.0), 9.0 * 0.3 / fb, 1e-15);
    const TestScene scene(plate_at_z(3.0, 100.0, true));
    Rng rng(3);
    double sum = 0.0, sum_sq = 0.0;
    std::size_t n = 0;
    for (int frame = 0; frame < 20; ++frame) {
        for (const Eigen::Vector3d& p :
             stereo.scan(scene.view(), Eigen::Isometry3d::Identity(), rng).points) {
            sum += p.z() - 3.0;
            sum_sq += (p.z() - 3.0) * (p.z() - 3.0);
            ++n;
        }
    }
    ASSERT_GT(n, 7000u);
    const double sigma_m = stereo.depth_sigma_m(3.0);
    EXPECT_NEAR(sum / n, 0.0, 4.0 * sigma_m / std::sqrt(double(n)));
    EXPECT_NEAR(std::sqrt(sum_sq / n), sigma_m, kStdRelTol * sigma_m);
}

TEST(StereoPoints, PointsHiddenFromTheRightCameraAreDropped) {
    World world = plate_at_z(2.0, 100.0, true);
    // A wall in the plane x = 0.03 between the cameras, from z = 0.01 to 1.999: the left camera
    // (x < 0.03) sees the plate only at x < 0.03, the right camera (x = 0.064) only at x > 0.03.
    const int tag = add_surface(world, "divider", false);
    add_box(world, {0.0295, -100.0, 0.01}, {0.0305, 100.0, 1.999}, tag);
    const TestScene scene(std::move(world));
    const StereoPoints stereo(noiseless_stereo());
    Rng rng(4);
    EXPECT_TRUE(stereo.scan(scene.view(), Eigen::Isometry3d::Identity(), rng).empty());
}

TEST(StereoPoints, OneAndTwoThreadsAndSameSeedGiveIdenticalPoints) {
    const TestScene scene(plate_at_z(2.5, 100.0, true));
    const StereoPoints stereo;
    Rng a(5), b(5), c(6);
    const PointCloud one = stereo.scan(scene.view(), Eigen::Isometry3d::Identity(), a, 0.0, {1});
    const PointCloud two = stereo.scan(scene.view(), Eigen::Isometry3d::Identity(), b, 0.0, {2});
    const PointCloud other = stereo.scan(scene.view(), Eigen::Isometry3d::Identity(), c, 0, {2});
    EXPECT_EQ(one.points, two.points);
    EXPECT_NE(one.points, other.points);
}

TEST(StereoPoints, BadConfigsThrowNamingTheField) {
    StereoPointsConfig c;
    c.baseline_m = 0.0;
    try {
        StereoPoints{c};
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("stereo_points.baseline_m = 0"), std::string::npos);
    }
    c = StereoPointsConfig{};
    c.feature_spacing_px = 0.5;
    EXPECT_THROW(StereoPoints{c}, ConfigError);
    c = StereoPointsConfig{};
    c.max_depth_m = 0.1;
    EXPECT_THROW(StereoPoints{c}, ConfigError);
}

}  // namespace
}  // namespace scantling::sim
