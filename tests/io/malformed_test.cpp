// A corpus of malformed files, generated here: every reader must throw the right typed error
// naming the file and the line or byte offset; every failing writer must leave nothing behind.
#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/kitti.hpp>
#include <scantling/io/mesh_io.hpp>
#include <scantling/io/pcd.hpp>
#include <scantling/io/ply.hpp>
#include <scantling/io/tum.hpp>

#include <functional>

#include "../../src/io/detail/lzf.hpp"
#include "test_files.hpp"

namespace scantling::io {
namespace {

using test::expect_file_error;
using test::TempDir;

/// Header of an x y z float cloud; data lines start at line 12.
std::string xyz_header(int width, int height, int points, const std::string& data) {
    return "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " +
           std::to_string(width) + "\nHEIGHT " + std::to_string(height) +
           "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(points) + "\nDATA " + data + "\n";
}

std::string xyz_ply_header(const std::string& format, int vertices, int faces) {
    return "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(vertices) +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
           std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

struct Expected {
    std::optional<int> line;
    std::optional<std::uint64_t> byte;
    std::string fragment;  ///< part of the message that says what was expected
};

void expect_parse_error(const std::function<void()>& call, const std::string& path,
                        const Expected& expected) {
    try {
        call();
        ADD_FAILURE() << "no error for " << path;
    } catch (const ParseError& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.path(), path);
        EXPECT_EQ(what.rfind(path, 0), 0u) << what;
        EXPECT_NE(what.find(expected.fragment), std::string::npos) << what;
        if (expected.line) {
            EXPECT_EQ(e.location().line, expected.line) << what;
            EXPECT_NE(what.find("line " + std::to_string(*expected.line)), std::string::npos)
                << what;
        }
        if (expected.byte) {
            EXPECT_EQ(e.location().byte_offset, expected.byte) << what;
            EXPECT_NE(what.find("byte " + std::to_string(*expected.byte)), std::string::npos)
                << what;
        }
        EXPECT_TRUE(e.location().line || e.location().byte_offset) << what;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type for " << path << ": " << e.what();
    }
}

const std::vector<std::pair<std::string, std::function<void(const std::string&)>>> kReaders = {
    {"pcd", [](const std::string& p) { read_pcd(p); }},
    {"ply", [](const std::string& p) { read_ply(p); }},
    {"bin", [](const std::string& p) { read_kitti_bin(p); }},
    {"poses.txt", [](const std::string& p) { read_kitti_poses(p); }},
    {"tum.txt", [](const std::string& p) { read_tum(p); }},
    {"stl", [](const std::string& p) { read_mesh(p); }},
    {"obj", [](const std::string& p) { read_mesh(p); }},
};

TEST(Malformed, PcdHeaderErrorsNameTheLine) {
    TempDir dir;
    const std::string p = dir.file("bad.pcd");
    const auto check = [&](const std::string& bytes, const Expected& expected) {
        test::write_bytes(p, bytes);
        expect_parse_error([&] { read_pcd(p); }, p, expected);
    };
    check(xyz_header(4, 1, 5, "ascii"), {10, {}, "expected WIDTH * HEIGHT"});
    check(xyz_header(2, 3, 5, "binary"), {10, {}, "expected WIDTH * HEIGHT"});
    check(xyz_header(1, 1, 1, "zip"), {11, {}, "unknown DATA type 'zip'"});
    std::string no_fields = xyz_header(1, 1, 1, "ascii");
    no_fields.replace(no_fields.find("FIELDS"), 11, "# no fields");
    check(no_fields + "1 2 3\n", {11, {}, "lacks the FIELDS line"});
    std::string bad_type = xyz_header(1, 1, 1, "ascii");
    bad_type.replace(bad_type.find("TYPE F F F"), 10, "TYPE F F X");
    check(bad_type, {5, {}, "expected F (4, 8), I or U"});
    std::string short_size = xyz_header(1, 1, 1, "ascii");
    short_size.replace(short_size.find("SIZE 4 4 4"), 10, "SIZE 4 4");
    check(short_size, {4, {}, "expected 3"});
    check("# .PCD\nVERSION 0.7\nFIELDS x y z\nBOGUS 1\n", {4, {}, "unknown PCD header key"});
    check("VERSION 0.7\nFIELDS x y z\n", {2, {}, "no DATA line"});
    check("", {1, {}, "empty file"});
}

TEST(Malformed, PcdAsciiBodyErrorsNameTheLine) {
    TempDir dir;
    const std::string p = dir.file("bad.pcd");
    const auto check = [&](const std::string& bytes, const Expected& expected) {
        test::write_bytes(p, bytes);
        expect_parse_error([&] { read_pcd(p); }, p, expected);
    };
    check(xyz_header(2, 1, 2, "ascii") + "1 2 3\n4 1.0abc 6\n", {13, {}, "invalid token '1.0abc'"});
    check(xyz_header(2, 1, 2, "ascii") + "1 2 3\n4 5\n", {13, {}, "found 2 values, expected 3"});
    check(xyz_header(3, 1, 3, "ascii") + "1 2 3\n4 5 6\n", {13, {}, "expected POINTS = 3"});
    check(xyz_header(1, 1, 1, "ascii") + "1 2 3\n4 5 6\n", {13, {}, "more points than POINTS"});
    std::string no_z = xyz_header(1, 1, 1, "ascii");
    no_z.replace(no_z.find("FIELDS x y z"), 12, "FIELDS x y w");
    check(no_z + "1 2 3\n", {11, {}, "lacks one of x, y, z"});
}

TEST(Malformed, TruncatedBinaryPcdNamesWhereTheDataEnds) {
    TempDir dir;
    const std::string p = dir.file("short.pcd");
    std::string bytes = xyz_header(10, 1, 10, "binary");
    bytes.append(9 * 12 + 6, '\0');
    test::write_bytes(p, bytes);
    expect_parse_error([&] { read_pcd(p); }, p,
                       {{}, bytes.size(), "expected 10 points of 12 bytes"});
}

TEST(Malformed, CorruptLzfStreamIsAParseErrorAtItsByteOffset) {
    TempDir dir;
    const std::string p = dir.file("lzf.pcd");
    const std::string header = xyz_header(4, 1, 4, "binary_compressed");
    std::vector<std::uint8_t> raw(48, 7);
    auto packed = detail::lzf_compress(raw);
    ASSERT_GE(packed.size(), 3u);
    packed[packed.size() - 1] = 0xff;  // back reference far before the start of the output
    packed[packed.size() - 2] = 0xff;
    std::string bytes = header;
    test::put(bytes, static_cast<std::uint32_t>(packed.size()));
    test::put(bytes, std::uint32_t{48});
    bytes.append(reinterpret_cast<const char*>(packed.data()), packed.size());
    test::write_bytes(p, bytes);
    expect_parse_error([&] { read_pcd(p); }, p, {{}, {}, "corrupt LZF stream"});
    try {
        read_pcd(p);
    } catch (const ParseError& e) {
        EXPECT_GE(*e.location().byte_offset, header.size() + 8);
        EXPECT_LT(*e.location().byte_offset, bytes.size());
    }
    std::string lying = header;
    test::put(lying, std::uint32_t{1000});
    test::put(lying, std::uint32_t{48});
    test::write_bytes(p, lying + "abc");
    expect_parse_error([&] { read_pcd(p); }, p,
                       {{}, lying.size() + 3, "compressed block of 1000 bytes"});
}

TEST(Malformed, PlyErrorsNameTheLineOrByte) {
    TempDir dir;
    const std::string p = dir.file("bad.ply");
    const auto check = [&](const std::string& bytes, const Expected& expected) {
        test::write_bytes(p, bytes);
        expect_parse_error([&] { read_ply(p); }, p, expected);
    };
    check("plx\nformat ascii 1.0\nend_header\n", {1, {}, "bad magic"});
    check("", {1, {}, "empty file"});
    check("ply\nformat binary_middle_endian 1.0\nend_header\n", {2, {}, "unknown PLY format"});
    check("ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
          {4, {}, "unknown PLY type"});
    check("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", {4, {}, "no end_header"});
    const std::string ascii = xyz_ply_header("ascii", 3, 1);  // data from line 10
    check(ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", {13, {}, "vertex index 5"});
    check(ascii + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n", {11, {}, "too few values"});
    check(ascii + "0 0 0\n1 0 0 7\n0 1 0\n3 0 1 2\n", {11, {}, "found 4 values"});
    check(ascii + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", {13, {}, "polygon with 2 corners"});
    check(ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n",
          {14, {}, "counts in the header disagree"});
    check(ascii + "0 0 0\n1 0 0\n", {11, {}, "file ends before element 'vertex' row 2 of 3"});
}

TEST(Malformed, TruncatedBinaryPlyNamesTheByteOffset) {
    TempDir dir;
    const std::string p = dir.file("short.ply");
    const std::string header = xyz_ply_header("binary_little_endian", 3, 0);
    test::write_bytes(p, header + std::string(30, '\0'));
    // Vertex 2's y starts at 24 + 4 = 28 bytes into the data, and 2 of its 4 bytes exist.
    expect_parse_error([&] { read_ply(p); }, p,
                       {{}, header.size() + 28, "file ends inside element 'vertex' row 2"});
    test::write_bytes(p, header + std::string(36 + 12, '\0'));
    expect_parse_error([&] { read_ply(p); }, p,
                       {{}, header.size() + 36, "counts in the header disagree"});
    std::string face = xyz_ply_header("binary_little_endian", 1, 1) + std::string(12, '\0');
    test::put(face, std::uint8_t{3});
    for (std::int32_t v : {0, 0, -1}) test::put(face, v);
    test::write_bytes(p, face);
    expect_parse_error([&] { read_ply(p); }, p, {{}, face.size() - 4, "vertex index -1"});
}

TEST(Malformed, KittiErrorsNameTheLineOrByte) {
    TempDir dir;
    const std::string bin = dir.file("bad.bin");
    test::write_bytes(bin, std::string(15, '\0'));
    expect_parse_error([&] { read_kitti_bin(bin); }, bin, {{}, 0, "not a multiple of 16"});
    test::write_bytes(bin, std::string(16 + 15, '\0'));
    expect_parse_error([&] { read_kitti_bin(bin); }, bin, {{}, 16, "not a multiple of 16"});
    test::write_bytes(bin, "");
    expect_parse_error([&] { read_kitti_bin(bin); }, bin, {{}, 0, "empty file"});
    const std::string poses = dir.file("poses.txt");
    const std::string identity = "1 0 0 0 0 1 0 0 0 0 1 0\n";
    test::write_bytes(poses, identity + "1 0 0 0 0 1 0 0 0 0 1\n");
    expect_parse_error([&] { read_kitti_poses(poses); }, poses,
                       {2, {}, "found 11 values, expected 12"});
    test::write_bytes(poses, identity + identity + "1 0 0 0 0 1 0 0 0 0 1 0x\n");
    expect_parse_error([&] { read_kitti_poses(poses); }, poses, {3, {}, "invalid token '0x'"});
    test::write_bytes(poses, "1 0 0 0 0 1.01 0 0 0 0 1 0\n");
    expect_parse_error([&] { read_kitti_poses(poses); }, poses, {1, {}, "not orthonormal"});
    test::write_bytes(poses, "1 0 0 nan 0 1 0 0 0 0 1 0\n");
    expect_parse_error([&] { read_kitti_poses(poses); }, poses,
                       {1, {}, "expected a finite number"});
    test::write_bytes(poses, "\n");
    expect_parse_error([&] { read_kitti_poses(poses); }, poses, {1, {}, "no poses"});
}

TEST(Malformed, TumErrorsNameTheLine) {
    TempDir dir;
    const std::string p = dir.file("t.txt");
    const auto check = [&](const std::string& bytes, const Expected& expected) {
        test::write_bytes(p, bytes);
        expect_parse_error([&] { read_tum(p); }, p, expected);
    };
    check("# header\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0.5 0.5\n", {3, {}, "quaternion norm"});
    check("1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n", {2, {}, "not after the previous one"});
    check("1 0 0 0 0 0 0 1\n0.5 0 0 0 0 0 0 1\n", {2, {}, "not after the previous one"});
    check("1 0 0 0 0 0 1\n", {1, {}, "found 7 values, expected 8"});
    check("1 0 0 inf 0 0 0 1\n", {1, {}, "expected a finite number"});
    check("", {1, {}, "no poses"});
    check("# only a comment\n", {1, {}, "no poses"});
}

TEST(Malformed, EmptyFileIsAnErrorForEveryFormat) {
    TempDir dir;
    for (const auto& reader : kReaders) {
        const std::string& extension = reader.first;
        const auto& read = reader.second;  // not a structured binding: lambdas capture it
        const std::string p = dir.file("empty." + extension);
        test::write_bytes(p, "");
        EXPECT_THROW(read(p), ParseError) << extension;
    }
    test::write_bytes(dir.file("empty.PCD"), "");
    EXPECT_THROW(read_cloud(dir.file("empty.PCD")), ParseError);
}

TEST(Malformed, MissingFileAndDirectoryAreFileErrorsForEveryReader) {
    TempDir dir;
    for (const auto& reader : kReaders) {
        const std::string& extension = reader.first;
        const auto& read = reader.second;  // not a structured binding: lambdas capture it
        const std::string missing = dir.file("missing." + extension);
        expect_file_error([&] { read(missing); }, missing);
        const std::string folder = dir.file("folder." + extension);
        std::filesystem::create_directory(folder);
        expect_file_error([&] { read(folder); }, folder);
    }
}

TEST(Malformed, GarbageMeshIsAParseErrorWithAssimpsMessage) {
    TempDir dir;
    const std::string stl = dir.file("garbage.stl");
    test::write_bytes(stl, std::string("\x01\x02 not a mesh at all \x7f"));
    EXPECT_THROW(read_mesh(stl), ParseError);
    const std::string obj = dir.file("points.obj");
    test::write_bytes(obj, "v 0 0 0\nv 1 0 0\n");
    try {
        read_mesh(obj);
        ADD_FAILURE() << "no error";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.path(), obj);
    }
}

}  // namespace
}  // namespace scantling::io
