// Laser-pointer triangulation (perception/laser_pointers.hpp) on the simulator's own camera:
// two parallel red pointers beside the ROV camera (sim/laser_spots.hpp) on a hull plate at
// known distance and pitch, pixel noise on. Issue 14 item 5: distance within 2 %, pitch within
// 1°. And a camera without lasers renders exactly the image it rendered before lasers existed.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include <scantling/core/random.hpp>
#include <scantling/perception/laser_pointers.hpp>
#include <scantling/sim/pinhole_camera.hpp>

#include "../sim/sensor_test_support.hpp"

namespace scantling::mission {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kDistanceTolFraction = 0.02;  // issue 14 item 5
constexpr double kPitchTolRad = 1.0 * kDeg;    // issue 14 item 5
constexpr double kBaselineHalfM = 0.1;         // the perception's default geometry

// A 2 × 2 m plate through (0, 0, distance_m) on the optical axis, pitched about the camera
// x axis: its normal is +z turned by pitch_rad about +x (the sign of LaserPointerMeasurement).
sim::World plate(double distance_m, double pitch_rad) {
    const Eigen::Vector3d c(0.0, 0.0, distance_m);
    const Eigen::Vector3d across = Eigen::Vector3d::UnitX();
    const Eigen::Vector3d down(0.0, std::cos(pitch_rad), std::sin(pitch_rad));
    sim::World world;
    const int tag = sim::testing::add_surface(world, "hull");
    sim::testing::add_quad(world, c - across - down, c + across - down, c + across + down,
                           c - across + down, tag);
    return world;
}

sim::PinholeCameraConfig camera_with_lasers() {
    sim::PinholeCameraConfig config = sim::rov_camera(1280);
    config.lasers = {sim::LaserPointer{.origin_camera = {0.0, -kBaselineHalfM, 0.0}},
                     sim::LaserPointer{.origin_camera = {0.0, kBaselineHalfM, 0.0}}};
    return config;
}

TEST(LaserPointersOnTheSimulator, RecoverDistanceAndPitchOfAHullPlate) {
    const sim::PinholeCamera camera(camera_with_lasers());
    const perception::LaserPointerConfig config;  // lasers a, b at y = ∓0.1 m along +z
    for (const double distance_m : {0.5, 1.0, 1.5}) {
        for (const double pitch_deg : {-20.0, 0.0, 15.0}) {
            SCOPED_TRACE(testing::Message() << distance_m << " m, " << pitch_deg << " deg");
            const sim::testing::TestScene scene(plate(distance_m, pitch_deg * kDeg));
            Rng rng(11);
            const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
            const sim::RgbImage image = camera.render(scene.view(), pose, rng);
            const std::vector<sim::LaserSpot> truth = camera.laser_spots(scene.view(), pose);
            ASSERT_EQ(truth.size(), 2u);
            const perception::LaserPointerMeasurement m =
                perception::measure_laser_pointers(image, camera.config().intrinsics, config);
            ASSERT_TRUE(m.ok()) << m.message;
            EXPECT_NEAR(m.distance_m, distance_m, kDistanceTolFraction * distance_m);
            EXPECT_NEAR(m.pitch_rad, pitch_deg * kDeg, kPitchTolRad);
            for (int i = 0; i < 2; ++i) {
                EXPECT_NEAR((m.spots_px[i] - truth[i].pixel).norm(), 0.0, 0.2) << "laser " << i;
                EXPECT_NEAR((m.p_camera[i] - truth[i].p_camera).norm(), 0.0,
                            kDistanceTolFraction * distance_m)
                    << "laser " << i;
            }
            std::cout << "[ INFO     ] " << distance_m << " m, " << pitch_deg
                      << " deg: distance error " << 100.0 * (m.distance_m - distance_m) / distance_m
                      << " %, pitch error " << (m.pitch_rad / kDeg - pitch_deg) << " deg, "
                      << m.mm_per_px << " mm/px\n";
        }
    }
}

TEST(LaserPointersOnTheSimulator, SpotHiddenOrOffTheHullIsNotDrawn) {
    const sim::PinholeCamera camera(camera_with_lasers());
    // A plate covering only the upper half: laser b (below the camera) misses it.
    sim::World world;
    const int tag = sim::testing::add_surface(world, "hull");
    sim::testing::add_quad(world, {-1.0, -1.0, 1.0}, {1.0, -1.0, 1.0}, {1.0, -0.02, 1.0},
                           {-1.0, -0.02, 1.0}, tag);
    const sim::testing::TestScene scene(std::move(world));
    Rng rng(5);
    const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    const std::vector<sim::LaserSpot> spots = camera.laser_spots(scene.view(), pose);
    ASSERT_EQ(spots.size(), 1u);
    EXPECT_EQ(spots[0].laser, 0);
    const perception::LaserPointerMeasurement m = perception::measure_laser_pointers(
        camera.render(scene.view(), pose, rng), camera.config().intrinsics);
    EXPECT_EQ(m.status, perception::LaserPointerStatus::kOneSpot) << m.message;
    // A small box on the camera's line of sight to laser a's spot, clear of the beam: the spot
    // is lit but hidden.
    sim::World blocked = scene.world;
    sim::testing::add_box(blocked, {-0.02, -0.07, 0.45}, {0.02, -0.03, 0.55}, tag);
    const sim::testing::TestScene blocked_scene(std::move(blocked));
    EXPECT_TRUE(camera.laser_spots(blocked_scene.view(), pose).empty());
}

TEST(LaserPointersOnTheSimulator, CameraWithoutLasersRendersTheSameImage) {
    const sim::testing::TestScene scene(plate(1.0, 10.0 * kDeg));
    const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    const sim::PinholeCamera plain(sim::rov_camera(1280));
    sim::PinholeCameraConfig away_config = camera_with_lasers();
    for (sim::LaserPointer& laser : away_config.lasers)
        laser.direction_camera = -laser.direction_camera;
    const sim::PinholeCamera away(away_config);  // lasers pointing backwards: no spot
    const sim::PinholeCamera lasers(camera_with_lasers());
    Rng rng_plain(9);
    Rng rng_away(9);
    Rng rng_lasers(9);
    const sim::RgbImage plain_image = plain.render(scene.view(), pose, rng_plain);
    EXPECT_EQ(away.render(scene.view(), pose, rng_away).pixels, plain_image.pixels);
    // With spots, only the pixels within the spots' discs change, and the noise stream is the
    // same (the next draws agree).
    const sim::RgbImage spot_image = lasers.render(scene.view(), pose, rng_lasers);
    EXPECT_EQ(rng_lasers.next_u64(), rng_plain.next_u64());
    const std::vector<sim::LaserSpot> spots = lasers.laser_spots(scene.view(), pose);
    ASSERT_EQ(spots.size(), 2u);
    int changed = 0;
    for (int v = 0; v < plain_image.height; ++v) {
        for (int u = 0; u < plain_image.width; ++u) {
            const std::size_t i = static_cast<std::size_t>(v) * plain_image.width + u;
            if (spot_image.pixels[i] == plain_image.pixels[i]) continue;
            ++changed;
            bool in_spot = false;
            for (const sim::LaserSpot& s : spots) {
                in_spot |= (Eigen::Vector2d(u, v) - s.pixel).norm() <= s.radius_px + 1.0;
            }
            EXPECT_TRUE(in_spot) << "pixel " << u << ", " << v << " changed";
        }
    }
    EXPECT_GT(changed, 10);
}

}  // namespace
}  // namespace scantling::mission
