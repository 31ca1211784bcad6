#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/kitti.hpp>

#include <bit>

#include "detail/binary_scalar.hpp"
#include "detail/text_lines.hpp"

namespace scantling::io {
namespace {

constexpr std::size_t kRecordBytes = 16;           // float32 x, y, z, reflectance
constexpr double kOrthonormalityTolerance = 1e-3;  // KITTI files print ~7 significant digits
constexpr int kPoseValues = 12;

Eigen::Isometry3d parse_pose(const std::vector<std::string_view>& tokens,
                             const detail::LineContext& where) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c)
            T.matrix()(r, c) = detail::parse_double(tokens[4 * r + c], where);
    }
    const Eigen::Matrix3d R = T.linear();
    const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (error > kOrthonormalityTolerance || R.determinant() < 0) {
        throw ParseError(where.path, {std::nullopt, where.line.number, std::nullopt},
                         "rotation is not orthonormal (max |R^T R - I| = " + std::to_string(error) +
                             ", det = " + std::to_string(R.determinant()) + ")");
    }
    return T;
}

void check_finite_pose(const Eigen::Isometry3d& T, std::size_t i, const std::string& path) {
    if (!T.matrix().allFinite()) {
        throw InputError("write_kitti_poses " + path + ": pose " + std::to_string(i) +
                         " is not finite");
    }
}

}  // namespace

PointCloud read_kitti_bin(const std::string& path) {
    const std::string bytes = detail::read_whole_file(path);
    if (bytes.empty())
        throw ParseError(path, {0, std::nullopt, std::nullopt},
                         "empty file, expected float32 x y z reflectance records");
    const std::size_t n = bytes.size() / kRecordBytes;
    if (bytes.size() % kRecordBytes != 0) {
        throw ParseError(path, {n * kRecordBytes, std::nullopt, std::nullopt},
                         "incomplete record of " + std::to_string(bytes.size() % kRecordBytes) +
                             " bytes: the file size " + std::to_string(bytes.size()) +
                             " is not a multiple of 16 (float32 x y z reflectance)");
    }
    PointCloud cloud;
    cloud.points.resize(n);
    cloud.intensities.resize(n);
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    for (std::size_t i = 0; i < n; ++i) {
        const unsigned char* record = data + i * kRecordBytes;
        for (std::ptrdiff_t k = 0; k < 3; ++k) {
            cloud.points[i][k] = detail::load_scalar<float>(record + 4 * k, std::endian::little);
        }
        cloud.intensities[i] = detail::load_scalar<float>(record + 12, std::endian::little);
    }
    return cloud;
}

void write_kitti_bin(const std::string& path, const PointCloud& cloud) {
    check_consistent(cloud, "write_kitti_bin " + path);
    if (cloud.empty())
        throw InputError("write_kitti_bin " + path +
                         ": the cloud is empty (an empty .bin is not a valid scan)");
    std::string bytes;
    bytes.reserve(cloud.size() * kRecordBytes);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        for (int k = 0; k < 3; ++k)
            detail::append_le(bytes, static_cast<float>(cloud.points[i][k]));
        detail::append_le(bytes, cloud.has_intensities() ? cloud.intensities[i] : 0.0f);
    }
    write_file_atomically(path, [&](std::ostream& out) {
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    });
}

std::vector<Eigen::Isometry3d> read_kitti_poses(const std::string& path) {
    const std::string text = detail::read_whole_file(path);
    std::vector<Eigen::Isometry3d> poses;
    detail::LineReader reader(text);
    detail::TextLine line{{}, 1, 0};
    std::vector<std::string_view> tokens;
    while (reader.next(line)) {
        if (detail::trim(line.text).empty()) continue;
        const detail::LineContext where{path, line};
        detail::split_exactly(line.text, tokens, kPoseValues, where, "row-major 3x4 pose");
        poses.push_back(parse_pose(tokens, where));
    }
    if (poses.empty())
        throw ParseError(path, {std::nullopt, line.number, std::nullopt},
                         "no poses, expected lines of 12 numbers");
    return poses;
}

void write_kitti_poses(const std::string& path, std::span<const Eigen::Isometry3d> poses) {
    std::string text;
    for (std::size_t i = 0; i < poses.size(); ++i) {
        check_finite_pose(poses[i], i, path);
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 4; ++c) {
                detail::append_number(text, poses[i].matrix()(r, c));
                text += (r == 2 && c == 3) ? '\n' : ' ';
            }
        }
    }
    write_file_atomically(path, [&](std::ostream& out) {
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
    });
}

}  // namespace scantling::io
