#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/io/pcd.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "../../src/io/detail/lzf.hpp"
#include "test_files.hpp"

namespace scantling::io {
namespace {

using test::put;
using test::TempDir;

// GCC 12.2 at -O2/-O3 (SLP vectoriser) folds `(double)(float)x` on pairs of Eigen
// coefficients into `x`; a volatile float forces the rounding.
double round_to_float32(double value) {
    volatile float rounded = static_cast<float>(value);
    return rounded;
}

struct TestField {
    std::string name;
    char type;
    int size;
    int count = 1;
};

std::string header(const std::vector<TestField>& fields, std::size_t width, std::size_t height,
                   const std::string& data) {
    std::string names, sizes, types, counts;
    for (const auto& f : fields) {
        names.append(" ").append(f.name);
        sizes.append(" ").append(std::to_string(f.size));
        types.append(" ").push_back(f.type);
        counts.append(" ").append(std::to_string(f.count));
    }
    return "# .PCD v0.7\nVERSION 0.7\nFIELDS" + names + "\nSIZE" + sizes + "\nTYPE" + types +
           "\nCOUNT" + counts + "\nWIDTH " + std::to_string(width) + "\nHEIGHT " +
           std::to_string(height) + "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
           std::to_string(width * height) + "\nDATA " + data + "\n";
}

void put_value(std::string& out, const TestField& f, double v) {
    switch (f.type * 16 + f.size) {
        case 'F' * 16 + 4:
            return put(out, static_cast<float>(v));
        case 'F' * 16 + 8:
            return put(out, v);
        case 'I' * 16 + 1:
            return put(out, static_cast<std::int8_t>(v));
        case 'I' * 16 + 2:
            return put(out, static_cast<std::int16_t>(v));
        case 'I' * 16 + 4:
            return put(out, static_cast<std::int32_t>(v));
        case 'I' * 16 + 8:
            return put(out, static_cast<std::int64_t>(v));
        case 'U' * 16 + 1:
            return put(out, static_cast<std::uint8_t>(v));
        case 'U' * 16 + 2:
            return put(out, static_cast<std::uint16_t>(v));
        case 'U' * 16 + 4:
            return put(out, static_cast<std::uint32_t>(v));
        default:
            return put(out, static_cast<std::uint64_t>(v));
    }
}

/// Point-major records; value(point, field, element).
template <typename Value>
std::string binary_body(const std::vector<TestField>& fields, std::size_t n, Value value) {
    std::string body;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t f = 0; f < fields.size(); ++f) {
            for (int k = 0; k < fields[f].count; ++k) put_value(body, fields[f], value(i, f, k));
        }
    }
    return body;
}

/// PCL's binary_compressed: field-major values, LZF-compressed, preceded by both sizes.
template <typename Value>
std::string compressed_body(const std::vector<TestField>& fields, std::size_t n, Value value) {
    std::string raw;
    for (std::size_t f = 0; f < fields.size(); ++f) {
        for (std::size_t i = 0; i < n; ++i) {
            for (int k = 0; k < fields[f].count; ++k) put_value(raw, fields[f], value(i, f, k));
        }
    }
    const auto packed =
        detail::lzf_compress({reinterpret_cast<const std::uint8_t*>(raw.data()), raw.size()});
    std::string body;
    put(body, static_cast<std::uint32_t>(packed.size()));
    put(body, static_cast<std::uint32_t>(raw.size()));
    body.append(reinterpret_cast<const char*>(packed.data()), packed.size());
    return body;
}

// Fields of every supported type and size, a histogram (COUNT 3) and padding among them.
const std::vector<TestField> kMixedFields = {
    {"x", 'F', 8},       {"y", 'F', 4},         {"z", 'F', 4},         {"_", 'U', 1, 3},
    {"fpfh", 'F', 4, 3}, {"intensity", 'U', 2}, {"ring", 'U', 1},      {"label", 'I', 8},
    {"t", 'U', 4},       {"rgba", 'U', 4},      {"curvature", 'I', 2},
};

double mixed_value(std::size_t i, std::size_t f, int k) {
    switch (f) {
        case 0:
            return 0.125 * static_cast<double>(i) - 3.0;
        case 1:
            return -0.5 * static_cast<double>(i);
        case 2:
            return 1.5;
        case 5:
            return static_cast<double>(1000 + i);
        case 6:
            return static_cast<double>(i % 32);
        case 8:
            return static_cast<double>(i) * 1000.0;  // nanoseconds
        case 9:
            return static_cast<double>(0xff102030u + i % 200);  // blue stays below 256
        default:
            return static_cast<double>(k) + 1.0;
    }
}

void expect_mixed_cloud(const PointCloud& cloud, std::size_t n) {
    ASSERT_EQ(cloud.size(), n);
    EXPECT_FALSE(cloud.has_normals());
    for (std::size_t i = 0; i < n; ++i) {
        EXPECT_EQ(cloud.points[i],
                  Eigen::Vector3d(mixed_value(i, 0, 0), mixed_value(i, 1, 0), 1.5));
        EXPECT_EQ(cloud.intensities[i], static_cast<float>(1000 + i));
        EXPECT_EQ(cloud.rings[i], i % 32);
        EXPECT_EQ(cloud.times_s[i], static_cast<float>(static_cast<double>(i) * 1e-6));
        EXPECT_EQ(cloud.colors[i], Rgb8(0x10, 0x20, static_cast<std::uint8_t>(0x30 + i % 200)));
    }
}

TEST(Pcd, RoundTripsEveryFieldBitExactInBinary) {
    TempDir dir;
    const PointCloud cloud = test::make_full_cloud(1000);
    write_pcd(dir.file("a.pcd"), cloud, PcdEncoding::kBinary);
    test::expect_same_cloud(cloud, read_pcd(dir.file("a.pcd")));
}

TEST(Pcd, RoundTripsEveryFieldBitExactInAscii) {
    TempDir dir;
    const PointCloud cloud = test::make_full_cloud(1000);
    write_pcd(dir.file("a.pcd"), cloud, PcdEncoding::kAscii);
    test::expect_same_cloud(cloud, read_pcd(dir.file("a.pcd")));
}

TEST(Pcd, RoundsDoublePositionsToFloat32) {
    TempDir dir;
    PointCloud cloud;
    cloud.points = {Eigen::Vector3d(0.1, 1e6 + 0.3, -12345.678901)};
    write_pcd(dir.file("a.pcd"), cloud);
    Eigen::Vector3d expected;
    for (int k = 0; k < 3; ++k) expected[k] = round_to_float32(cloud.points[0][k]);
    EXPECT_NE(expected, cloud.points[0]);
    EXPECT_EQ(read_pcd(dir.file("a.pcd")).points[0], expected);
}

TEST(Pcd, WritesOnlyThePresentFields) {
    TempDir dir;
    PointCloud cloud;
    cloud.points = {Eigen::Vector3d(1, 2, 3)};
    cloud.rings = {7};
    write_pcd(dir.file("a.pcd"), cloud, PcdEncoding::kAscii);
    const std::string text = test::read_bytes(dir.file("a.pcd"));
    EXPECT_NE(text.find("FIELDS x y z ring\nSIZE 4 4 4 2\nTYPE F F F U\n"), std::string::npos)
        << text;
    EXPECT_NE(text.find("DATA ascii\n1 2 3 7\n"), std::string::npos) << text;
    const PointCloud back = read_pcd(dir.file("a.pcd"));
    EXPECT_FALSE(back.has_normals() || back.has_intensities() || back.has_times() ||
                 back.has_colors());
    EXPECT_EQ(back.rings, cloud.rings);
}

TEST(Pcd, RoundTripsAnEmptyCloud) {
    TempDir dir;
    write_pcd(dir.file("a.pcd"), PointCloud{}, PcdEncoding::kBinary);
    EXPECT_TRUE(read_pcd(dir.file("a.pcd")).empty());
}

TEST(Pcd, ReadsEveryTypeSizeAndSkipsUnknownFieldsInBinary) {
    TempDir dir;
    const std::size_t n = 37;
    test::write_bytes(dir.file("a.pcd"), header(kMixedFields, n, 1, "binary") +
                                             binary_body(kMixedFields, n, mixed_value));
    expect_mixed_cloud(read_pcd(dir.file("a.pcd")), n);
}

TEST(Pcd, ReadsBinaryCompressedWrittenWithOurLzf) {
    TempDir dir;
    const std::size_t n = 500;
    test::write_bytes(dir.file("a.pcd"), header(kMixedFields, n, 1, "binary_compressed") +
                                             compressed_body(kMixedFields, n, mixed_value));
    expect_mixed_cloud(read_pcd(dir.file("a.pcd")), n);
}

TEST(Pcd, ReadsBinaryCompressedFloatFieldsBitExact) {
    TempDir dir;
    const PointCloud cloud = test::make_full_cloud(300);
    const std::vector<TestField> fields = {
        {"x", 'F', 4}, {"y", 'F', 4}, {"z", 'F', 4}, {"intensity", 'F', 4}};
    const auto value = [&](std::size_t i, std::size_t f, int) {
        return f < 3 ? cloud.points[i][static_cast<int>(f)] : cloud.intensities[i];
    };
    test::write_bytes(dir.file("c.pcd"), header(fields, 300, 1, "binary_compressed") +
                                             compressed_body(fields, 300, value));
    const PointCloud back = read_pcd(dir.file("c.pcd"));
    EXPECT_EQ(back.points, cloud.points);
    EXPECT_EQ(back.intensities, cloud.intensities);
}

TEST(Pcd, ReadsAsciiWithMixedTypesAndHistograms) {
    TempDir dir;
    std::string text = header(kMixedFields, 3, 1, "ascii");
    text += "0.5 -1 2 0 0 0 1e-3 2 3 1000 7 -5 2000000000 16711680 -1\n";
    text += "+1.25 0 0 1 1 1 0 0 0 0 0 0 0 255 0\r\n";
    text += "\n-2 3.5 -0.0 9 9 9 1 1 1 65535 255 9 0 65280 3\n";
    test::write_bytes(dir.file("a.pcd"), text);
    const PointCloud cloud = read_pcd(dir.file("a.pcd"));
    ASSERT_EQ(cloud.size(), 3u);
    EXPECT_EQ(cloud.points[0], Eigen::Vector3d(0.5, -1, 2));
    EXPECT_EQ(cloud.points[1], Eigen::Vector3d(1.25, 0, 0));
    EXPECT_EQ(cloud.intensities[2], 65535.0f);
    EXPECT_EQ(cloud.rings[0], 7);
    EXPECT_EQ(cloud.times_s[0], 2.0f);  // "t" as uint: nanoseconds
    EXPECT_EQ(cloud.colors[0], Rgb8(255, 0, 0));
    EXPECT_EQ(cloud.colors[1], Rgb8(0, 0, 255));
    EXPECT_EQ(cloud.colors[2], Rgb8(0, 255, 0));
}

TEST(Pcd, ReadsCrlfLineEndingsAndCommentsInTheHeader) {
    TempDir dir;
    const std::string lf = "# a comment\n" +
                           header({{"x", 'F', 4}, {"y", 'F', 4}, {"z", 'F', 4}}, 1, 1, "ascii") +
                           "1 2 3\n";
    std::string crlf;
    for (const char c : lf) {
        if (c == '\n') crlf.push_back('\r');
        crlf.push_back(c);
    }
    test::write_bytes(dir.file("a.pcd"), crlf);
    EXPECT_EQ(read_pcd(dir.file("a.pcd")).points.at(0), Eigen::Vector3d(1, 2, 3));
}

TEST(Pcd, KeepsNanPointsOfAnOrganisedCloudInRowMajorOrder) {
    TempDir dir;
    std::string text = header({{"x", 'F', 4}, {"y", 'F', 4}, {"z", 'F', 4}}, 2, 2, "ascii");
    text += "1 2 3\nnan nan nan\n4 5 6\n7 8 nan\n";
    test::write_bytes(dir.file("a.pcd"), text);
    const PointCloud cloud = read_pcd(dir.file("a.pcd"));
    ASSERT_EQ(cloud.size(), 4u);
    EXPECT_EQ(cloud.points[2], Eigen::Vector3d(4, 5, 6));
    EXPECT_TRUE(std::isnan(cloud.points[1].x()));
    EXPECT_TRUE(std::isnan(cloud.points[3].z()));
    EXPECT_EQ(remove_non_finite(cloud).size(), 2u);
}

TEST(Pcd, ReadsPclPackedFloatRgbInBinaryAndAscii) {
    TempDir dir;
    const Rgb8 color(12, 34, 56);
    const std::uint32_t bits = (12u << 16) | (34u << 8) | 56u;
    float packed;
    std::memcpy(&packed, &bits, sizeof(packed));
    const std::vector<TestField> fields = {
        {"x", 'F', 4}, {"y", 'F', 4}, {"z", 'F', 4}, {"rgb", 'F', 4}};
    std::string binary = header(fields, 1, 1, "binary");
    for (float v : {1.0f, 2.0f, 3.0f, packed}) put(binary, v);
    test::write_bytes(dir.file("b.pcd"), binary);
    test::write_bytes(dir.file("a.pcd"),
                      header(fields, 1, 1, "ascii") + "1 2 3 " + std::to_string(bits) + "\n");
    EXPECT_EQ(read_pcd(dir.file("b.pcd")).colors.at(0), color);
    EXPECT_EQ(read_pcd(dir.file("a.pcd")).colors.at(0), color);
}

TEST(Pcd, MovesAbsoluteDoubleTimestampsIntoStamp) {
    TempDir dir;
    const std::vector<TestField> fields = {
        {"x", 'F', 4}, {"y", 'F', 4}, {"z", 'F', 4}, {"timestamp", 'F', 8}};
    std::string text = header(fields, 2, 1, "ascii");
    text += "0 0 0 1700000000.25\n1 1 1 1700000000.5\n";
    test::write_bytes(dir.file("a.pcd"), text);
    const PointCloud cloud = read_pcd(dir.file("a.pcd"));
    EXPECT_EQ(cloud.stamp_s, 1700000000.25);
    EXPECT_EQ(cloud.times_s, (std::vector<float>{0.0f, 0.25f}));
}

}  // namespace
}  // namespace scantling::io
