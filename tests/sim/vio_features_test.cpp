// VIO feature quality from the scene: texture, open space, range, lighting; and its effect on
// the VIO's drift and tracking.
#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/sim/vio.hpp>
#include <scantling/sim/vio_features.hpp>

#include "sensor_test_support.hpp"

namespace scantling::sim {
namespace {

using testing::plate_at_z;

/// body ← optical frame of a camera looking straight down (image x = −body y, image y =
/// −body x), for a level body.
Eigen::Isometry3d down_looking() {
    Eigen::Matrix3d R;
    R.col(0) = -Eigen::Vector3d::UnitY();
    R.col(1) = -Eigen::Vector3d::UnitX();
    R.col(2) = -Eigen::Vector3d::UnitZ();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R;
    return T;
}

/// body ← optical frame looking along body x (z forward = body x, y down = −body z).
Eigen::Isometry3d forward_looking() {
    Eigen::Matrix3d R;
    R.col(0) = -Eigen::Vector3d::UnitY();
    R.col(1) = -Eigen::Vector3d::UnitZ();
    R.col(2) = Eigen::Vector3d::UnitX();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R;
    return T;
}

Eigen::Isometry3d body_at(const Eigen::Vector3d& p_world) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = p_world;
    return T;
}

double quality_over(const World& world, const Eigen::Isometry3d& T_world_body,
                    const VioFeatureConfig& config) {
    const RayCaster caster(world.mesh, world.surface_tags);
    return vio_feature_quality(SceneView{caster, world.metadata}, T_world_body, config);
}

TEST(VioFeatures, TexturedPlateInFullViewGivesFullQualityAndUntexturedGivesNone) {
    VioFeatureConfig config;
    config.T_body_sensor = down_looking();
    const Eigen::Isometry3d T_world_body = body_at({0.0, 0.0, 1.0});
    EXPECT_DOUBLE_EQ(quality_over(plate_at_z(0.0, 10.0, true), T_world_body, config), 1.0);
    EXPECT_DOUBLE_EQ(quality_over(plate_at_z(0.0, 10.0, false), T_world_body, config), 0.0);
}

TEST(VioFeatures, LightingScalesTheQuality) {
    VioFeatureConfig config;
    config.T_body_sensor = down_looking();
    config.ambient_light = 0.25;
    EXPECT_DOUBLE_EQ(quality_over(plate_at_z(0.0, 10.0, true), body_at({0.0, 0.0, 1.0}), config),
                     0.25);
}

TEST(VioFeatures, OpenSpaceAboveTheHorizonCountsAsFeatureless) {
    // Looking level over a floor 1 m below: the lower 3 of 6 ray rows hit it within 10 m
    // (the row nearest the horizon at 8.9° down, 6.4 m away), the upper 3 see open space.
    VioFeatureConfig config;
    config.T_body_sensor = forward_looking();
    EXPECT_DOUBLE_EQ(quality_over(plate_at_z(0.0, 10.0, true), body_at({0.0, 0.0, 1.0}), config),
                     0.5);
}

TEST(VioFeatures, SurfacesOutsideTheRangeGiveNoFeatures) {
    VioFeatureConfig config;
    config.T_body_sensor = down_looking();
    const World plate = plate_at_z(0.0, 100.0, true);
    EXPECT_DOUBLE_EQ(quality_over(plate, body_at({0.0, 0.0, 0.1}), config), 0.0);   // too near
    EXPECT_DOUBLE_EQ(quality_over(plate, body_at({0.0, 0.0, 12.0}), config), 0.0);  // too far
}

TEST(VioFeatures, InvalidConfigsAreRejected) {
    VioFeatureConfig config;
    config.rows = 0;
    EXPECT_THROW(config.validate(), ConfigError);
    config = VioFeatureConfig{};
    config.ambient_light = 1.5;
    EXPECT_THROW(config.validate(), ConfigError);
    config = VioFeatureConfig{};
    config.max_range_m = config.min_range_m;
    EXPECT_THROW(config.validate(), ConfigError);
    config = VioFeatureConfig{};
    config.T_body_sensor.linear() *= 2.0;
    EXPECT_THROW(config.validate(), ConfigError);
}

struct VioRun {
    double final_error_m = 0.0;
    double final_variance_x_m2 = 0.0;
    int valid = 0;
    int samples = 0;
};

/// 4 m along x at 1 m/s, 0.5 m above the plate, VIO at 30 Hz fed by the scene's quality.
VioRun fly_over(const World& world) {
    const RayCaster caster(world.mesh, world.surface_tags);
    VioFeatureConfig features;
    features.T_body_sensor = down_looking();
    VioConfig vio_config;
    vio_config.dropout_rate_per_s = 0.0;  // only the features may stop tracking here
    VioSimulator vio(vio_config);
    Rng rng(7);  // the same draws for both plates: only the feature quality differs
    VioRun run;
    for (int k = 0; k <= 120; ++k) {
        MotionState truth;
        truth.stamp_s = k / 30.0;
        truth.T_world_body = body_at({-2.0 + truth.stamp_s, 0.0, 0.5});
        truth.v_world_mps = Eigen::Vector3d::UnitX();
        const double quality =
            vio_feature_quality(SceneView{caster, world.metadata}, truth.T_world_body, features);
        const VioSample sample = vio.step(truth, quality, rng);
        EXPECT_DOUBLE_EQ(sample.feature_quality, quality);
        const Eigen::Isometry3d estimate = vio.T_world_odom() * sample.T_odom_body;
        run.final_error_m = (estimate.translation() - truth.T_world_body.translation()).norm();
        run.final_variance_x_m2 = sample.covariance(0, 0);
        run.valid += sample.valid ? 1 : 0;
        ++run.samples;
    }
    return run;
}

TEST(VioFeatures, UntexturedPlateLosesTrackingAndDriftsMoreThanTexturedPlate) {
    const VioRun textured = fly_over(plate_at_z(0.0, 10.0, true));
    const VioRun untextured = fly_over(plate_at_z(0.0, 10.0, false));
    EXPECT_EQ(textured.valid, textured.samples);
    EXPECT_EQ(untextured.valid, 0);
    // Quality 0 scales the drift σ by 1 + poor_features_drift_gain = 5: variance × 25 (less the
    // jitter share, which does not scale).
    constexpr double kMinVarianceRatio = 10.0;
    EXPECT_GT(untextured.final_variance_x_m2, kMinVarianceRatio * textured.final_variance_x_m2);
    EXPECT_GT(untextured.final_error_m, 2.0 * textured.final_error_m);
}

}  // namespace
}  // namespace scantling::sim
