#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <scantling/core/error.hpp>
#include <scantling/io/kitti.hpp>
#include <scantling/io/pcd.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/io/sweep_source.hpp>
#include <scantling/io/tum.hpp>

#include "test_files.hpp"

namespace scantling::io {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

PointCloud cloud_of(int n, double x) {
    PointCloud c;
    for (int i = 0; i < n; ++i) c.points.emplace_back(x, 0.1 * i, 1.0);
    return c;
}

TEST(SweepSource, FolderOfCloudsInNameOrderWithRegularStamps) {
    TempDir dir;
    // Written out of order: the source sorts by name.
    write_pcd(dir.file("b.pcd"), cloud_of(3, 2.0), PcdEncoding::kBinary);
    write_pcd(dir.file("a.pcd"), cloud_of(5, 1.0), PcdEncoding::kBinary);
    std::ofstream(dir.file("notes.txt")) << "ignored";
    SweepSourceOptions options;
    options.period_s = 0.05;
    const auto source = open_sweep_source(dir.path().string(), options);
    EXPECT_EQ(source->kind(), SweepSourceKind::kCloudFolder);
    ASSERT_EQ(source->size(), 2U);
    EXPECT_EQ(source->read(0).size(), 5U);
    EXPECT_DOUBLE_EQ(source->read(1).stamp_s, 0.05);
    EXPECT_FALSE(source->ground_truth().has_value());
    EXPECT_NE(source->file_of(1).find("b.pcd"), std::string::npos);
    EXPECT_THROW(source->read(2), InputError);
}

TEST(SweepSource, KittiSequenceWithTimes) {
    TempDir dir;
    fs::create_directories(dir.path() / "velodyne");
    for (int i = 0; i < 3; ++i) {
        write_kitti_bin((dir.path() / "velodyne" / ("00000" + std::to_string(i) + ".bin")).string(),
                        cloud_of(4 + i, i));
    }
    std::ofstream(dir.file("times.txt")) << "0.0\n0.103\n0.207\n";
    const auto source = open_sweep_source(dir.path().string());
    EXPECT_EQ(source->kind(), SweepSourceKind::kKittiSequence);
    ASSERT_EQ(source->size(), 3U);
    EXPECT_DOUBLE_EQ(source->stamp_s(2), 0.207);
    EXPECT_EQ(source->read(2).size(), 6U);
    // A times.txt that does not match the sweeps names the file.
    std::ofstream(dir.file("times.txt")) << "0.0\n0.1\n";
    try {
        open_sweep_source(dir.path().string());
        FAIL();
    } catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find("times.txt"), std::string::npos) << e.what();
    }
}

TEST(SweepSource, RecordingGivesGroundTruth) {
    TempDir dir;
    fs::create_directories(dir.path() / "lidar");
    write_tum(dir.file("groundtruth.tum"),
              std::vector<StampedPose>{{0.0, Eigen::Isometry3d::Identity()},
                                       {0.1, Eigen::Isometry3d::Identity()}});
    std::vector<Eigen::Isometry3d> poses(2, Eigen::Isometry3d::Identity());
    poses[1].translation() = Eigen::Vector3d(0.5, 0.0, 0.0);
    write_kitti_poses((dir.path() / "lidar" / "poses_gt.txt").string(), poses);
    std::ofstream((dir.path() / "lidar" / "times.txt").string()) << "0.0\n0.1\n";
    write_kitti_bin((dir.path() / "lidar" / "000000.bin").string(), cloud_of(3, 0.0));
    write_kitti_bin((dir.path() / "lidar" / "000001.bin").string(), cloud_of(3, 0.0));
    const auto source = open_sweep_source(dir.path().string());
    EXPECT_EQ(source->kind(), SweepSourceKind::kRecording);
    ASSERT_EQ(source->size(), 2U);
    const auto gt = source->ground_truth();
    ASSERT_TRUE(gt.has_value());
    EXPECT_DOUBLE_EQ((*gt)[1].translation().x(), 0.5);
    EXPECT_DOUBLE_EQ(source->read(1).stamp_s, 0.1);
}

TEST(SweepSource, BadPathsNameThePathAndWhatWasExpected) {
    TempDir dir;
    EXPECT_THROW(open_sweep_source(dir.file("missing")), FileError);
    std::ofstream(dir.file("file.pcd")) << "x";
    EXPECT_THROW(open_sweep_source(dir.file("file.pcd")), FileError);
    fs::create_directories(dir.path() / "empty");
    try {
        open_sweep_source((dir.path() / "empty").string());
        FAIL();
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("no .pcd, .ply or .bin"), std::string::npos);
    }
    fs::create_directories(dir.path() / "mixed");
    write_pcd((dir.path() / "mixed" / "a.pcd").string(), cloud_of(2, 0), PcdEncoding::kBinary);
    write_kitti_bin((dir.path() / "mixed" / "b.bin").string(), cloud_of(2, 0));
    EXPECT_THROW(open_sweep_source((dir.path() / "mixed").string()), FileError);
    SweepSourceOptions bad;
    bad.period_s = 0.0;
    EXPECT_THROW(open_sweep_source(dir.path().string(), bad), ConfigError);
}

}  // namespace
}  // namespace scantling::io
