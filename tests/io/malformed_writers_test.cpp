// Failing writers: each must throw a typed error naming the path and leave neither the target
// nor a temporary behind (an existing target stays intact).
#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/kitti.hpp>
#include <scantling/io/mesh_io.hpp>
#include <scantling/io/pcd.hpp>
#include <scantling/io/ply.hpp>
#include <scantling/io/tum.hpp>

#include <functional>

#include "test_files.hpp"

namespace scantling::io {
namespace {

using test::expect_file_error;
using test::TempDir;

using Writer = std::function<void(const std::string&)>;

std::vector<std::pair<std::string, Writer>> writers() {
    const PointCloud cloud = test::make_full_cloud(5);
    TriangleMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 1, 2}};
    return {
        {"a.pcd", [=](const std::string& p) { write_pcd(p, cloud, PcdEncoding::kAscii); }},
        {"b.pcd", [=](const std::string& p) { write_cloud(p, cloud); }},
        {"c.ply", [=](const std::string& p) { write_ply(p, cloud); }},
        {"d.bin", [=](const std::string& p) { write_kitti_bin(p, cloud); }},
        {"e.txt",
         [](const std::string& p) {
             write_kitti_poses(p, std::vector<Eigen::Isometry3d>(2, Eigen::Isometry3d::Identity()));
         }},
        {"f.txt", [](const std::string& p) { write_tum(p, std::vector<StampedPose>(1)); }},
        {"g.ply", [=](const std::string& p) { write_mesh(p, mesh); }},
        {"h.stl", [=](const std::string& p) { write_mesh(p, mesh); }},
    };
}

TEST(Malformed, UnwritableTargetsAreFileErrorsAndLeaveNothingBehind) {
    TempDir dir;
    test::write_bytes(dir.file("plain_file"), "x");
    for (const auto& writer : writers()) {
        const std::string& name = writer.first;
        const auto& write = writer.second;  // not a structured binding: lambdas capture it
        const std::string in_missing_dir = dir.file("no_such_dir/" + name);
        expect_file_error([&] { write(in_missing_dir); }, in_missing_dir);
        const std::string under_a_file = dir.file("plain_file/" + name);
        expect_file_error([&] { write(under_a_file); }, under_a_file);
        const std::string is_a_dir = dir.file("dir_" + name);
        std::filesystem::create_directory(is_a_dir);
        expect_file_error([&] { write(is_a_dir); }, is_a_dir);
        EXPECT_TRUE(std::filesystem::is_empty(is_a_dir)) << name;
        std::filesystem::remove(is_a_dir);
        EXPECT_EQ(dir.list(), std::vector<std::string>{"plain_file"}) << name;
    }
}

TEST(Malformed, InvalidInputToWritersLeavesNoFileAndNoTemporary) {
    TempDir dir;
    PointCloud inconsistent = test::make_full_cloud(5);
    inconsistent.intensities.pop_back();
    EXPECT_THROW(write_pcd(dir.file("a.pcd"), inconsistent), InputError);
    EXPECT_THROW(write_ply(dir.file("a.ply"), inconsistent), InputError);
    EXPECT_THROW(write_kitti_bin(dir.file("a.bin"), inconsistent), InputError);
    EXPECT_THROW(write_kitti_bin(dir.file("a.bin"), PointCloud{}), InputError);
    const std::vector<Eigen::Vector3i> faces = {{0, 1, 5}};
    EXPECT_THROW(write_ply(dir.file("a.ply"), test::make_full_cloud(5), faces), InputError);
    EXPECT_TRUE(dir.list().empty());
}

TEST(AtomicFileWriter, WritesThroughATemporaryInTheSameDirectory) {
    TempDir dir;
    const std::string p = dir.file("out.txt");
    AtomicFileWriter writer(p);
    EXPECT_EQ(writer.temporary_path().rfind(p + ".tmp-", 0), 0u) << writer.temporary_path();
    writer.stream() << "hello";
    EXPECT_FALSE(std::filesystem::exists(p));
    writer.commit();
    EXPECT_EQ(test::read_bytes(p), "hello");
    EXPECT_EQ(dir.list(), std::vector<std::string>{"out.txt"});
    EXPECT_THROW(writer.commit(), FileError);
}

TEST(Malformed, FailedAtomicWriteKeepsTheOldFileAndRemovesTheTemporary) {
    TempDir dir;
    const std::string p = dir.file("keep.txt");
    test::write_bytes(p, "old content");
    EXPECT_THROW(write_file_atomically(p,
                                       [](std::ostream& out) {
                                           out << "partial new content";
                                           throw std::runtime_error("producer failed");
                                       }),
                 std::runtime_error);
    EXPECT_EQ(test::read_bytes(p), "old content");
    EXPECT_EQ(dir.list(), std::vector<std::string>{"keep.txt"});
    {
        AtomicFileWriter abandoned(p);
        abandoned.stream() << "never committed";
        EXPECT_TRUE(std::filesystem::exists(abandoned.temporary_path()));
    }
    EXPECT_EQ(test::read_bytes(p), "old content");
    EXPECT_EQ(dir.list(), std::vector<std::string>{"keep.txt"});
}

}  // namespace
}  // namespace scantling::io
