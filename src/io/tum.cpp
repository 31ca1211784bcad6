#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/tum.hpp>

#include <cmath>

#include "detail/text_lines.hpp"

namespace scantling::io {
namespace {

constexpr double kUnitNormTolerance = 1e-3;  // files print quaternions with ~6-9 digits
constexpr int kTumValues = 8;

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
    throw ParseError(path, {std::nullopt, line, std::nullopt}, what);
}

StampedPose parse_line(const std::vector<std::string_view>& tokens,
                       const detail::LineContext& where) {
    double v[kTumValues];
    for (int k = 0; k < kTumValues; ++k) v[k] = detail::parse_double(tokens[k], where);
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);  // file order: qx qy qz qw
    const double norm = q.norm();
    if (std::abs(norm - 1.0) > kUnitNormTolerance) {
        fail(where.path, where.line.number,
             "quaternion norm " + std::to_string(norm) + ", expected 1 within 1e-3");
    }
    StampedPose pose;
    pose.stamp_s = v[0];
    pose.T_world_body.linear() = q.normalized().toRotationMatrix();
    pose.T_world_body.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    return pose;
}

void check_writable(std::span<const StampedPose> poses, const std::string& path) {
    for (std::size_t i = 0; i < poses.size(); ++i) {
        const std::string where = "write_tum " + path + ": pose " + std::to_string(i);
        if (!std::isfinite(poses[i].stamp_s) || !poses[i].T_world_body.matrix().allFinite()) {
            throw InputError(where + " is not finite");
        }
        if (i > 0 && !(poses[i].stamp_s > poses[i - 1].stamp_s)) {
            throw InputError(where + ": time stamps must increase strictly");
        }
    }
}

void append_pose(std::string& text, const StampedPose& pose) {
    Eigen::Quaterniond q(pose.T_world_body.linear());
    if (q.w() < 0) q.coeffs() = -q.coeffs();  // same rotation; one canonical text
    const Eigen::Vector3d t = pose.T_world_body.translation();
    const double values[kTumValues] = {pose.stamp_s, t.x(), t.y(), t.z(),
                                       q.x(),        q.y(), q.z(), q.w()};
    for (int k = 0; k < kTumValues; ++k) {
        detail::append_number(text, values[k]);
        text += k + 1 < kTumValues ? ' ' : '\n';
    }
}

}  // namespace

std::vector<StampedPose> read_tum(const std::string& path) {
    const std::string text = detail::read_whole_file(path);
    std::vector<StampedPose> poses;
    detail::LineReader reader(text);
    detail::TextLine line{{}, 1, 0};
    std::vector<std::string_view> tokens;
    while (reader.next(line)) {
        const std::string_view values = detail::strip_comment(line.text);
        if (values.empty()) continue;
        const detail::LineContext where{path, line};
        detail::split_exactly(values, tokens, kTumValues, where, "timestamp tx ty tz qx qy qz qw");
        StampedPose pose = parse_line(tokens, where);
        if (!poses.empty() && !(pose.stamp_s > poses.back().stamp_s)) {
            fail(path, line.number,
                 "time stamp " + std::string(tokens[0]) + " is not after the previous one");
        }
        poses.push_back(pose);
    }
    if (poses.empty())
        fail(path, line.number, "no poses, expected lines 'timestamp tx ty tz qx qy qz qw'");
    return poses;
}

void write_tum(const std::string& path, std::span<const StampedPose> poses) {
    check_writable(poses, path);
    std::string text = "# timestamp tx ty tz qx qy qz qw\n";
    for (const StampedPose& pose : poses) append_pose(text, pose);
    write_file_atomically(path, [&](std::ostream& out) {
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
    });
}

}  // namespace scantling::io
