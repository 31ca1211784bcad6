// Height keeping: the vertical attenuation and push of height_keeping.hpp, the clearances from
// the LiDAR's footprint cylinder, and the input and config contracts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/safety/height_keeping.hpp>

namespace scantling::safety {
namespace {

constexpr double kExact = 1e-12;      // m/s: closed-form values, only rounding differs
const HeightKeepingConfig kConfig{};  // floor/ceiling min 0.6, att 1.2, K 1, v_z max 0.5

TEST(HeightKeeping, NoClearanceLeavesTheSpeedUnchanged) {
    const auto result = keep_height(-0.4, {}, kConfig);
    EXPECT_EQ(result.v_z_cmd_mps, -0.4);
    EXPECT_EQ(result.lambda, 1.0);
    EXPECT_EQ(result.status, AttenuationStatus::kNoData);
}

TEST(HeightKeeping, DescentAttenuatesMonotonicallyAndStopsAtTheMinimum) {
    double previous = -1.0;
    for (double h = 0.3; h <= 2.0; h += 0.01) {
        const auto result = keep_height(-0.5, {h, std::nullopt}, kConfig);
        const double lambda = std::clamp((h - 0.6) / 0.6, 0.0, 1.0);
        const double push = std::max(0.0, 0.6 - h);
        EXPECT_NEAR(result.lambda, lambda, kExact) << "h = " << h;
        EXPECT_NEAR(result.v_z_cmd_mps, -0.5 * lambda + push, kExact) << "h = " << h;
        EXPECT_GE(result.lambda, previous);
        if (h <= 0.6) {
            EXPECT_GE(result.v_z_cmd_mps, 0.0) << "never down below the minimum";
        }
        previous = result.lambda;
    }
    EXPECT_EQ(keep_height(-0.5, {0.9, std::nullopt}, kConfig).status,
              AttenuationStatus::kAttenuated);
    EXPECT_EQ(keep_height(-0.5, {0.5, std::nullopt}, kConfig).status, AttenuationStatus::kStopped);
}

TEST(HeightKeeping, ClimbIgnoresTheFloorAndDescentIgnoresTheCeiling) {
    EXPECT_EQ(keep_height(0.5, {0.7, std::nullopt}, kConfig).v_z_cmd_mps, 0.5);
    EXPECT_EQ(keep_height(-0.5, {std::nullopt, 0.7}, kConfig).v_z_cmd_mps, -0.5);
    EXPECT_NEAR(keep_height(0.5, {std::nullopt, 0.9}, kConfig).v_z_cmd_mps, 0.25, kExact);
}

TEST(HeightKeeping, PushesAwayFromTheNearerSurfaceAndClamps) {
    EXPECT_NEAR(keep_height(0.0, {0.4, std::nullopt}, kConfig).push_mps, 0.2, kExact);
    EXPECT_NEAR(keep_height(0.0, {std::nullopt, 0.3}, kConfig).push_mps, -0.3, kExact);
    EXPECT_NEAR(keep_height(0.0, {0.4, 0.3}, kConfig).push_mps, -0.1, kExact);  // one per side
    HeightKeepingConfig strong = kConfig;
    strong.gain_per_s = 10.0;  // 10 · 0.5 = 5 m/s before the clamp
    EXPECT_NEAR(keep_height(0.0, {0.1, std::nullopt}, strong).v_z_cmd_mps, 0.5, kExact);
}

TEST(HeightKeeping, InfiniteClearanceIsNothingInRange) {
    const double inf = std::numeric_limits<double>::infinity();
    const auto result = keep_height(-0.3, {inf, inf}, kConfig);
    EXPECT_EQ(result.v_z_cmd_mps, -0.3);
    EXPECT_EQ(result.status, AttenuationStatus::kClear);
}

TEST(HeightKeeping, BadInputsThrow) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(keep_height(nan, {1.0, 1.0}, kConfig), InputError);
    EXPECT_THROW(keep_height(0.1, {nan, std::nullopt}, kConfig), InputError);
    EXPECT_THROW(keep_height(0.1, {std::nullopt, -0.2}, kConfig), InputError);
}

TEST(HeightKeeping, ClearanceFromTheLidarFootprint) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    PointCloud cloud;
    cloud.points = {{0.1, 0.2, -1.3},
                    {-0.3, 0.0, -0.9},
                    {0.0, 0.0, 2.4},
                    {1.0, 0.0, -0.2},  // a wall beside the vehicle, outside the footprint
                    {nan, 0.0, -0.1}};
    const auto clearance = clearance_from_cloud(cloud, kConfig);
    ASSERT_TRUE(clearance.floor_m && clearance.ceiling_m);
    EXPECT_EQ(*clearance.floor_m, 0.9);
    EXPECT_EQ(*clearance.ceiling_m, 2.4);
    EXPECT_FALSE(clearance_from_cloud(PointCloud{}, kConfig).floor_m);
}

TEST(HeightKeeping, NearestTakesTheNearerSourcePerSide) {
    const auto merged = nearest({1.5, std::nullopt}, {1.2, 3.0});
    ASSERT_TRUE(merged.floor_m && merged.ceiling_m);
    EXPECT_EQ(*merged.floor_m, 1.2);
    EXPECT_EQ(*merged.ceiling_m, 3.0);
}

void expect_config_error(const std::function<void(HeightKeepingConfig&)>& spoil,
                         const std::string& field) {
    HeightKeepingConfig config;
    spoil(config);
    try {
        keep_height(0.0, {}, config);
        ADD_FAILURE() << "no ConfigError for " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("height_keeping." + field + " = "), std::string::npos)
            << e.what();
    }
}

TEST(HeightKeeping, BadConfigsThrowNamingTheField) {
    expect_config_error([](auto& c) { c.floor_min_m = 0.0; }, "floor_min_m");
    expect_config_error([](auto& c) { c.floor_att_m = 0.6; }, "floor_att_m");
    expect_config_error([](auto& c) { c.ceiling_min_m = -1.0; }, "ceiling_min_m");
    expect_config_error([](auto& c) { c.ceiling_att_m = 0.5; }, "ceiling_att_m");
    expect_config_error([](auto& c) { c.gain_per_s = std::nan(""); }, "gain_per_s");
    expect_config_error([](auto& c) { c.max_vertical_speed_mps = 0.0; }, "max_vertical_speed_mps");
    expect_config_error([](auto& c) { c.footprint_radius_m = 0.0; }, "footprint_radius_m");
}

}  // namespace
}  // namespace scantling::safety
