#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/sim/vio.hpp>

#include "motion_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace scantling::sim {
namespace {

using testing::ClimbingCircle;
using testing::straight_line;

constexpr double kExact = 1e-9;
// Ensemble RMS over n error samples has relative error ≈ 1 / √(2n); 4σ bound.
double rms_tolerance(double rms, int n) { return 4.0 * rms / std::sqrt(2.0 * n); }

VioConfig only(double position_walk, double yaw_walk) {
    VioConfig c = noiseless(VioConfig{});
    c.position_random_walk_m_per_sqrt_m = position_walk;
    c.yaw_random_walk_rad_per_sqrt_m = yaw_walk;
    return c;
}

// Position error of a sample in the odom frame.
Eigen::Vector3d position_error(const VioSimulator& vio, const VioSample& s, const MotionState& m) {
    return s.T_odom_body.translation() -
           (vio.T_world_odom().inverse() * m.T_world_body).translation();
}

TEST(Vio, ZeroConfigReportsTheTruePoseInAGravityAlignedOdomFrame) {
    const ClimbingCircle circle;
    VioSimulator vio(noiseless(VioConfig{}));
    Rng rng(1);
    const VioSample first = vio.step(circle.at(0.0), 1.0, rng);
    EXPECT_NEAR(first.T_odom_body.translation().norm(), 0.0, kExact);
    // Odom z is vertical (the z row of the attitude is the world's) and the start yaw is 0.
    const Eigen::Matrix3d& R = first.T_odom_body.linear();
    EXPECT_NEAR((R.row(2) - circle.R_tilt.row(2)).norm(), 0.0, kExact);
    EXPECT_NEAR(std::atan2(R(1, 0), R(0, 0)), 0.0, kExact);
    for (int k = 1; k <= 90; ++k) {
        const MotionState m = circle.at(k / 30.0);
        const VioSample s = vio.step(m, 0.0, rng);
        ASSERT_TRUE(s.valid);
        const Eigen::Isometry3d expected = vio.T_world_odom().inverse() * m.T_world_body;
        EXPECT_NEAR((s.T_odom_body.matrix() - expected.matrix()).norm(), 0.0, kExact);
        EXPECT_NEAR((s.v_body_mps - m.T_world_body.linear().transpose() * m.v_world_mps).norm(),
                    0.0, kExact);
        EXPECT_EQ(s.covariance, Matrix6d::Zero());
    }
    EXPECT_GT(vio.distance_travelled_m(), 3.0);  // 3 s at ≈ 1 m/s
}

TEST(Vio, PositionDriftGrowsWithTheSquareRootOfDistance) {
    const double walk = 0.02;
    const int runs = 200;
    double sq_25 = 0.0, sq_100 = 0.0, predicted_var_100 = 0.0;
    for (int run = 0; run < runs; ++run) {
        VioSimulator vio(only(walk, 0.0));
        Rng rng(100 + run);
        for (int k = 0; k <= 100; ++k) {  // 1 m per step, heading 0.3 rad
            const MotionState m = straight_line(k, 1.0, 0.3, {1.0, 2.0, -1.0});
            const VioSample s = vio.step(m, 1.0, rng);
            if (k == 25) sq_25 += position_error(vio, s, m).squaredNorm();
            if (k == 100) sq_100 += position_error(vio, s, m).squaredNorm();
            if (k == 100) predicted_var_100 = s.covariance(0, 0);
        }
    }
    const int n = 3 * runs;
    const double rms_25 = std::sqrt(sq_25 / n), rms_100 = std::sqrt(sq_100 / n);
    EXPECT_NEAR(rms_25, walk * 5.0, rms_tolerance(walk * 5.0, n));
    EXPECT_NEAR(rms_100, walk * 10.0, rms_tolerance(walk * 10.0, n));
    EXPECT_NEAR(predicted_var_100, walk * walk * 100.0, kExact);
}

TEST(Vio, YawDriftBendsThePathAndTheCovarianceTracksIt) {
    const double walk = 0.01;
    const int runs = 300;
    double yaw_sq = 0.0, lateral_sq = 0.0;
    Matrix6d predicted = Matrix6d::Zero();
    for (int run = 0; run < runs; ++run) {
        VioSimulator vio(only(0.0, walk));
        Rng rng(500 + run);
        for (int k = 0; k <= 50; ++k) {
            const MotionState m = straight_line(k, 1.0);
            const VioSample s = vio.step(m, 1.0, rng);
            if (k < 50) continue;
            yaw_sq += std::pow(so3_log(s.T_odom_body.linear()).z(), 2);
            lateral_sq += std::pow(position_error(vio, s, m).y(), 2);
            predicted = s.covariance;
        }
    }
    // Lateral error = ∫ yaw error ds: variance σ² d³ / 3 in the continuum (the 1 m steps
    // give Σ (d − k)², the same to 3 %), which the linear propagation reproduces.
    EXPECT_NEAR(predicted(5, 5), walk * walk * 50.0, kExact);
    EXPECT_NEAR(predicted(1, 1), walk * walk * (49.0 * 50.0 * 99.0 / 6.0), kExact);
    EXPECT_NEAR(std::sqrt(yaw_sq / runs), std::sqrt(predicted(5, 5)),
                rms_tolerance(std::sqrt(predicted(5, 5)), runs));
    EXPECT_NEAR(std::sqrt(lateral_sq / runs), std::sqrt(predicted(1, 1)),
                rms_tolerance(std::sqrt(predicted(1, 1)), runs));
}

TEST(Vio, PoorFeaturesMultiplyTheDriftAndTooFewLoseTracking) {
    const VioConfig config = only(0.02, 0.0);
    VioSimulator good(config), dark(config);
    Rng rng_a(3), rng_b(3);
    VioSample s_good, s_dark;
    for (int k = 0; k <= 10; ++k) {
        s_good = good.step(straight_line(k, 1.0), 1.0, rng_a);
        s_dark = dark.step(straight_line(k, 1.0), 0.5, rng_b);
    }
    const double gain = 1.0 + config.poor_features_drift_gain * 0.5;
    EXPECT_NEAR(s_dark.covariance(0, 0), gain * gain * s_good.covariance(0, 0), kExact);
    EXPECT_TRUE(s_dark.valid);
    VioSimulator lost(VioConfig{});
    Rng rng(4);
    EXPECT_FALSE(lost.step(straight_line(0.0, 1.0), 0.01, rng).valid);  // below 0.05
    EXPECT_TRUE(lost.step(straight_line(0.1, 1.0), 0.9, rng).valid);
}

TEST(Vio, DropoutsHappenAtTheConfiguredRate) {
    VioConfig config = noiseless(VioConfig{});
    config.dropout_rate_per_s = 0.2;
    config.dropout_duration_s = 1.0;
    VioSimulator vio(config);
    Rng rng(5);
    int starts = 0, invalid = 0;
    bool previous_valid = true;
    const int steps = 30 * 1000;  // 1000 s at 30 Hz
    for (int k = 0; k < steps; ++k) {
        const bool valid = vio.step(straight_line(k / 30.0, 0.5), 1.0, rng).valid;
        starts += previous_valid && !valid;
        invalid += !valid;
        previous_valid = valid;
    }
    // Starts only while tracking: rate λ over T / (1 + λ d) seconds ≈ 167; Poisson 4σ ≈ 52.
    const double expected_starts = 0.2 * 1000.0 / 1.2;
    EXPECT_NEAR(starts, expected_starts, 4.0 * std::sqrt(expected_starts));
    EXPECT_NEAR(static_cast<double>(invalid) / starts, 30.0, 1.0);  // 1 s = 30 samples each
}

TEST(Vio, SameSeedGivesIdenticalSamples) {
    const ClimbingCircle circle;
    VioSimulator a(VioConfig{}), b(VioConfig{});
    Rng rng_a(6), rng_b(6);
    for (int k = 0; k < 100; ++k) {
        const VioSample sa = a.step(circle.at(k / 30.0), 0.7, rng_a);
        const VioSample sb = b.step(circle.at(k / 30.0), 0.7, rng_b);
        EXPECT_EQ(sa.T_odom_body.matrix(), sb.T_odom_body.matrix());
        EXPECT_EQ(sa.covariance, sb.covariance);
        EXPECT_EQ(sa.valid, sb.valid);
    }
}

TEST(Vio, BadConfigAndInputThrow) {
    VioConfig c;
    c.position_random_walk_m_per_sqrt_m = -0.1;
    try {
        VioSimulator vio(c);
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("vio.position_random_walk_m_per_sqrt_m = -0.1"),
                  std::string::npos)
            << e.what();
    }
    c = VioConfig{};
    c.lost_feature_quality = 2.0;
    EXPECT_THROW(VioSimulator{c}, ConfigError);
    VioSimulator vio(VioConfig{});
    Rng rng(7);
    EXPECT_THROW(vio.step(straight_line(0.0, 1.0), 1.5, rng), InputError);
    vio.step(straight_line(1.0, 1.0), 1.0, rng);
    EXPECT_THROW(vio.step(straight_line(0.5, 1.0), 1.0, rng), InputError);
}

}  // namespace
}  // namespace scantling::sim
