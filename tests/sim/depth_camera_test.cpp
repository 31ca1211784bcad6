#include <scantling/core/error.hpp>
#include <scantling/sim/depth_camera.hpp>

#include "sensor_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace scantling::sim {
namespace {

using testing::noiseless;
using testing::plate_at_z;
using testing::TestScene;

// Brief: mean depth within 1 mm with noise off, noise std within 10 % of the model.
constexpr double kMeanTol_m = 1e-3;
constexpr double kStdRelTol = 0.1;

DepthCameraConfig small_l515(bool noise) {
    DepthCameraConfig config = intel_l515(320);
    config.depth_noise.dropout_probability = 0.0;
    if (!noise) config.depth_noise = noiseless(config.depth_noise);
    return config;
}

struct DepthStats {
    std::size_t valid = 0;
    double mean_m = 0.0;
    double std_m = 0.0;
};

DepthStats depth_stats(const PointCloud& cloud) {
    DepthStats s;
    double sum = 0.0, sum_sq = 0.0;
    for (const Eigen::Vector3d& p : cloud.points) {
        if (!std::isfinite(p.z())) continue;
        ++s.valid;
        sum += p.z();
        sum_sq += p.z() * p.z();
    }
    s.mean_m = sum / s.valid;
    s.std_m = std::sqrt(std::max(0.0, sum_sq / s.valid - s.mean_m * s.mean_m));
    return s;
}

TEST(DepthCamera, PresetsMatchTheDatasheets) {
    const DepthCameraConfig l515 = intel_l515();
    EXPECT_EQ(l515.intrinsics.width, 640);
    EXPECT_EQ(l515.intrinsics.height, 480);
    EXPECT_NEAR(l515.intrinsics.hfov_rad(), 70.0 * std::numbers::pi / 180.0, 1e-12);
    EXPECT_EQ(l515.min_depth_m, 0.25);
    EXPECT_EQ(l515.max_depth_m, 9.0);
    const DepthCameraConfig kinect = azure_kinect_nfov();
    EXPECT_EQ(kinect.intrinsics.width, 640);
    EXPECT_EQ(kinect.intrinsics.height, 576);
    EXPECT_NEAR(kinect.intrinsics.vfov_rad(), 65.0 * std::numbers::pi / 180.0, 1e-12);
    EXPECT_EQ(kinect.max_depth_m, 3.86);
    EXPECT_EQ(azure_kinect_nfov(true).intrinsics.width, 320);
    EXPECT_THROW(intel_l515(500), ConfigError);
}

TEST(DepthCamera, NoiselessPlaneIsSeenAtItsDepthInEveryPixel) {
    const TestScene scene(plate_at_z(2.0, 50.0, true));
    const DepthCamera camera(small_l515(false));
    Rng rng(1);
    const PointCloud cloud = camera.scan(scene.view(), Eigen::Isometry3d::Identity(), rng, 4.0);
    ASSERT_EQ(cloud.size(), 320u * 240u);
    EXPECT_EQ(cloud.stamp_s, 4.0);
    const DepthStats s = depth_stats(cloud);
    EXPECT_EQ(s.valid, cloud.size());
    EXPECT_NEAR(s.mean_m, 2.0, kMeanTol_m);
    for (const Eigen::Vector3d& p : cloud.points) ASSERT_NEAR(p.z(), 2.0, 1e-9);
    // Pixel (u, v) sees the plate where its ray meets z = 2.
    const PinholeIntrinsics& k = camera.config().intrinsics;
    const Eigen::Vector3d expected = k.unproject(Eigen::Vector2d(10, 200), 2.0);
    EXPECT_TRUE(cloud.points[200 * 320 + 10].isApprox(expected, 1e-12));
}

TEST(DepthCamera, NoiseGrowsWithDepthAsModelled) {
    const DepthCamera camera(small_l515(true));
    for (const double depth_m : {1.0, 4.0}) {
        const TestScene scene(plate_at_z(depth_m, 100.0, true));
        Rng rng(2);
        const DepthStats s =
            depth_stats(camera.scan(scene.view(), Eigen::Isometry3d::Identity(), rng));
        const double sigma_m = camera.config().depth_noise.sigma_at(depth_m);
        EXPECT_NEAR(s.mean_m, depth_m, 4.0 * sigma_m / std::sqrt(double(s.valid)));
        EXPECT_NEAR(s.std_m, sigma_m, kStdRelTol * sigma_m) << "depth " << depth_m;
    }
}

TEST(DepthCamera, PixelsWithoutReturnAreNaNInTheCloudAndZeroInTheImage) {
    const TestScene scene(plate_at_z(2.0, 0.5, true));  // smaller than the field of view
    const DepthCamera camera(small_l515(false));
    Rng rng(3);
    const PointCloud cloud = camera.scan(scene.view(), Eigen::Isometry3d::Identity(), rng);
    EXPECT_TRUE(std::isnan(cloud.points[0].x()));               // corner: no plate
    EXPECT_NEAR(cloud.points[120 * 320 + 160].z(), 2.0, 1e-9);  // centre: plate
    EXPECT_EQ(cloud.intensities[0], 0.0f);
    const DepthImage image = to_depth_image(cloud, 320, 240);
    EXPECT_EQ(image.depth_m[0], 0.0f);
    EXPECT_FLOAT_EQ(image.depth_m[120 * 320 + 160], 2.0f);
    EXPECT_THROW(to_depth_image(cloud, 320, 241), InputError);
}

TEST(DepthCamera, SurfacesOutsideTheDepthWindowGiveNoReturn) {
    const DepthCamera camera(small_l515(false));
    for (const double depth_m : {0.2, 9.5}) {
        const TestScene scene(plate_at_z(depth_m, 100.0, true));
        Rng rng(4);
        EXPECT_EQ(depth_stats(camera.scan(scene.view(), Eigen::Isometry3d::Identity(), rng)).valid,
                  0u)
            << depth_m;
    }
}

TEST(DepthCamera, OneAndTwoThreadsAndSameSeedGiveIdenticalFrames) {
    const TestScene scene(plate_at_z(3.0, 100.0, true));
    const DepthCamera camera(intel_l515(320));
    Rng a(5), b(5), c(6);
    const PointCloud one = camera.scan(scene.view(), Eigen::Isometry3d::Identity(), a, 0.0, {1});
    const PointCloud two = camera.scan(scene.view(), Eigen::Isometry3d::Identity(), b, 0.0, {2});
    const PointCloud other = camera.scan(scene.view(), Eigen::Isometry3d::Identity(), c, 0.0, {2});
    const DepthImage i1 = to_depth_image(one, 320, 240), i2 = to_depth_image(two, 320, 240);
    EXPECT_EQ(i1.depth_m, i2.depth_m);
    EXPECT_NE(i1.depth_m, to_depth_image(other, 320, 240).depth_m);
}

TEST(DepthCamera, BadConfigsThrowNamingTheField) {
    DepthCameraConfig c;
    c.max_depth_m = 0.1;
    try {
        c.validate();
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("depth_camera.max_depth_m = 0.1"), std::string::npos);
    }
    c = DepthCameraConfig{};
    c.intrinsics.fx = 0.0;
    try {
        DepthCamera{c};
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("depth_camera.intrinsics.fx = 0"), std::string::npos);
    }
    c = DepthCameraConfig{};
    c.depth_noise.sigma_per_m2 = -1.0;
    EXPECT_THROW(DepthCamera{c}, ConfigError);
}

}  // namespace
}  // namespace scantling::sim
