#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/io/cloud_io.hpp>

#include "test_files.hpp"

namespace scantling::io {
namespace {

using test::TempDir;

TEST(CloudIo, PicksTheFormatFromTheExtensionIgnoringCase) {
    EXPECT_EQ(cloud_format_from_path("a/b.pcd"), CloudFormat::kPcd);
    EXPECT_EQ(cloud_format_from_path("B.PCD"), CloudFormat::kPcd);
    EXPECT_EQ(cloud_format_from_path("x.Ply"), CloudFormat::kPly);
    EXPECT_EQ(cloud_format_from_path("/data/000000.BIN"), CloudFormat::kKittiBin);
}

TEST(CloudIo, UnknownExtensionIsAFileErrorListingTheSupportedOnes) {
    for (const std::string path : {"cloud.xyz", "cloud", "dir.pcd/cloud.las"}) {
        try {
            cloud_format_from_path(path);
            ADD_FAILURE() << "no error for " << path;
        } catch (const FileError& e) {
            EXPECT_EQ(e.path(), path);
            const std::string what = e.what();
            for (const char* ext : {".pcd", ".ply", ".bin"})
                EXPECT_NE(what.find(ext), std::string::npos) << what;
        }
    }
}

TEST(CloudIo, RoundTripsThroughEveryFormat) {
    TempDir dir;
    const PointCloud cloud = test::make_full_cloud(100);
    for (const std::string name : {"a.pcd", "b.PLY", "c.ply"}) {
        write_cloud(dir.file(name), cloud);
        test::expect_same_cloud(cloud, read_cloud(dir.file(name)));
    }
    write_cloud(dir.file("d.bin"), cloud);
    const PointCloud kitti = read_cloud(dir.file("d.bin"));
    EXPECT_EQ(kitti.points, cloud.points);
    EXPECT_EQ(kitti.intensities, cloud.intensities);
    EXPECT_FALSE(kitti.has_normals());
}

TEST(CloudIo, WritesAsciiPcdWhenAsked) {
    TempDir dir;
    const PointCloud cloud = test::make_full_cloud(10);
    write_cloud(dir.file("a.pcd"), cloud, CloudWriteOptions{.binary = false});
    EXPECT_NE(test::read_bytes(dir.file("a.pcd")).find("DATA ascii\n"), std::string::npos);
    test::expect_same_cloud(cloud, read_cloud(dir.file("a.pcd")));
}

TEST(CloudIo, ReplacesAnExistingFileAndLeavesNoTemporary) {
    TempDir dir;
    write_cloud(dir.file("a.pcd"), test::make_full_cloud(10));
    write_cloud(dir.file("a.pcd"), test::make_full_cloud(3));
    EXPECT_EQ(read_cloud(dir.file("a.pcd")).size(), 3u);
    EXPECT_EQ(dir.list(), std::vector<std::string>{"a.pcd"});
}

}  // namespace
}  // namespace scantling::io
