// Crafted headers that lie about sizes and counts (issue 10). Every reader computes the sizes a
// header implies with overflow checks and bounds them by the bytes present, so each lie is a
// ParseError naming the file and the line or byte: never a signal, a huge allocation or a cloud
// decoded with the wrong stride. Each test says what the readers did before the fix.
#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/io/kitti.hpp>
#include <scantling/io/pcd.hpp>
#include <scantling/io/ply.hpp>
#include <scantling/io/tum.hpp>

#include <cstdint>
#include <functional>
#include <optional>

#include "../../src/io/detail/lzf.hpp"
#include "test_files.hpp"

namespace scantling::io {
namespace {

using test::put;
using test::TempDir;

struct Expected {
    std::optional<int> line;
    std::optional<std::uint64_t> byte;
    std::string fragment;  ///< part of the message that says what is wrong
};

void expect_parse_error(const std::string& path, const std::function<void()>& read,
                        const Expected& expected) {
    try {
        read();
        ADD_FAILURE() << "no error for " << path;
    } catch (const ParseError& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.path(), path);
        EXPECT_EQ(what.rfind(path, 0), 0u) << what;
        EXPECT_NE(what.find(expected.fragment), std::string::npos) << what;
        if (expected.line) {
            EXPECT_EQ(e.location().line, expected.line) << what;
        }
        if (expected.byte) {
            EXPECT_EQ(e.location().byte_offset, expected.byte) << what;
        }
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type for " << path << ": " << e.what();
    }
}

/// Lines 1..9: VERSION FIELDS SIZE TYPE COUNT WIDTH HEIGHT POINTS DATA.
std::string pcd_header(const std::string& fields, const std::string& sizes,
                       const std::string& types, const std::string& counts,
                       const std::string& width, const std::string& points, const std::string& data,
                       const std::string& height = "1") {
    return "VERSION 0.7\nFIELDS " + fields + "\nSIZE " + sizes + "\nTYPE " + types + "\nCOUNT " +
           counts + "\nWIDTH " + width + "\nHEIGHT " + height + "\nPOINTS " + points + "\nDATA " +
           data + "\n";
}

std::string xyz_pcd_header(std::size_t points, const std::string& data) {
    const std::string n = std::to_string(points);
    return pcd_header("x y z", "4 4 4", "F F F", "1 1 1", n, n, data);
}

std::string xyz_floats(std::size_t points) {
    std::string body;
    for (std::size_t i = 0; i < 3 * points; ++i) put(body, static_cast<float>(i));
    return body;
}

class HostileHeader : public testing::Test {
  protected:
    void expect_pcd_error(const std::string& bytes, const Expected& expected) {
        test::write_bytes(pcd_, bytes);
        expect_parse_error(
            pcd_, [&] { read_pcd(pcd_); }, expected);
    }
    void expect_ply_error(const std::string& bytes, const Expected& expected) {
        test::write_bytes(ply_, bytes);
        expect_parse_error(
            ply_, [&] { read_ply(ply_); }, expected);
    }

    TempDir dir_;
    std::string pcd_ = dir_.file("hostile.pcd");
    std::string ply_ = dir_.file("hostile.ply");
};

// Before: point_step = 12 + 4 x (2^62 - 3) wrapped to 0 and `available / point_step` raised
// SIGFPE (the example of issue 10).
TEST_F(HostileHeader, PcdCountWrappingThePointStepToZeroIsRefusedAtTheCountLine) {
    const std::string header = pcd_header("x y z foo", "4 4 4 4", "F F F U",
                                          "1 1 1 4611686018427387901", "4", "4", "binary");
    expect_pcd_error(header + std::string(48, '\0'),
                     {5, {}, "field 'foo' has SIZE 4 x COUNT 4611686018427387901"});
}

// Before: the record wrapped to 16 bytes while x sat 2^62 bytes in (SIGSEGV), or x sat at
// offset 2^64 - 1, one byte before the data, and was read from there (exit 0).
TEST_F(HostileHeader, PcdCountWrappingAFieldOffsetIsRefused) {
    const std::string wraps_to_16 =
        pcd_header("foo x y z bar", "1 4 4 4 1", "U F F F U",
                   "4611686018427387904 1 1 1 13835058055282163716", "4", "4", "binary");
    expect_pcd_error(wraps_to_16 + std::string(64, '\0'), {5, {}, "field 'bar'"});
    const std::string before_the_data = pcd_header(
        "foo x y z", "1 4 4 4", "U F F F", "18446744073709551615 1 1 1", "4", "4", "binary");
    expect_pcd_error(before_the_data + std::string(48, '\0'), {5, {}, "field 'x'"});
}

// Before: 2^32 x 2^32 wrapped to 0 = POINTS and the file read as an empty cloud.
TEST_F(HostileHeader, PcdWidthTimesHeightOverflowingIsRefused) {
    const std::string header =
        pcd_header("x y z", "4 4 4", "F F F", "1 1 1", "4294967296", "0", "ascii", "4294967296");
    expect_pcd_error(header, {8, {}, "expected WIDTH * HEIGHT"});
}

// Before: the later x won silently (x = 9).
TEST_F(HostileHeader, PcdRepeatedFieldIsRefusedButRepeatedPaddingIsRead) {
    expect_pcd_error(
        pcd_header("x y z x", "4 4 4 4", "F F F F", "1 1 1 1", "1", "1", "ascii") + "1 2 3 9\n",
        {2, {}, "field 'x' appears twice"});
    test::write_bytes(
        pcd_, pcd_header("x _ y _ z", "4 1 4 2 4", "F U F U F", "1 1 1 3 1", "1", "1", "ascii") +
                  "1 0 2 0 0 0 3\n");
    EXPECT_EQ(read_pcd(pcd_).points.at(0), Eigen::Vector3d(1, 2, 3));
}

// Before: the later field overwrote the intensities silently.
TEST_F(HostileHeader, PcdTwoFieldsFeedingOneCloudMemberAreRefused) {
    expect_pcd_error(pcd_header("x y z intensity reflectance", "4 4 4 4 4", "F F F F F",
                                "1 1 1 1 1", "1", "1", "ascii") +
                         "1 2 3 4 5\n",
                     {2, {}, "fields 'intensity' and 'reflectance' both map"});
}

// Before: 8 doubles under a header of one float point read as x = 0, y = 1.875, exit 0.
TEST_F(HostileHeader, PcdBinaryDataLongerThanDeclaredIsRefused) {
    const std::string header = xyz_pcd_header(1, "binary");
    std::string body;
    for (int i = 1; i <= 8; ++i) put(body, static_cast<double>(i));
    expect_pcd_error(header + body, {{}, header.size() + 12, "52 bytes follow the declared data"});
}

// PCL up to 1.8 stretches binary files to a page: the zeros after the data are not a lie.
TEST_F(HostileHeader, PcdPagePaddingAfterBinaryDataIsRead) {
    const std::string header = xyz_pcd_header(5, "binary");
    test::write_bytes(pcd_, header + xyz_floats(5) + std::string(4096 - header.size(), '\0'));
    const PointCloud cloud = read_pcd(pcd_);
    ASSERT_EQ(cloud.size(), 5u);
    EXPECT_EQ(cloud.points[4], Eigen::Vector3d(12, 13, 14));
}

// Before: 49 / 4 == 12 passed, and the LZF decoder failed later with another message.
TEST_F(HostileHeader, PcdCompressedSizeOtherThanPointsTimesStepIsRefused) {
    const std::string header = xyz_pcd_header(4, "binary_compressed");
    const std::string raw = xyz_floats(4) + "x";
    const auto packed =
        detail::lzf_compress({reinterpret_cast<const std::uint8_t*>(raw.data()), raw.size()});
    std::string bytes = header;
    put(bytes, static_cast<std::uint32_t>(packed.size()));
    put(bytes, static_cast<std::uint32_t>(raw.size()));
    bytes.append(reinterpret_cast<const char*>(packed.data()), packed.size());
    expect_pcd_error(bytes, {{}, header.size() + 4, "uncompressed size 49, expected POINTS * 12"});
}

// Before: a ring of 300 in a U 1 field was stored as 300.
TEST_F(HostileHeader, PcdAsciiValueOutsideItsDeclaredTypeIsRefused) {
    expect_pcd_error(pcd_header("x y z ring", "4 4 4 1", "F F F U", "1 1 1 1", "1", "1", "ascii") +
                         "1 2 3 300\n",
                     {10, {}, "invalid token '300', expected a value that fits uint8"});
}

// Before: refused at the DATA line with "only 12 bytes follow"; the bound now allows for the
// bytes a row takes and the data is walked to say where it ends.
TEST_F(HostileHeader, PcdAsciiPointsBeyondTheDataAreReportedWhereTheDataEnds) {
    expect_pcd_error(xyz_pcd_header(1000, "ascii") + "1 2 3\n4 5 6\n",
                     {11, {}, "file ends after 2 points, expected POINTS = 1000"});
    expect_pcd_error(xyz_pcd_header(3, "ascii") + "1 2 3\n4\n5\n",
                     {11, {}, "found 1 values, expected 3"});
}

std::string xyz_ply_header(const std::string& format, const std::string& vertices,
                           const std::string& extra_properties = "") {
    return "ply\nformat " + format + " 1.0\nelement vertex " + vertices +
           "\nproperty float x\nproperty float y\nproperty float z\n" + extra_properties +
           "end_header\n";
}

// Before: a uint64 count of 2^64 - 1 became a double of 2^64, converted to size_t (undefined;
// 0 on x86, "polygon with 0 corners").
TEST_F(HostileHeader, PlyListLongerThanTheDataIsRefusedBeforeUse) {
    std::string bytes = xyz_ply_header("binary_little_endian", "3",
                                       "element face 1\nproperty list uint64 int vertex_indices\n");
    const std::size_t list_at = bytes.size() + 36;
    bytes += xyz_floats(3);
    put(bytes, UINT64_MAX);  // 2^64 once converted to double
    bytes.append(12, '\0');
    expect_ply_error(bytes, {{}, list_at, "list of 18446744073709551616 values"});
    const std::string ascii =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    expect_ply_error(ascii + "0 0 0\n1 0 0\n0 1 0\n200 0 1 2\n",
                     {13, {}, "list of 200 values in element 'face' row 0 of 1, but only 3"});
}

// Before: the later x won silently.
TEST_F(HostileHeader, PlyRepeatedPropertyIsRefused) {
    expect_ply_error(xyz_ply_header("ascii", "1", "property float x\n") + "1 2 3 9\n",
                     {7, {}, "property 'x' declared twice in element 'vertex'"});
}

// Before: the second vertex element was skipped silently.
TEST_F(HostileHeader, PlyRepeatedElementIsRefused) {
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
        "property float y\nproperty float z\nelement vertex 1\n"
        "property float x\nproperty float y\nproperty float z\n"
        "end_header\n";
    expect_ply_error(header + "1 2 3\n4 5 6\n", {7, {}, "element 'vertex' declared twice"});
}

// Before: the later property overwrote the normals silently.
TEST_F(HostileHeader, PlyTwoPropertiesFeedingOneCloudMemberAreRefused) {
    expect_ply_error(xyz_ply_header("ascii", "1",
                                    "property float nx\nproperty float ny\nproperty float nz\n"
                                    "property float normal_x\n") +
                         "1 2 3 0 0 1 1\n",
                     {10, {}, "properties 'nx' and 'normal_x' both map"});
}

// Before: red 300 was clamped to 255 and a uint64 of -1 was read as -1.
TEST_F(HostileHeader, PlyAsciiValueOutsideItsDeclaredTypeIsRefused) {
    expect_ply_error(xyz_ply_header("ascii", "1", "property uchar red\n") + "1 2 3 300\n",
                     {9, {}, "invalid token '300', expected a value that fits uint8"});
    expect_ply_error(xyz_ply_header("ascii", "1", "property uint64 id\n") + "1 2 3 -1\n",
                     {9, {}, "invalid token '-1'"});
}

// Before: refused before reading with "declares 1000 rows, but only 60 bytes follow"; the
// bound is now count x bytes per row, and the data is walked to say where it ends.
TEST_F(HostileHeader, PlyRowCountsBeyondTheDataAreReportedWhereTheDataEnds) {
    const std::string binary = xyz_ply_header("binary_little_endian", "1000");
    expect_ply_error(binary + xyz_floats(5),
                     {{}, binary.size() + 60, "file ends inside element 'vertex' row 5 of 1000"});
    const std::string overflowing = xyz_ply_header("binary_little_endian", "4611686018427387904");
    expect_ply_error(overflowing + xyz_floats(1), {{}, overflowing.size() + 12, "row 1 of"});
    expect_ply_error(xyz_ply_header("ascii", "1000") + "1 2 3\n4 5 6\n",
                     {9, {}, "file ends before element 'vertex' row 2 of 1000"});
}

// Confirms the pose readers refuse an absurd line by counting its tokens, storing none.
TEST_F(HostileHeader, PoseLineOfAMillionValuesIsRefusedNamingTheLine) {
    std::string line;
    for (int i = 0; i < 1000000; ++i) line += "1 ";
    const std::string kitti = dir_.file("poses.txt");
    test::write_bytes(kitti, "1 0 0 0 0 1 0 0 0 0 1 0\n" + line + "\n");
    expect_parse_error(kitti, [&] { read_kitti_poses(kitti); },
                       {2, {}, "found 1000000 values, expected 12"});
    const std::string tum = dir_.file("poses.tum");
    test::write_bytes(tum, line + "\n");
    expect_parse_error(tum, [&] { read_tum(tum); }, {1, {}, "found 1000000 values, expected 8"});
}

}  // namespace
}  // namespace scantling::io
