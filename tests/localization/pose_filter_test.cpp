#include <gtest/gtest.h>

#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/localization/pose_filter.hpp>

#include "filter_scene.hpp"

namespace scantling::localization {
namespace {

using test::FilterScene;

/// Runs the filter over the scene, each measurement delivered `delay_s` after its capture
/// (initialised from the first). Returns the states at every VIO sample.
std::vector<FusedState> run(PoseFilter& filter, const FilterScene& scene, double delay_s) {
    std::vector<FusedState> states;
    std::size_t next = 0;
    bool initialized = false;
    for (const io::VioRecord& v : scene.vio) {
        filter.add_odometry(v);
        while (next < scene.measurements.size() &&
               scene.measurements[next].stamp_s + delay_s <= v.stamp_s) {
            const AbsolutePose& m = scene.measurements[next++];
            if (!initialized) {
                EXPECT_EQ(filter.initialize(m), MeasurementStatus::kApplied);
                initialized = true;
            } else {
                EXPECT_EQ(filter.update(m), MeasurementStatus::kApplied);
            }
        }
        if (auto s = filter.state()) states.push_back(*s);
    }
    for (; next < scene.measurements.size(); ++next) {  // those still in flight at the end
        EXPECT_EQ(filter.update(scene.measurements[next]), MeasurementStatus::kApplied);
    }
    return states;
}

TEST(PoseFilter, LateMeasurementsGiveTheSameEstimateAsOnTimeOnes) {
    for (const FilterKind kind : {FilterKind::kEkf, FilterKind::kUkf}) {
        PoseFilterConfig config;
        config.kind = kind;
        const FilterScene scene = test::make_filter_scene(config, 7, 30.0, 2.0);
        PoseFilter on_time(config), late(config);
        run(on_time, scene, 0.0);
        run(late, scene, 0.8);  // each registration lands ~24 VIO samples after its frame
        const FusedState a = *on_time.state();
        const FusedState b = *late.state();
        EXPECT_LT((a.T_world_body.translation() - b.T_world_body.translation()).norm(), 1e-9);
        EXPECT_LT((a.T_world_body.linear() - b.T_world_body.linear()).norm(), 1e-9);
        EXPECT_LT((a.covariance - b.covariance).norm(), 1e-12);
    }
}

TEST(PoseFilter, ArrivalOrderDoesNotMatter) {
    PoseFilterConfig config;
    config.history_s = 100.0;
    const FilterScene scene = test::make_filter_scene(config, 8, 30.0, 2.0);
    PoseFilter in_order(config), reversed(config);
    run(in_order, scene, 0.0);
    for (const io::VioRecord& v : scene.vio) {
        reversed.add_odometry(v);
        if (!reversed.initialized() && v.stamp_s >= scene.measurements.front().stamp_s) {
            ASSERT_EQ(reversed.initialize(scene.measurements.front()), MeasurementStatus::kApplied);
        }
    }
    for (std::size_t i = scene.measurements.size() - 1; i >= 1; --i) {
        ASSERT_EQ(reversed.update(scene.measurements[i]), MeasurementStatus::kApplied);
    }
    const FusedState a = *in_order.state();
    const FusedState b = *reversed.state();
    EXPECT_LT((a.T_world_body.translation() - b.T_world_body.translation()).norm(), 1e-9);
    EXPECT_LT((a.covariance - b.covariance).norm(), 1e-12);
}

TEST(PoseFilter, EkfAndUkfAgreeOnTheSameData) {
    PoseFilterConfig ekf_config;
    PoseFilterConfig ukf_config;
    ukf_config.kind = FilterKind::kUkf;
    const FilterScene scene = test::make_filter_scene(ekf_config, 11, 60.0, 1.0);
    PoseFilter ekf(ekf_config), ukf(ukf_config);
    const auto a = run(ekf, scene, 0.1);
    const auto b = run(ukf, scene, 0.1);
    ASSERT_EQ(a.size(), b.size());
    double worst_m = 0.0, worst_sigma_ratio = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        worst_m = std::max(
            worst_m, (a[i].T_world_body.translation() - b[i].T_world_body.translation()).norm());
        for (int k = 0; k < 6; ++k) {
            const double r = std::sqrt(b[i].covariance(k, k) / a[i].covariance(k, k));
            worst_sigma_ratio = std::max(worst_sigma_ratio, std::abs(r - 1.0));
        }
    }
    EXPECT_LT(worst_m, 2e-3);
    EXPECT_LT(worst_sigma_ratio, 0.05);
}

TEST(PoseFilter, FusedCovarianceIsConsistentOverSeeds) {
    for (const FilterKind kind : {FilterKind::kEkf, FilterKind::kUkf}) {
        PoseFilterConfig config;
        config.kind = kind;
        double nees_sum = 0.0;
        int count = 0;
        for (std::uint64_t seed = 1; seed <= 25; ++seed) {
            const FilterScene scene = test::make_filter_scene(config, 100 + seed, 40.0, 1.0);
            PoseFilter filter(config);
            const auto states = run(filter, scene, 0.0);
            const std::size_t offset = scene.vio.size() - states.size();
            for (std::size_t i = 0; i < states.size(); i += 90) {  // every 3 s
                const Vector6d e =
                    position_attitude_error(scene.truth[offset + i], states[i].T_world_body);
                nees_sum += e.dot(states[i].covariance.ldlt().solve(e));
                ++count;
            }
        }
        const double mean = nees_sum / count;
        // χ²(6): mean 6; over ~325 samples (correlated in time) the mean stays well inside ±25 %.
        EXPECT_GT(mean, 4.5) << to_string(kind);
        EXPECT_LT(mean, 7.5) << to_string(kind);
    }
}

TEST(PoseFilter, RegistrationsBoundTheDriftOfTheOdometry) {
    PoseFilterConfig config;
    config.position_random_walk_m_per_sqrt_m = 0.05;  // a poor VIO
    const FilterScene scene = test::make_filter_scene(config, 5, 60.0, 1.0);
    PoseFilter filter(config);
    const auto states = run(filter, scene, 0.0);
    const std::size_t offset = scene.vio.size() - states.size();
    double fused = 0.0, vio_only = 0.0;
    const Eigen::Isometry3d E0 = scene.truth[offset] * scene.vio[offset].T_odom_body.inverse();
    for (std::size_t i = 0; i < states.size(); ++i) {
        fused +=
            (states[i].T_world_body.translation() - scene.truth[offset + i].translation()).norm();
        vio_only += ((E0 * scene.vio[offset + i].T_odom_body).translation() -
                     scene.truth[offset + i].translation())
                        .norm();
    }
    // 1 Hz poses with 2 cm noise against a VIO drifting 5 cm per √m at ~0.3 m/s (2.7 cm per
    // axis in a second): the fused error stays at that scale while the VIO's grows.
    EXPECT_LT(fused, 0.3 * vio_only) << fused / states.size() << " vs " << vio_only / states.size();
    EXPECT_LT(fused / states.size(), 0.06);
}

TEST(PoseFilter, AJumpOfTheOdometryDoesNotMoveTheBody) {
    PoseFilterConfig config;
    PoseFilter filter(config);
    io::VioRecord v;
    v.valid = true;
    for (int k = 0; k < 10; ++k) {
        v.stamp_s = 0.1 * k;
        v.T_odom_body.translation() = Eigen::Vector3d(0.01 * k, 0, 0);
        filter.add_odometry(v);
        if (k == 0) {
            ASSERT_EQ(filter.initialize(
                          {0.0, Eigen::Isometry3d::Identity(), Matrix6d::Identity() * 1e-4}),
                      MeasurementStatus::kApplied);
        }
    }
    const Eigen::Vector3d before = filter.state()->T_world_body.translation();
    v.stamp_s = 1.0;
    v.T_odom_body.translation() = Eigen::Vector3d(5.0, 2.0, 0.0);  // 50 m/s: a reset
    EXPECT_EQ(filter.add_odometry(v), OdometryStatus::kJump);
    EXPECT_LT((filter.state()->T_world_body.translation() - before).norm(), 1e-9);
    EXPECT_GT(filter.state()->covariance(0, 0), 0.3 * 0.3 * 0.9);
}

TEST(PoseFilter, RefusesBadInputWithoutChangingTheEstimate) {
    PoseFilter filter;
    io::VioRecord v;
    v.valid = true;
    v.stamp_s = 1.0;
    filter.add_odometry(v);
    EXPECT_EQ(filter.update({1.0, Eigen::Isometry3d::Identity(), Matrix6d::Identity()}),
              MeasurementStatus::kNotInitialized);
    ASSERT_EQ(filter.initialize({1.0, Eigen::Isometry3d::Identity(), Matrix6d::Identity() * 1e-4}),
              MeasurementStatus::kApplied);
    v.stamp_s = 0.5;
    EXPECT_EQ(filter.add_odometry(v), OdometryStatus::kOutOfOrder);
    AbsolutePose nan{1.0, Eigen::Isometry3d::Identity(), Matrix6d::Identity()};
    nan.T_world_body.translation().x() = NAN;
    EXPECT_EQ(filter.update(nan), MeasurementStatus::kInvalid);
    EXPECT_EQ(filter.update({1.0, Eigen::Isometry3d::Identity(), -Matrix6d::Identity()}),
              MeasurementStatus::kInvalid);
    EXPECT_EQ(filter.update({0.2, Eigen::Isometry3d::Identity(), Matrix6d::Identity()}),
              MeasurementStatus::kTooOld);
    EXPECT_EQ(filter.update({2.0, Eigen::Isometry3d::Identity(), Matrix6d::Identity()}),
              MeasurementStatus::kPending);
    EXPECT_TRUE(filter.state()->T_world_body.matrix().allFinite());
    v.stamp_s = 3.0;
    v.T_odom_body.translation().x() = NAN;
    EXPECT_THROW(filter.add_odometry(v), InputError);
    PoseFilterConfig bad;
    bad.history_s = 0.0;
    EXPECT_THROW(PoseFilter{bad}, ConfigError);
}

}  // namespace
}  // namespace scantling::localization
