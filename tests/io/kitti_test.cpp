#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/io/kitti.hpp>

#include <random>

#include "test_files.hpp"

namespace scantling::io {
namespace {

using test::TempDir;

std::vector<Eigen::Isometry3d> random_poses(int n) {
    std::mt19937 rng(11);
    std::normal_distribution<double> normal;
    std::vector<Eigen::Isometry3d> poses;
    for (int i = 0; i < n; ++i) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng))
                         .normalized()
                         .toRotationMatrix();
        T.translation() = 1000.0 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
        poses.push_back(T);
    }
    return poses;
}

TEST(KittiBin, RoundTripsPointsAndIntensitiesBitExact) {
    TempDir dir;
    PointCloud cloud = test::make_full_cloud(200);
    write_kitti_bin(dir.file("a.bin"), cloud);
    EXPECT_EQ(std::filesystem::file_size(dir.file("a.bin")), 200u * 16u);
    const PointCloud back = read_kitti_bin(dir.file("a.bin"));
    EXPECT_EQ(back.points, cloud.points);
    EXPECT_EQ(back.intensities, cloud.intensities);
    EXPECT_FALSE(back.has_normals() || back.has_rings() || back.has_colors() || back.has_times());
}

TEST(KittiBin, WritesZeroIntensityWhenTheCloudHasNone) {
    TempDir dir;
    PointCloud cloud;
    cloud.points = {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(-4, 5.5, 6)};
    write_kitti_bin(dir.file("a.bin"), cloud);
    const PointCloud back = read_kitti_bin(dir.file("a.bin"));
    EXPECT_EQ(back.points, cloud.points);
    EXPECT_EQ(back.intensities, (std::vector<float>{0.0f, 0.0f}));
}

TEST(KittiBin, ReadsLittleEndianRecords) {
    TempDir dir;
    std::string bytes;
    for (float v : {1.5f, -2.0f, 3.25f, 0.75f}) test::put(bytes, v);
    test::write_bytes(dir.file("a.bin"), bytes);
    const PointCloud cloud = read_kitti_bin(dir.file("a.bin"));
    ASSERT_EQ(cloud.size(), 1u);
    EXPECT_EQ(cloud.points[0], Eigen::Vector3d(1.5, -2.0, 3.25));
    EXPECT_EQ(cloud.intensities[0], 0.75f);
}

TEST(KittiPoses, RoundTripEveryDoubleBitExact) {
    TempDir dir;
    const auto poses = random_poses(50);
    write_kitti_poses(dir.file("p.txt"), poses);
    const auto back = read_kitti_poses(dir.file("p.txt"));
    ASSERT_EQ(back.size(), poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i)
        EXPECT_EQ(back[i].matrix(), poses[i].matrix()) << i;
}

TEST(KittiPoses, ReadsTheOfficialLayoutRowMajorWithBlankLines) {
    TempDir dir;
    test::write_bytes(dir.file("p.txt"),
                      "1 0 0 1.5 0 1 0 -2 0 0 1 3e2\n\n"
                      "0 -1 0 0 1 0 0 0 0 0 1 0\r\n");
    const auto poses = read_kitti_poses(dir.file("p.txt"));
    ASSERT_EQ(poses.size(), 2u);
    EXPECT_EQ(poses[0].translation(), Eigen::Vector3d(1.5, -2, 300));
    EXPECT_EQ(poses[1].linear()(0, 1), -1.0);
    EXPECT_EQ(poses[1].linear()(1, 0), 1.0);
}

TEST(KittiPoses, RejectsReflectionsAndWritesNonFiniteAsInputError) {
    TempDir dir;
    test::write_bytes(dir.file("p.txt"), "-1 0 0 0 0 1 0 0 0 0 1 0\n");
    EXPECT_THROW(read_kitti_poses(dir.file("p.txt")), ParseError);
    Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
    bad.translation().x() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(write_kitti_poses(dir.file("q.txt"), std::vector<Eigen::Isometry3d>{bad}),
                 InputError);
    EXPECT_FALSE(std::filesystem::exists(dir.file("q.txt")));
}

}  // namespace
}  // namespace scantling::io
