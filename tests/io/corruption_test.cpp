// Random corruptions of valid files (flipped, inserted, deleted bytes, truncation): readers
// must either succeed or throw ParseError — never crash, read out of bounds (run under ASan to
// check) or throw anything else. Seeds are fixed, so failures reproduce.
#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/io/kitti.hpp>
#include <scantling/io/pcd.hpp>
#include <scantling/io/ply.hpp>
#include <scantling/io/tum.hpp>

#include <functional>
#include <random>

#include "../../src/io/detail/lzf.hpp"
#include "test_files.hpp"

namespace scantling::io {
namespace {

using test::TempDir;

constexpr int kMutationsPerFile = 300;

std::string mutate(std::string bytes, std::mt19937& rng) {
    static const char kPlausible[] = "0123456789 \n-.enan";
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < edits && !bytes.empty(); ++k) {
        const std::size_t at = rng() % bytes.size();
        switch (rng() % 4) {
            case 0:
                bytes[at] = static_cast<char>(rng());
                break;
            case 1:
                bytes.resize(at);
                break;
            case 2:
                bytes.insert(at, 1, kPlausible[rng() % (sizeof(kPlausible) - 1)]);
                break;
            default:
                bytes.erase(at, 1);
                break;
        }
    }
    return bytes;
}

/// Returns how many corrupted variants were rejected with ParseError.
int count_rejections(const std::string& original, const std::string& path,
                     const std::function<void(const std::string&)>& read) {
    std::mt19937 rng(1234);
    int rejected = 0;
    for (int i = 0; i < kMutationsPerFile; ++i) {
        test::write_bytes(path, mutate(original, rng));
        try {
            read(path);
        } catch (const ParseError& e) {
            EXPECT_EQ(e.path(), path);
            ++rejected;
        } catch (const std::exception& e) {
            ADD_FAILURE() << "mutation " << i << " of " << path << ": " << e.what();
        }
    }
    return rejected;
}

std::string compressed_pcd(const PointCloud& cloud) {
    std::string raw;
    for (int axis = 0; axis < 3; ++axis) {
        for (const auto& p : cloud.points) test::put(raw, static_cast<float>(p[axis]));
    }
    const auto packed =
        detail::lzf_compress({reinterpret_cast<const std::uint8_t*>(raw.data()), raw.size()});
    const std::string n = std::to_string(cloud.size());
    std::string bytes = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " +
                        n + "\nHEIGHT 1\nPOINTS " + n + "\nDATA binary_compressed\n";
    test::put(bytes, static_cast<std::uint32_t>(packed.size()));
    test::put(bytes, static_cast<std::uint32_t>(raw.size()));
    bytes.append(reinterpret_cast<const char*>(packed.data()), packed.size());
    return bytes;
}

TEST(Corruption, PcdReaderOnlyThrowsParseErrors) {
    TempDir dir;
    const PointCloud cloud = test::make_full_cloud(40);
    const auto read = [](const std::string& p) { read_pcd(p); };
    write_pcd(dir.file("a.pcd"), cloud, PcdEncoding::kAscii);
    write_pcd(dir.file("b.pcd"), cloud, PcdEncoding::kBinary);
    EXPECT_GT(count_rejections(test::read_bytes(dir.file("a.pcd")), dir.file("m.pcd"), read), 0);
    EXPECT_GT(count_rejections(test::read_bytes(dir.file("b.pcd")), dir.file("m.pcd"), read), 0);
    EXPECT_GT(count_rejections(compressed_pcd(cloud), dir.file("m.pcd"), read), 0);
}

TEST(Corruption, PlyReaderOnlyThrowsParseErrors) {
    TempDir dir;
    const std::vector<Eigen::Vector3i> faces = {{0, 1, 2}, {3, 4, 5}, {39, 0, 7}};
    write_ply(dir.file("a.ply"), test::make_full_cloud(40), faces);
    const auto read = [](const std::string& p) { read_ply(p); };
    EXPECT_GT(count_rejections(test::read_bytes(dir.file("a.ply")), dir.file("m.ply"), read), 0);
    const std::string ascii =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nproperty list uchar int extra\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n0 0 0 2 1 2\n1 0 0 0\n0 1 0 1 5\n"
        "3 0 1 2\n";
    EXPECT_GT(count_rejections(ascii, dir.file("m.ply"), read), 0);
}

TEST(Corruption, PoseReadersOnlyThrowParseErrors) {
    TempDir dir;
    write_tum(dir.file("t.txt"), std::vector<StampedPose>(1));
    write_kitti_poses(dir.file("k.txt"),
                      std::vector<Eigen::Isometry3d>(3, Eigen::Isometry3d::Identity()));
    EXPECT_GT(count_rejections(test::read_bytes(dir.file("t.txt")), dir.file("m.txt"),
                               [](const std::string& p) { read_tum(p); }),
              0);
    EXPECT_GT(count_rejections(test::read_bytes(dir.file("k.txt")), dir.file("m.txt"),
                               [](const std::string& p) { read_kitti_poses(p); }),
              0);
}

}  // namespace
}  // namespace scantling::io
