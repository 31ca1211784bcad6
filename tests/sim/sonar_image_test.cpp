#include <scantling/core/error.hpp>
#include <scantling/sim/multibeam_sonar.hpp>

#include "sensor_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace scantling::sim {
namespace {

using testing::add_quad;
using testing::add_surface;
using testing::TestScene;

constexpr double kDeg = std::numbers::pi / 180.0;

SonarImage wall_image() {
    World world;
    const int tag = add_surface(world, "wall");
    add_quad(world, {5, -20, -5}, {5, 20, -5}, {5, 20, 5}, {5, -20, 5}, tag);
    const TestScene scene(std::move(world));
    MultibeamSonarConfig config;
    config.speckle = false;
    Rng rng(1);
    return MultibeamSonar(config).scan(scene.view(), Eigen::Isometry3d::Identity(), rng);
}

TEST(SonarImage, BinAndBeamLookupsInvertTheAxes) {
    const SonarImage image = wall_image();
    for (const int j : {0, 17, 511}) EXPECT_EQ(image.bin_of(image.ranges_m[j]), j);
    for (const int b : {0, 100, 511}) EXPECT_EQ(image.beam_of(image.bearings_rad[b]), b);
    EXPECT_EQ(image.bin_of(0.05), -1);
    EXPECT_EQ(image.bin_of(30.0), -1);
    EXPECT_EQ(image.beam_of(66 * kDeg), -1);
    EXPECT_EQ(image.beam_of(-66 * kDeg), -1);
    EXPECT_NEAR(image.bearings_rad.front(), -65 * kDeg + 65 * kDeg / 512, 1e-12);
}

TEST(SonarImage, CartesianFanPutsTheWallAheadAndBlanksOutsideTheFan) {
    const SonarImage image = wall_image();
    const CartesianSonarImage fan = to_cartesian(image, 0.1);
    EXPECT_EQ(fan.width, static_cast<int>(std::ceil(2 * 30 * std::sin(65 * kDeg) / 0.1)));
    EXPECT_EQ(fan.height, 300);
    EXPECT_EQ(fan.intensity[0], 0.0F);  // far left corner: beyond 30 m
    // The pixel straight ahead at x ≈ 5.05 m reads the beam at bearing 0 and that range.
    const int v = static_cast<int>((fan.x_max_m - 5.05) / 0.1);
    const int u = static_cast<int>(fan.y_max_m / 0.1);
    const double x = fan.x_max_m - (v + 0.5) * 0.1, y = fan.y_max_m - (u + 0.5) * 0.1;
    const float expected =
        image.at(image.beam_of(std::atan2(y, x)), image.bin_of(std::hypot(x, y)));
    EXPECT_EQ(fan.intensity[static_cast<std::size_t>(v) * fan.width + u], expected);
    EXPECT_GT(expected, 10.0F * image.at(256, 0));  // the wall, well above the noise floor
    // Behind the fan's edge (bearing 80°, 10 m): outside.
    const int u_side = static_cast<int>((fan.y_max_m - 10 * std::sin(80 * kDeg)) / 0.1);
    const int v_side = static_cast<int>((fan.x_max_m - 10 * std::cos(80 * kDeg)) / 0.1);
    EXPECT_EQ(fan.intensity[static_cast<std::size_t>(v_side) * fan.width + u_side], 0.0F);
}

TEST(SonarImage, BadInputsAndConfigsThrowNamingTheField) {
    const SonarImage image = wall_image();
    EXPECT_THROW(to_cartesian(image, 0.0), InputError);
    EXPECT_THROW(to_cartesian(image, 1e-5), InputError);  // 6e6 × 3e6 pixels
    SonarImage broken = image;
    broken.intensity.pop_back();
    EXPECT_THROW(to_cartesian(broken, 0.1), InputError);

    MultibeamSonarConfig c;
    c.num_beams = 0;
    try {
        MultibeamSonar sonar(c);
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("multibeam_sonar.num_beams = 0"), std::string::npos);
    }
    c = MultibeamSonarConfig{};
    c.vertical_fov_rad = 2.0;
    EXPECT_THROW(MultibeamSonar{c}, ConfigError);
    c = MultibeamSonarConfig{};
    c.max_range_m = 0.05;
    EXPECT_THROW(MultibeamSonar{c}, ConfigError);
    c = MultibeamSonarConfig{};
    c.water_surface_z_m = std::nan("");
    EXPECT_THROW(MultibeamSonar{c}, ConfigError);
    c = MultibeamSonarConfig{};
    c.rays_per_beam = 0;
    EXPECT_THROW(MultibeamSonar{c}, ConfigError);
}

}  // namespace
}  // namespace scantling::sim
