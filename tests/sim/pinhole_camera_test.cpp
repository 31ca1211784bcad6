#include <scantling/core/error.hpp>
#include <scantling/sim/pinhole_camera.hpp>

#include "sensor_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace scantling::sim {
namespace {

using testing::add_box;
using testing::add_surface;
using testing::plate_at_z;
using testing::TestScene;

constexpr double kPixelTol = 1e-9;  // projection is a handful of double operations
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr int kWidth = 640;

// A corrosion patch (id 7) on the plate z = 3, facing the camera at the origin.
World plate_with_defect(bool textured = true) {
    World world = plate_at_z(3.0, 1.0, textured);
    Defect defect;
    defect.id = 7;
    defect.centre = Eigen::Vector3d(0.2, 0.1, 3.0);
    defect.normal = -Eigen::Vector3d::UnitZ();
    defect.radius_m = 0.1;
    defect.surface_tag = 0;
    world.metadata.defects.push_back(defect);
    return world;
}

PinholeCameraConfig noiseless_camera() {
    PinholeCameraConfig config = uav3d_camera();
    config.pixel_noise_dn = 0.0;
    return config;
}

TEST(PinholeCamera, ProjectsAKnownPointToItsPixelAndUnprojectInverts) {
    const PinholeIntrinsics k = uav3d_camera().intrinsics;
    EXPECT_NEAR(k.hfov_rad(), 66.0 * kDeg, 1e-12);
    EXPECT_NEAR(k.vfov_rad(), 49.5 * kDeg, 1e-12);
    const double fx = 320.0 / std::tan(33.0 * kDeg);
    const double fy = 240.0 / std::tan(24.75 * kDeg);
    const Eigen::Vector3d p(0.5, -0.25, 2.0);
    const auto pixel = k.project(p);
    ASSERT_TRUE(pixel.has_value());
    EXPECT_NEAR(pixel->x(), 319.5 + fx * 0.25, kPixelTol);
    EXPECT_NEAR(pixel->y(), 239.5 - fy * 0.125, kPixelTol);
    EXPECT_TRUE(k.unproject(*pixel, 2.0).isApprox(p, 1e-14));
    EXPECT_TRUE(k.ray_direction(*pixel).isApprox(p.normalized(), 1e-14));
}

TEST(PinholeCamera, PointsBehindOrOutsideTheImageDoNotProject) {
    const PinholeIntrinsics k = uav3d_camera().intrinsics;
    EXPECT_FALSE(k.project({0.0, 0.0, -1.0}).has_value());
    EXPECT_FALSE(k.project({0.0, 0.0, 0.0}).has_value());
    EXPECT_FALSE(k.project({2.0, 0.0, 1.0}).has_value());  // 63° off axis > 33°
    EXPECT_TRUE(k.contains({-0.5, -0.5}));
    EXPECT_FALSE(k.contains({639.5, 0.0}));
}

TEST(PinholeCamera, DefectInFrontIsVisibleAndHiddenBehindAnOccluder) {
    const PinholeCamera camera(noiseless_camera());
    {
        const TestScene scene(plate_with_defect());
        EXPECT_EQ(camera.visible_defects(scene.view(), Eigen::Isometry3d::Identity()),
                  std::vector<int>{7});
        // Turned around, the camera no longer sees it.
        Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
        T_world_body.linear() =
            Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitY()).toRotationMatrix();
        EXPECT_TRUE(camera.visible_defects(scene.view(), T_world_body).empty());
    }
    World world = plate_with_defect();
    add_box(world, {0.0, 0.0, 1.4}, {0.2, 0.2, 1.6}, add_surface(world, "occluder"));
    const TestScene occluded(std::move(world));
    EXPECT_TRUE(camera.visible_defects(occluded.view(), Eigen::Isometry3d::Identity()).empty());
}

TEST(PinholeCamera, SightingsAreTheProjectedCentresWithTheApparentRadius) {
    const PinholeCamera camera(noiseless_camera());
    const TestScene scene(plate_with_defect());
    const std::vector<io::DefectSighting> sightings =
        camera.sight_defects(scene.view(), Eigen::Isometry3d::Identity());
    ASSERT_EQ(sightings.size(), 1u);
    const io::Defect& defect = scene.view().metadata.defects[0];
    const PinholeIntrinsics& k = camera.config().intrinsics;
    const Eigen::Vector3d c = defect.centre;  // the body is the camera here
    EXPECT_EQ(sightings[0].defect_id, 7);
    EXPECT_NEAR(sightings[0].pixel.x(), k.fx * c.x() / c.z() + k.cx, 1e-9);
    EXPECT_NEAR(sightings[0].pixel.y(), k.fy * c.y() / c.z() + k.cy, 1e-9);
    EXPECT_NEAR(sightings[0].radius_px, k.fx * defect.radius_m / c.z(), 1e-9);
}

TEST(PinholeCamera, DefectSeenFromBehindItsPlateIsNotVisible) {
    World world = plate_with_defect();
    world.metadata.defects[0].normal = Eigen::Vector3d::UnitZ();  // on the far face
    const TestScene scene(std::move(world));
    const PinholeCamera camera(noiseless_camera());
    EXPECT_TRUE(camera.visible_defects(scene.view(), Eigen::Isometry3d::Identity()).empty());
}

TEST(PinholeCamera, RenderDrawsDefectsSurfacesAndBackground) {
    const TestScene scene(plate_with_defect());
    const PinholeCamera camera(noiseless_camera());
    Rng rng(1);
    const RgbImage image = camera.render(scene.view(), Eigen::Isometry3d::Identity(), rng);
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.pixels.size(), 640u * 480u);
    const auto pixel = camera.config().intrinsics.project({0.2, 0.1, 3.0});
    ASSERT_TRUE(pixel.has_value());
    const Rgb8 seen = image.pixels[std::lround(pixel->y()) * kWidth + std::lround(pixel->x())];
    // Head-on (cos 0.997): light = 0.2 + 0.8 cos ≈ 0.998 of the corrosion colour.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], kCorrosionRgb[c], 1) << "channel " << c;
    EXPECT_EQ(image.pixels[0], Rgb8(0, 0, 0));  // corner: beyond the plate
    // An untextured plate is 255 · albedo · (ambient + (1 − ambient) cos θ) in every pixel; the
    // textured one varies by up to ± texture_contrast around that.
    const TestScene plain(plate_with_defect(false));
    const RgbImage plain_image = camera.render(plain.view(), Eigen::Isometry3d::Identity(), rng);
    const PinholeIntrinsics& k = camera.config().intrinsics;
    std::set<int> textured_greys;
    for (int v = 230; v < 250; ++v) {
        for (int u = 200; u < 260; ++u) {
            const double cos_theta = k.ray_direction(Eigen::Vector2d(u, v)).z();
            const double expected = 255.0 * 0.5 * (0.2 + 0.8 * cos_theta);
            ASSERT_NEAR(plain_image.pixels[v * kWidth + u][0], expected, 0.5 + 1e-9);
            textured_greys.insert(image.pixels[v * kWidth + u][0]);
        }
    }
    EXPECT_GT(textured_greys.size(), 10u);
}

TEST(PinholeCamera, OneAndTwoThreadsGiveIdenticalNoisyImages) {
    const TestScene scene(plate_with_defect());
    const PinholeCamera camera(rov_camera(320));
    EXPECT_EQ(camera.config().intrinsics.height, 180);
    Rng a(2), b(2);
    const RgbImage one = camera.render(scene.view(), Eigen::Isometry3d::Identity(), a, {1});
    const RgbImage two = camera.render(scene.view(), Eigen::Isometry3d::Identity(), b, {2});
    EXPECT_EQ(one.pixels, two.pixels);
}

TEST(PinholeCamera, BadConfigsThrowNamingTheField) {
    PinholeCameraConfig c;
    c.ambient = 2.0;
    try {
        PinholeCamera{c};
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("pinhole_camera.ambient = 2"), std::string::npos);
    }
    c = PinholeCameraConfig{};
    c.intrinsics.width = 0;
    EXPECT_THROW(PinholeCamera{c}, ConfigError);
    c = PinholeCameraConfig{};
    c.texture_contrast = 1.0;
    EXPECT_THROW(PinholeCamera{c}, ConfigError);
    EXPECT_THROW(PinholeIntrinsics::from_fov(640, 480, 3.2, 1.0), ConfigError);
    EXPECT_THROW(rov_camera(8), ConfigError);
}

}  // namespace
}  // namespace scantling::sim
