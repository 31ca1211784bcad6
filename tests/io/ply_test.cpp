#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/io/ply.hpp>

#include "test_files.hpp"

namespace scantling::io {
namespace {

using test::TempDir;

const char* const kTypedHeader =
    "element vertex 3\n"
    "property double x\nproperty float y\nproperty int z\n"
    "property char c\nproperty short s\nproperty ushort ring\nproperty uint u\n"
    "property list uchar int extra\n"
    "property float nx\nproperty float ny\nproperty float nz\n"
    "property uchar red\nproperty uint8 green\nproperty uchar blue\n"
    "property float32 intensity\nproperty float64 time\n"
    "element face 2\nproperty uchar flags\nproperty list uint8 uint32 vertex_indices\n"
    "element edge 1\nproperty list ushort short corners\nproperty int16 weight\n"
    "end_header\n";

template <typename Put>
void typed_vertex(Put put, double x, float y, std::int32_t z, std::uint16_t ring, std::uint8_t r) {
    put(x), put(y), put(z), put(std::int8_t{-3}), put(std::int16_t{-300}), put(ring);
    put(std::uint32_t{4000000000u});
    put(std::uint8_t{2}), put(std::int32_t{11}), put(std::int32_t{12});  // skipped list
    put(0.0f), put(0.0f), put(1.0f);
    put(r), put(std::uint8_t{20}), put(std::uint8_t{30});
    put(0.5f), put(0.25);
}

/// The same content as kTypedHeader describes, in binary with the given byte order.
template <typename Put>
std::string typed_binary(const std::string& format, Put put_bytes) {
    std::string out = "ply\nformat " + format + " 1.0\ncomment hand-built\n" + kTypedHeader;
    const auto put = [&](auto v) { put_bytes(out, v); };
    typed_vertex(put, -1.5, 2.25f, -7, 5, 10);
    typed_vertex(put, 3.0, -4.0f, 8, 6, 11);
    typed_vertex(put, 0.0, 0.5f, 0, 7, 12);
    put(std::uint8_t{1}), put(std::uint8_t{3});
    for (std::uint32_t v : {0u, 1u, 2u}) put(v);
    put(std::uint8_t{0}), put(std::uint8_t{4});  // a quad → two triangles
    for (std::uint32_t v : {2u, 1u, 0u, 1u}) put(v);
    put(std::uint16_t{2}), put(std::int16_t{0}), put(std::int16_t{1}), put(std::int16_t{9});
    return out;
}

void expect_typed_content(const PlyData& data) {
    const PointCloud& c = data.cloud;
    ASSERT_EQ(c.size(), 3u);
    EXPECT_EQ(c.points[0], Eigen::Vector3d(-1.5, 2.25, -7));
    EXPECT_EQ(c.points[1], Eigen::Vector3d(3, -4, 8));
    EXPECT_EQ(c.normals[2], Eigen::Vector3d(0, 0, 1));
    EXPECT_EQ(c.rings, (std::vector<std::uint16_t>{5, 6, 7}));
    EXPECT_EQ(c.colors[1], Rgb8(11, 20, 30));
    EXPECT_EQ(c.intensities[0], 0.5f);
    EXPECT_EQ(c.times_s[2], 0.25f);
    ASSERT_EQ(data.faces.size(), 3u);
    EXPECT_EQ(data.faces[0], Eigen::Vector3i(0, 1, 2));
    EXPECT_EQ(data.faces[1], Eigen::Vector3i(2, 1, 0));
    EXPECT_EQ(data.faces[2], Eigen::Vector3i(2, 0, 1));
}

TEST(Ply, RoundTripsEveryFieldAndFacesBitExact) {
    TempDir dir;
    const PointCloud cloud = test::make_full_cloud(500);
    const std::vector<Eigen::Vector3i> faces = {{0, 1, 2}, {499, 3, 250}};
    write_ply(dir.file("a.ply"), cloud, faces);
    const PlyData back = read_ply(dir.file("a.ply"));
    test::expect_same_cloud(cloud, back.cloud);
    EXPECT_EQ(back.faces, faces);
}

TEST(Ply, WritesOnlyPresentFieldsAndNoFaceElementWithoutFaces) {
    TempDir dir;
    PointCloud cloud;
    cloud.points = {Eigen::Vector3d(1, 2, 3)};
    write_ply(dir.file("a.ply"), cloud);
    const std::string bytes = test::read_bytes(dir.file("a.ply"));
    EXPECT_EQ(bytes.find("face"), std::string::npos);
    EXPECT_EQ(bytes.size(), bytes.find("end_header\n") + 11 + 12);
    const PlyData back = read_ply(dir.file("a.ply"));
    EXPECT_EQ(back.cloud.points, cloud.points);
    EXPECT_FALSE(back.cloud.has_normals() || back.cloud.has_colors() || back.cloud.has_rings());
}

TEST(Ply, ReadsEveryScalarTypeInLittleEndian) {
    TempDir dir;
    test::write_bytes(
        dir.file("le.ply"),
        typed_binary("binary_little_endian", [](std::string& o, auto v) { test::put(o, v); }));
    expect_typed_content(read_ply(dir.file("le.ply")));
}

TEST(Ply, ReadsEveryScalarTypeInBigEndian) {
    TempDir dir;
    test::write_bytes(
        dir.file("be.ply"),
        typed_binary("binary_big_endian", [](std::string& o, auto v) { test::put_be(o, v); }));
    expect_typed_content(read_ply(dir.file("be.ply")));
}

TEST(Ply, ReadsEveryScalarTypeInAscii) {
    TempDir dir;
    std::string text = std::string("ply\r\nformat ascii 1.0\nobj_info x\n") + kTypedHeader;
    text += "-1.5 2.25 -7 -3 -300 5 4000000000 2 11 12 0 0 1 10 20 30 0.5 0.25\n";
    text += "3 -4 8 -3 -300 6 4000000000 0 0 0 1 11 20 30 0.5 0.25\n";
    text += "0.0 0.5 0 -3 -300 7 4000000000 1 5 0 0 1 12 20 30 0.5 0.25\n";
    text += "1 3 0 1 2\n0 4 2 1 0 1\n\n2 0 1 9\n\n";
    test::write_bytes(dir.file("a.ply"), text);
    expect_typed_content(read_ply(dir.file("a.ply")));
}

TEST(Ply, ScalesFloatColoursAndReadsCloudCompareIntensity) {
    TempDir dir;
    test::write_bytes(
        dir.file("a.ply"),
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nproperty float red\nproperty float green\n"
        "property float blue\nproperty float scalar_intensity\nend_header\n"
        "1 2 3 1.0 0.5 0 42\n");
    const PlyData data = read_ply(dir.file("a.ply"));
    EXPECT_EQ(data.cloud.colors.at(0), Rgb8(255, 128, 0));
    EXPECT_EQ(data.cloud.intensities.at(0), 42.0f);
    EXPECT_TRUE(data.faces.empty());
}

}  // namespace
}  // namespace scantling::io
