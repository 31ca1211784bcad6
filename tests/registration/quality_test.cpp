#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/quality.hpp>

namespace scantling::registration {
namespace {

/// A 1 m grid of n × n points on z = 0.
PointCloud grid(int n) {
    PointCloud cloud;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) cloud.points.emplace_back(i, j, 0.0);
    }
    return cloud;
}

TEST(QualityTest, OverlapCountsPointsWithinOneVoxel) {
    const PointCloud target = grid(20);
    const KdTree tree(target.points);
    PointCloud source = grid(20);
    for (std::size_t i = 0; i < source.size(); i += 4) source.points[i].z() = 0.5;  // 25 % off
    EXPECT_DOUBLE_EQ(overlap_ratio(source, tree, 0.05), 0.75);
    EXPECT_DOUBLE_EQ(overlap_ratio(source, tree, 0.6), 1.0);
}

TEST(QualityTest, RmseOfAConstantOffsetIsTheOffset) {
    const PointCloud target = grid(10);
    const KdTree tree(target.points);
    const PointCloud source = transformed(
        target, make_isometry(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.01)));
    EXPECT_NEAR(rmse(source, tree, 0.1), 0.01, 1e-12);
    const CorrespondenceQuality q = evaluate_correspondences(source, tree, 0.005);
    EXPECT_EQ(q.num_inliers, 0u);
    EXPECT_EQ(q.rmse_m, 0.0);
}

TEST(QualityTest, OneAndTwoThreadsGiveBitIdenticalFigures) {
    const PointCloud target = grid(60);
    const KdTree tree(target.points);
    const PointCloud source = transformed(
        target,
        make_isometry(so3_exp(Eigen::Vector3d(0, 0, 0.01)), Eigen::Vector3d(0.1, 0.2, 0.3)));
    const CorrespondenceQuality one =
        evaluate_correspondences(source, tree, 1.0, {.num_threads = 1});
    const CorrespondenceQuality two =
        evaluate_correspondences(source, tree, 1.0, {.num_threads = 2});
    EXPECT_EQ(one.rmse_m, two.rmse_m);
    EXPECT_EQ(one.num_inliers, two.num_inliers);
}

TEST(QualityTest, BadInputThrows) {
    const PointCloud target = grid(3);
    const KdTree tree(target.points);
    EXPECT_THROW(overlap_ratio(target, tree, 0.0), ConfigError);
    PointCloud bad = target;
    bad.points[1].y() = std::nan("");
    EXPECT_THROW(rmse(bad, tree, 1.0), InputError);
}

TEST(GateTest, AttitudeGateComparesRollAndPitchButNotYaw) {
    const Eigen::Matrix3d imu = rotation_from_euler_zyx(0.02, -0.01, 0.3);
    EXPECT_TRUE(check_attitude(rotation_from_euler_zyx(0.03, 0.0, 2.0), imu).passed);
    const GateResult r = check_attitude(rotation_from_euler_zyx(0.02, 0.15, 0.3), imu);
    EXPECT_FALSE(r.passed);
    EXPECT_NE(r.reason.find("pitch"), std::string::npos) << r.reason;
    // Roll wraps: −π + 0.01 and π − 0.01 are 0.02 rad apart.
    const double pi = std::numbers::pi;
    EXPECT_TRUE(check_attitude(rotation_from_euler_zyx(pi - 0.01, 0.0, 0.0),
                               rotation_from_euler_zyx(-pi + 0.01, 0.0, 0.0))
                    .passed);
}

TEST(GateTest, SpeedGateRejectsJumpsFasterThanThreeTenthsOfAMetrePerSecond) {
    const Eigen::Isometry3d a = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d b = a;
    b.translation() = Eigen::Vector3d(0.3, 0.4, 0.0);    // 0.5 m
    EXPECT_TRUE(check_speed(a, 10.0, b, 12.0).passed);   // 0.25 m/s
    const GateResult r = check_speed(a, 10.0, b, 11.0);  // 0.5 m/s
    EXPECT_FALSE(r.passed);
    EXPECT_NE(r.reason.find("0.500 m/s"), std::string::npos) << r.reason;
    EXPECT_THROW(check_speed(a, 10.0, b, 10.0), InputError);
    EXPECT_THROW(check_speed(a, 10.0, b, std::nan("")), InputError);
}

TEST(GateTest, OverlapGateNeedsSeventyFivePercent) {
    EXPECT_TRUE(check_overlap(0.75).passed);
    EXPECT_FALSE(check_overlap(0.74).passed);
    EXPECT_THROW(check_overlap(1.2), InputError);
    const PointCloud target = grid(20);
    const KdTree tree(target.points);
    PointCloud scan = grid(20);
    for (std::size_t i = 0; i < scan.size(); i += 2) scan.points[i].z() = 1.0;  // 50 % off
    const GateResult r = check_overlap(scan, tree);
    EXPECT_FALSE(r.passed);
    EXPECT_NE(r.reason.find("0.500"), std::string::npos) << r.reason;
}

TEST(GateTest, BadGateConfigsThrowConfigError) {
    EXPECT_THROW(AttitudeGateConfig{.max_difference_rad = 0.0}.validate(), ConfigError);
    EXPECT_THROW(SpeedGateConfig{.max_speed_mps = -1.0}.validate(), ConfigError);
    EXPECT_THROW((OverlapGateConfig{.min_overlap = 0.0}.validate()), ConfigError);
    EXPECT_THROW((OverlapGateConfig{.min_overlap = 0.75, .voxel_size_m = 0.0}.validate()),
                 ConfigError);
}

}  // namespace
}  // namespace scantling::registration
