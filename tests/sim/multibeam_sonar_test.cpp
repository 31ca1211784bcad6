#include <scantling/core/error.hpp>
#include <scantling/sim/multibeam_sonar.hpp>

#include "sensor_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace scantling::sim {
namespace {

using testing::add_box;
using testing::add_quad;
using testing::add_surface;
using testing::TestScene;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kFloatRel = 1e-5;  // intensities are floats: ~6e-8 relative, squared and summed
// A cell is lit above this signal power: below one ray's echo in these scenes (≥ 1e-4) and far
// above the float rounding of the noise floor (≈ 1e-11).
constexpr double kLitPower = 1e-5;

MultibeamSonarConfig clean() {
    MultibeamSonarConfig c;
    c.speckle = false;
    return c;
}

// A wall facing the sonar at x = x_m, 40 m wide and 10 m high.
World wall_at(double x_m) {
    World world;
    const int tag = add_surface(world, "wall");
    add_quad(world, {x_m, -20, -5}, {x_m, 20, -5}, {x_m, 20, 5}, {x_m, -20, 5}, tag);
    return world;
}

// Signal power of a cell with speckle off: (I / gain)² − noise floor.
double cell_power(const SonarImage& image, const MultibeamSonarConfig& c, int beam, int bin) {
    return std::pow(image.at(beam, bin) / c.gain, 2) - c.noise_floor;
}

bool lit(const SonarImage& image, const MultibeamSonarConfig& c, int beam, int bin) {
    return cell_power(image, c, beam, bin) > kLitPower;
}

int argmax_bin(const SonarImage& image, int beam) {
    const auto first = image.intensity.begin() + static_cast<std::ptrdiff_t>(beam) * image.num_bins;
    return static_cast<int>(std::max_element(first, first + image.num_bins) - first);
}

TEST(MultibeamSonar, WallAppearsAtItsRangeInEveryBeam) {
    const TestScene scene(wall_at(5.0));
    const MultibeamSonar sonar(clean());
    Rng rng(1);
    const SonarImage image = sonar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng, 2.5);
    EXPECT_EQ(image.stamp_s, 2.5);
    ASSERT_EQ(image.intensity.size(), 512u * 512u);
    const double nearest_elevation = 0.5 * sonar.config().vertical_fov_rad / 16;
    int checked = 0;
    for (int b = 0; b < image.num_beams; ++b) {
        const double bearing = image.bearings_rad[b];
        if (std::abs(bearing) > 60.0 * kDeg) continue;
        const double r0 = 5.0 / std::cos(bearing);
        const int leading = image.bin_of(r0 / std::cos(nearest_elevation));
        int first_lit = 0;
        while (first_lit < image.num_bins && !lit(image, sonar.config(), b, first_lit)) ++first_lit;
        ASSERT_EQ(first_lit, leading) << "beam " << b;
        // Elevation ambiguity spreads the echo over r0 / cos ε: the peak lies within a bin.
        EXPECT_LE(std::abs(argmax_bin(image, b) - image.bin_of(r0)), 1) << "beam " << b;
        ++checked;
    }
    EXPECT_GT(checked, 400);
}

TEST(MultibeamSonar, PostAppearsAtItsBearingOnTheLeft) {
    World world;
    const Eigen::Vector3d centre(4.0 * std::cos(30 * kDeg), 4.0 * std::sin(30 * kDeg), 0.0);
    add_box(world, centre - Eigen::Vector3d(0.05, 0.05, 3.0),
            centre + Eigen::Vector3d(0.05, 0.05, 3.0), add_surface(world, "post"));
    const TestScene scene(std::move(world));
    const MultibeamSonar sonar(clean());
    Rng rng(2);
    const SonarImage image = sonar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng);
    double min_bearing = 1e9, max_bearing = -1e9;
    for (const double dx : {-0.05, 0.05}) {
        for (const double dy : {-0.05, 0.05}) {
            const double bearing = std::atan2(centre.y() + dy, centre.x() + dx);
            min_bearing = std::min(min_bearing, bearing);
            max_bearing = std::max(max_bearing, bearing);
        }
    }
    int first = -1, last = -1;
    for (int b = 0; b < image.num_beams; ++b) {
        bool any = false;
        for (int j = 0; j < image.num_bins; ++j) any = any || lit(image, sonar.config(), b, j);
        if (any && first < 0) first = b;
        if (any) last = b;
    }
    ASSERT_GE(first, 0);
    EXPECT_LE(std::abs(first - image.beam_of(min_bearing)), 1);
    EXPECT_LE(std::abs(last - image.beam_of(max_bearing)), 1);
    EXPECT_GT(first, image.num_beams / 2);  // positive bearing = left = upper beam indices
    const int peak = argmax_bin(image, (first + last) / 2);
    EXPECT_LE(std::abs(peak - image.bin_of(4.0 - 0.05)), 1);
}

TEST(MultibeamSonar, EchoPowerFollowsIncidenceSpreadingAndAbsorption) {
    const TestScene scene(wall_at(5.0));
    MultibeamSonarConfig config = clean();
    config.noise_floor = 0.0;
    const MultibeamSonar sonar(config);
    Rng rng(3);
    const SonarImage image = sonar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng);
    const int beam = 256;
    const double bearing = image.bearings_rad[beam];
    double expected = 0.0;  // albedo 0.5 · cos²θ · (1/r) · 10^(−0.2 dB/m · 2r / 10), per ray
    for (int k = 0; k < 16; ++k) {
        const double elevation = -10.0 * kDeg + 20.0 * kDeg * (k + 0.5) / 16;
        const double cos_incidence = std::cos(bearing) * std::cos(elevation);
        const double r = 5.0 / cos_incidence;
        expected += 0.5 * cos_incidence * cos_incidence / r * std::pow(10.0, -0.04 * r) / 16;
    }
    double measured = 0.0;
    for (int j = 0; j < image.num_bins; ++j) measured += cell_power(image, config, beam, j);
    EXPECT_NEAR(measured, expected, kFloatRel * expected);
}

TEST(MultibeamSonar, ElevationsCollapseIntoOneCellAndOutsideTheApertureIsUnseen) {
    const auto plate = [](World& world, double elevation_rad) {
        const double z = 3.0 * std::tan(elevation_rad);
        add_quad(world, {3, -0.3, z - 0.1}, {3, 0.3, z - 0.1}, {3, 0.3, z + 0.1},
                 {3, -0.3, z + 0.1}, add_surface(world, "plate"));
    };
    World up, down, both, outside;
    plate(up, 5 * kDeg);
    plate(down, -5 * kDeg);
    plate(both, 5 * kDeg);
    plate(both, -5 * kDeg);
    plate(outside, 15 * kDeg);
    const MultibeamSonar sonar(clean());
    const auto scan = [&](World world) {
        const TestScene scene(std::move(world));
        Rng rng(4);
        return sonar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng);
    };
    const SonarImage a = scan(up), b = scan(down), ab = scan(both), o = scan(outside);
    const int beam = 256;
    const int bin = argmax_bin(ab, beam);
    const double pa = cell_power(a, sonar.config(), beam, bin);
    const double pb = cell_power(b, sonar.config(), beam, bin);
    EXPECT_GT(pa, 0.0);
    EXPECT_NEAR(pa, pb, kFloatRel * pa);  // mirror images: same range, same cell
    EXPECT_NEAR(cell_power(ab, sonar.config(), beam, bin), pa + pb, kFloatRel * (pa + pb));
    const float floor_amplitude = static_cast<float>(std::sqrt(sonar.config().noise_floor));
    for (const float v : o.intensity) ASSERT_EQ(v, floor_amplitude);
}

TEST(MultibeamSonar, RaysLeavingTheWaterShowOnlyTheNoiseFloor) {
    World room = testing::box_room({-10, -10, -10}, {10, 10, 2.5});
    const TestScene scene(std::move(room));
    MultibeamSonarConfig config = clean();
    Eigen::Isometry3d pitched_up = Eigen::Isometry3d::Identity();
    pitched_up.linear() =
        Eigen::AngleAxisd(-45 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
    pitched_up.translation() = Eigen::Vector3d(0, 0, -1.0);
    const float floor_amplitude = static_cast<float>(std::sqrt(config.noise_floor));
    Rng rng(5);
    const SonarImage dry = MultibeamSonar(config).scan(scene.view(), pitched_up, rng);
    EXPECT_GT(*std::max_element(dry.intensity.begin(), dry.intensity.end()), 2 * floor_amplitude);
    config.water_surface_z_m = -0.5;  // every ray climbs: all leave the water within 3 m
    const SonarImage wet = MultibeamSonar(config).scan(scene.view(), pitched_up, rng);
    for (const float v : wet.intensity) ASSERT_EQ(v, floor_amplitude);
}

TEST(MultibeamSonar, SpeckleIsRayleighWithTheCellPower) {
    const TestScene scene(wall_at(100.0));  // beyond range: noise floor everywhere
    MultibeamSonarConfig config;
    config.gain = 3.0;
    const MultibeamSonar sonar(config);
    Rng rng(6);
    const SonarImage image = sonar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng);
    double sum = 0.0, sum_sq = 0.0;
    for (const float v : image.intensity) {
        sum += v;
        sum_sq += double(v) * v;
    }
    const double n = static_cast<double>(image.intensity.size());
    // E[I²] = gain² · floor (exponential power, relative std 1: 4σ = 4/√n ≈ 0.8 %);
    // Rayleigh: E[I] / √E[I²] = √π / 2.
    EXPECT_NEAR(sum_sq / n, 9.0 * config.noise_floor,
                4.0 / std::sqrt(n) * 9.0 * config.noise_floor);
    EXPECT_NEAR(sum / n / std::sqrt(sum_sq / n), std::sqrt(std::numbers::pi) / 2.0, 0.005);
}

TEST(MultibeamSonar, OneAndTwoThreadsGiveIdenticalImages) {
    const TestScene scene(testing::box_room({-3, -4, -2}, {6, 4, 2}));
    const MultibeamSonar sonar;
    Rng a(7), b(7), c(8);
    const SonarImage one = sonar.scan(scene.view(), Eigen::Isometry3d::Identity(), a, 0.0, {1});
    const SonarImage two = sonar.scan(scene.view(), Eigen::Isometry3d::Identity(), b, 0.0, {2});
    EXPECT_EQ(one.intensity, two.intensity);
    EXPECT_NE(one.intensity, sonar.scan(scene.view(), Eigen::Isometry3d::Identity(), c).intensity);
}

// The ping as the robot receives it (io::SonarPing) carries the image's data unchanged and
// passes the reader's own checks.
TEST(MultibeamSonar, ToSonarPingCopiesEveryFieldAndValidates) {
    const TestScene scene(wall_at(5.0));
    const MultibeamSonar sonar(clean());
    Rng rng(1);
    const SonarImage image = sonar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng, 2.5);
    const io::SonarPing ping = to_sonar_ping(image);
    EXPECT_EQ(ping.stamp_s, image.stamp_s);
    EXPECT_EQ(ping.num_beams, image.num_beams);
    EXPECT_EQ(ping.num_bins, image.num_bins);
    EXPECT_EQ(ping.intensity, image.intensity);
    EXPECT_EQ(ping.bearings_rad, image.bearings_rad);
    EXPECT_EQ(ping.ranges_m, image.ranges_m);
    EXPECT_EQ(ping.min_range_m, image.min_range_m);
    EXPECT_EQ(ping.max_range_m, image.max_range_m);
    EXPECT_EQ(ping.horizontal_fov_rad, image.horizontal_fov_rad);
    EXPECT_NO_THROW(ping.validate());
}

}  // namespace
}  // namespace scantling::sim
