#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/io/tum.hpp>

#include <random>

#include "test_files.hpp"

namespace scantling::io {
namespace {

using test::TempDir;

// Rotations go through a quaternion and back: a few ulps of 1.
constexpr double kRotationRoundTripTolerance = 1e-15;

std::vector<StampedPose> random_trajectory(int n) {
    std::mt19937 rng(5);
    std::normal_distribution<double> normal;
    std::vector<StampedPose> poses;
    double stamp_s = 1.6e9 + 0.123456789;
    for (int i = 0; i < n; ++i) {
        StampedPose pose;
        stamp_s += 0.1 + 0.01 * std::abs(normal(rng));
        pose.stamp_s = stamp_s;
        pose.T_world_body.linear() =
            Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng))
                .normalized()
                .toRotationMatrix();
        pose.T_world_body.translation() =
            100.0 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
        poses.push_back(pose);
    }
    return poses;
}

TEST(Tum, RoundTripsStampsAndTranslationsExactlyAndRotationsToRoundOff) {
    TempDir dir;
    const auto poses = random_trajectory(100);
    write_tum(dir.file("t.txt"), poses);
    const auto back = read_tum(dir.file("t.txt"));
    ASSERT_EQ(back.size(), poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i) {
        EXPECT_EQ(back[i].stamp_s, poses[i].stamp_s);
        EXPECT_EQ(back[i].T_world_body.translation(), poses[i].T_world_body.translation());
        EXPECT_LT(
            (back[i].T_world_body.linear() - poses[i].T_world_body.linear()).cwiseAbs().maxCoeff(),
            kRotationRoundTripTolerance);
    }
}

TEST(Tum, ReadsCommentsBlankLinesAndQuaternionInXyzwOrder) {
    TempDir dir;
    test::write_bytes(dir.file("t.txt"),
                      "# timestamp tx ty tz qx qy qz qw\n\n"
                      "1.0 1 2 3 0 0 0.70710678 0.70710678  # 90 deg about z\n"
                      "2.5 0 0 0 0 0 0 1\n");
    const auto poses = read_tum(dir.file("t.txt"));
    ASSERT_EQ(poses.size(), 2u);
    EXPECT_EQ(poses[0].stamp_s, 1.0);
    EXPECT_EQ(poses[0].T_world_body.translation(), Eigen::Vector3d(1, 2, 3));
    const Eigen::Vector3d x_rotated = poses[0].T_world_body.linear() * Eigen::Vector3d::UnitX();
    EXPECT_NEAR((x_rotated - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-12);
}

TEST(Tum, NormalisesQuaternionsSlightlyOffUnitNorm) {
    TempDir dir;
    test::write_bytes(dir.file("t.txt"), "0 0 0 0 0 0 0 1.0005\n");
    const auto poses = read_tum(dir.file("t.txt"));
    const Eigen::Matrix3d R = poses.at(0).T_world_body.linear();
    EXPECT_NEAR((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-14);
}

TEST(Tum, WriterRejectsStampsThatDoNotIncrease) {
    TempDir dir;
    std::vector<StampedPose> poses(2);
    poses[0].stamp_s = 1.0;
    poses[1].stamp_s = 1.0;
    EXPECT_THROW(write_tum(dir.file("t.txt"), poses), InputError);
    EXPECT_TRUE(dir.list().empty());
}

}  // namespace
}  // namespace scantling::io
