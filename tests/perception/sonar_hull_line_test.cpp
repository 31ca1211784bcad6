// The sonar hull line (SPEC §5, issue 14 item 2) on pings of a flat wall at known range and
// angle. tests/arch forbids a perception test to include the simulator, so the pings come from
// render_wall() below, which follows sim::MultibeamSonar's documented model for one infinite
// vertical plane: the same beam and elevation-ray layout, bins, echo power (Lambert cos², 1/r
// spreading, two-way absorption) and Rayleigh speckle on the amplitude.
#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/io/sonar_ping.hpp>
#include <scantling/perception/sonar_hull_line.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace scantling::perception {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// Issue 14 item 2's targets for the hull line.
constexpr double kAngleTolRad = 2.0 * kDeg;
constexpr double kRangeTolM = 0.05;

struct SonarModel {
    int num_beams = 256;
    int num_bins = 512;
    int rays_per_beam = 16;
    double horizontal_fov_rad = 130.0 * kDeg;  // Oculus M750d, as the simulator's default
    double vertical_fov_rad = 20.0 * kDeg;
    double min_range_m = 0.1;
    double max_range_m = 5.0;  // a 5 m range setting: ~1 cm bins for a 1-3 m stand-off
    double albedo = 0.5;
    double noise_floor = 1e-4;
    double absorption_db_per_m = 0.2;
};

double sample_angle(double fov_rad, int k, int n) {
    return -0.5 * fov_rad + fov_rad * (k + 0.5) / n;
}

io::SonarPing empty_ping(const SonarModel& m) {
    io::SonarPing ping;
    ping.num_beams = m.num_beams;
    ping.num_bins = m.num_bins;
    ping.min_range_m = m.min_range_m;
    ping.max_range_m = m.max_range_m;
    ping.horizontal_fov_rad = m.horizontal_fov_rad;
    for (int b = 0; b < m.num_beams; ++b) {
        ping.bearings_rad.push_back(sample_angle(m.horizontal_fov_rad, b, m.num_beams));
    }
    const double bin_m = (m.max_range_m - m.min_range_m) / m.num_bins;
    for (int j = 0; j < m.num_bins; ++j) ping.ranges_m.push_back(m.min_range_m + (j + 0.5) * bin_m);
    ping.intensity.assign(static_cast<std::size_t>(m.num_beams) * m.num_bins, 0.0F);
    return ping;
}

// Signal power per cell of the vertical plane n · p = distance_m, n = (cos a, sin a, 0).
std::vector<double> wall_power(const SonarModel& m, double distance_m, double angle_rad) {
    std::vector<double> power(static_cast<std::size_t>(m.num_beams) * m.num_bins, 0.0);
    const double bin_m = (m.max_range_m - m.min_range_m) / m.num_bins;
    for (int b = 0; b < m.num_beams; ++b) {
        const double bearing = sample_angle(m.horizontal_fov_rad, b, m.num_beams);
        for (int k = 0; k < m.rays_per_beam; ++k) {
            const double elevation = sample_angle(m.vertical_fov_rad, k, m.rays_per_beam);
            const double cos_incidence = std::cos(elevation) * std::cos(bearing - angle_rad);
            if (cos_incidence <= 0.0) continue;
            const double r = distance_m / cos_incidence;
            if (r < m.min_range_m || r >= m.max_range_m) continue;
            const int bin = std::min(m.num_bins - 1, static_cast<int>((r - m.min_range_m) / bin_m));
            power[static_cast<std::size_t>(b) * m.num_bins + bin] +=
                m.albedo * cos_incidence * cos_incidence / r *
                std::pow(10.0, -m.absorption_db_per_m * 2.0 * r / 10.0) / m.rays_per_beam;
        }
    }
    return power;
}

// Amplitude √(P · speckle), speckle ~ Exp(1) (Rayleigh amplitude), as the simulator's sonar.
void add_speckle(io::SonarPing& ping, const std::vector<double>& power, double noise_floor,
                 std::uint64_t seed) {
    Rng rng(seed);
    for (std::size_t i = 0; i < power.size(); ++i) {
        const double speckle = -std::log(1.0 - rng.uniform());
        ping.intensity[i] = static_cast<float>(std::sqrt((power[i] + noise_floor) * speckle));
    }
}

io::SonarPing render_wall(double distance_m, double angle_rad, std::uint64_t seed,
                          const SonarModel& m = {}) {
    io::SonarPing ping = empty_ping(m);
    add_speckle(ping, wall_power(m, distance_m, angle_rad), m.noise_floor, seed);
    return ping;
}

struct WallCase {
    double distance_m;
    double angle_deg;
};

class SonarHullLineWall : public ::testing::TestWithParam<WallCase> {};

TEST_P(SonarHullLineWall, RecoversRangeWithinFiveCmAndAngleWithinTwoDegrees) {
    const WallCase c = GetParam();
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        const SonarHullLine line =
            detect_hull_line(render_wall(c.distance_m, c.angle_deg * kDeg, seed));
        ASSERT_TRUE(line.ok()) << line.message;
        EXPECT_NEAR(line.distance_m, c.distance_m, kRangeTolM) << "seed " << seed;
        EXPECT_NEAR(line.angle_rad, c.angle_deg * kDeg, kAngleTolRad) << "seed " << seed;
    }
}

INSTANTIATE_TEST_SUITE_P(StandOffsAndAngles, SonarHullLineWall,
                         ::testing::Values(WallCase{1.0, -20.0}, WallCase{1.0, 0.0},
                                           WallCase{1.0, 15.0}, WallCase{1.3, -20.0},
                                           WallCase{1.3, 0.0}, WallCase{1.3, 15.0},
                                           WallCase{3.0, -20.0}, WallCase{3.0, 0.0},
                                           WallCase{3.0, 15.0}));

// The simulator's default 30 m range setting: 5.8 cm bins, so a wall echo fills about one bin
// and the edge's sub-bin refinement carries the range accuracy.
TEST(SonarHullLine, ThirtyMetreRangeSettingStillWithinTargets) {
    SonarModel m;
    m.num_beams = 512;
    m.max_range_m = 30.0;
    for (const WallCase c : {WallCase{1.0, -20.0}, WallCase{1.3, 15.0}, WallCase{3.0, 0.0}}) {
        const SonarHullLine line =
            detect_hull_line(render_wall(c.distance_m, c.angle_deg * kDeg, 3, m));
        ASSERT_TRUE(line.ok()) << line.message;
        EXPECT_NEAR(line.distance_m, c.distance_m, kRangeTolM) << c.distance_m << " m";
        EXPECT_NEAR(line.angle_rad, c.angle_deg * kDeg, kAngleTolRad) << c.angle_deg << " deg";
    }
}

// A ring of radius radius_m around the sonar on beams [first, last): every beam's echo at the
// same range, as a cylinder centred on the sonar would give (no straight hull line).
io::SonarPing render_ring(double radius_m, int first_beam, int last_beam, std::uint64_t seed,
                          const SonarModel& m = {}) {
    io::SonarPing ping = empty_ping(m);
    std::vector<double> power(ping.intensity.size(), 0.0);
    const double bin_m = (m.max_range_m - m.min_range_m) / m.num_bins;
    const int bin = static_cast<int>((radius_m - m.min_range_m) / bin_m);
    for (int b = first_beam; b < last_beam; ++b) {
        for (int j = bin; j < bin + 4; ++j)
            power[static_cast<std::size_t>(b) * m.num_bins + j] = 0.05;
    }
    add_speckle(ping, power, m.noise_floor, seed);
    return ping;
}

// The wall of render_wall() seen by beams [first, last) only (the others see nothing).
io::SonarPing render_wall_on_beams(int first_beam, int last_beam, const SonarModel& m = {}) {
    io::SonarPing ping = empty_ping(m);
    std::vector<double> power = wall_power(m, 1.3, 0.0);
    for (int b = 0; b < m.num_beams; ++b) {
        if (b >= first_beam && b < last_beam) continue;
        std::fill_n(power.begin() + static_cast<std::ptrdiff_t>(b) * m.num_bins, m.num_bins, 0.0);
    }
    add_speckle(ping, power, m.noise_floor, 7);
    return ping;
}

template <typename E, typename F>
void expect_throw_naming(F&& f, const std::string& field) {
    try {
        f();
        ADD_FAILURE() << "no exception; expected one naming " << field;
    } catch (const E& e) {
        EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
}

TEST(SonarHullLine, NoiseOnlyAndSilentPingsAreNoReturn) {
    io::SonarPing noise = empty_ping({});
    add_speckle(noise, std::vector<double>(noise.intensity.size(), 0.0), 1e-4, 3);
    const SonarHullLine line = detect_hull_line(noise);
    EXPECT_EQ(line.status, SonarHullLineStatus::kNoReturn) << line.message;
    EXPECT_TRUE(line.features.empty());
    EXPECT_FALSE(line.message.empty());
    EXPECT_EQ(detect_hull_line(empty_ping({})).status, SonarHullLineStatus::kNoReturn);
}

TEST(SonarHullLine, ReturnsOnFewBeamsAreTooFewFeatures) {
    const SonarHullLine line = detect_hull_line(render_wall_on_beams(126, 131));
    EXPECT_EQ(line.status, SonarHullLineStatus::kTooFewFeatures) << line.message;
    EXPECT_FALSE(line.ok());
    EXPECT_LE(line.features.size(), 5U);  // at most one per lit beam
}

TEST(SonarHullLine, ArcWithoutStraightStretchIsFitFailed) {
    SonarHullLineConfig config;
    config.min_inliers = 100;  // a 3 cm band covers only ~23° (~45 beams) of a 1.5 m ring
    const SonarHullLine line = detect_hull_line(render_ring(1.5, 0, 256, 5), config);
    EXPECT_EQ(line.status, SonarHullLineStatus::kFitFailed) << line.message;
    EXPECT_GE(line.features.size(), 200U);
}

TEST(SonarHullLine, SpeckleBeamIsFlaggedByTheWindowFilterAndIgnored) {
    constexpr int kBeam = 100;
    constexpr double kSpeckleRangeM = 0.6;  // 0.7 m short of the wall: far above the threshold
    io::SonarPing ping = render_wall(1.3, 0.0, 11);
    const int bin = static_cast<int>((kSpeckleRangeM - ping.min_range_m) /
                                     (ping.ranges_m[1] - ping.ranges_m[0]));
    for (int j = bin; j < bin + 3; ++j) {
        ping.intensity[static_cast<std::size_t>(kBeam) * ping.num_bins + j] = 1.0F;
    }
    const SonarHullLine line = detect_hull_line(ping);
    ASSERT_TRUE(line.ok()) << line.message;
    const auto it = std::find_if(line.features.begin(), line.features.end(),
                                 [](const SonarFeature& f) { return f.beam == kBeam; });
    ASSERT_NE(it, line.features.end());
    EXPECT_NEAR(it->range_m, kSpeckleRangeM, 0.03);
    EXPECT_TRUE(it->outlier);
    EXPECT_FALSE(it->inlier);
    EXPECT_GT(it->window_mean_distance_m, SonarHullLineConfig{}.outlier_distance_m);
    EXPECT_NEAR(line.distance_m, 1.3, kRangeTolM);
    EXPECT_NEAR(line.angle_rad, 0.0, kAngleTolRad);
    // Wall features away from the speckle beam pass the filter.
    for (const SonarFeature& f : line.features) {
        if (std::abs(f.beam - kBeam) > 3 && std::abs(f.beam - 128) < 60) {
            EXPECT_FALSE(f.outlier) << "beam " << f.beam;
        }
    }
}

TEST(SonarHullLine, FeaturesLieOnTheWallInTheSonarFrame) {
    const SonarHullLine line = detect_hull_line(render_wall(1.0, 15.0 * kDeg, 2));
    ASSERT_TRUE(line.ok()) << line.message;
    const Eigen::Vector2d n(std::cos(15.0 * kDeg), std::sin(15.0 * kDeg));
    for (const SonarFeature& f : line.features) {
        if (!f.inlier) continue;
        EXPECT_NEAR(n.dot(f.p_sonar), 1.0, kRangeTolM) << "beam " << f.beam;
    }
    EXPECT_NEAR(line.normal_sonar.norm(), 1.0, 1e-12);
    EXPECT_LT(line.rms_m, 0.02);
}

TEST(SonarHullLine, SameInputGivesIdenticalResults) {
    const io::SonarPing ping = render_wall(1.3, -20.0 * kDeg, 9);
    const SonarHullLine a = detect_hull_line(ping);
    const SonarHullLine b = detect_hull_line(ping);
    ASSERT_TRUE(a.ok());
    EXPECT_EQ(a.distance_m, b.distance_m);
    EXPECT_EQ(a.angle_rad, b.angle_rad);
    EXPECT_EQ(a.num_inliers, b.num_inliers);
    EXPECT_EQ(a.rms_m, b.rms_m);
    ASSERT_EQ(a.features.size(), b.features.size());
    for (std::size_t i = 0; i < a.features.size(); ++i) {
        EXPECT_EQ(a.features[i].beam, b.features[i].beam);
        EXPECT_EQ(a.features[i].inlier, b.features[i].inlier);
        EXPECT_EQ(a.features[i].outlier, b.features[i].outlier);
    }
}

TEST(SonarHullLine, MalformedPingThrowsInputErrorNamingTheField) {
    const io::SonarPing good = render_wall(1.3, 0.0, 1);
    io::SonarPing short_intensity = good;
    short_intensity.intensity.pop_back();
    expect_throw_naming<InputError>([&] { detect_hull_line(short_intensity); },
                                    "sonar_ping.intensity");
    io::SonarPing nan_bearing = good;
    nan_bearing.bearings_rad[3] = std::numeric_limits<double>::quiet_NaN();
    expect_throw_naming<InputError>([&] { detect_hull_line(nan_bearing); },
                                    "sonar_ping.bearings_rad");
}

TEST(SonarHullLine, BadConfigThrowsConfigErrorNamingTheField) {
    const io::SonarPing ping = render_wall(1.3, 0.0, 1);
    const auto expect_bad = [&](auto edit, const std::string& field) {
        SonarHullLineConfig config;
        edit(config);
        expect_throw_naming<ConfigError>([&] { detect_hull_line(ping, config); },
                                         "sonar_hull_line." + field);
    };
    expect_bad([](auto& c) { c.outlier_window_beams = 3; }, "outlier_window_beams");
    expect_bad([](auto& c) { c.outlier_window_beams = 0; }, "outlier_window_beams");
    expect_bad([](auto& c) { c.canny_high_threshold = 10.0; }, "canny_high_threshold");
    expect_bad([](auto& c) { c.canny_low_threshold = -1.0; }, "canny_low_threshold");
    expect_bad([](auto& c) { c.intensity_full_scale = 0.0; }, "intensity_full_scale");
    expect_bad([](auto& c) { c.blur_kernel_px = 4; }, "blur_kernel_px");
    expect_bad([](auto& c) { c.outlier_distance_m = std::nan(""); }, "outlier_distance_m");
    expect_bad([](auto& c) { c.ransac_inlier_distance_m = 0.0; }, "ransac_inlier_distance_m");
    expect_bad([](auto& c) { c.ransac_iterations = 0; }, "ransac_iterations");
    expect_bad([](auto& c) { c.min_inliers = 1; }, "min_inliers");
}

}  // namespace
}  // namespace scantling::perception
