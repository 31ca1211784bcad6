#include "detail/cloud_builder.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace scantling::io::detail {
namespace {

constexpr double kAbsoluteTimeThresholdS = 1e5;  // > 1 day: a clock reading, not an offset

bool has_target(const std::vector<CloudTarget>& targets, std::initializer_list<CloudTarget> any) {
    return std::any_of(any.begin(), any.end(), [&](CloudTarget t) {
        return std::find(targets.begin(), targets.end(), t) != targets.end();
    });
}

}  // namespace

CloudTarget cloud_target(std::string_view name) {
    using T = CloudTarget;
    static constexpr std::pair<std::string_view, CloudTarget> kNames[] = {
        {"x", T::kX},
        {"y", T::kY},
        {"z", T::kZ},
        {"normal_x", T::kNormalX},
        {"normal_y", T::kNormalY},
        {"normal_z", T::kNormalZ},
        {"nx", T::kNormalX},
        {"ny", T::kNormalY},
        {"nz", T::kNormalZ},
        {"intensity", T::kIntensity},
        {"scalar_intensity", T::kIntensity},
        {"reflectance", T::kIntensity},
        {"ring", T::kRing},
        {"time", T::kTime},
        {"t", T::kTime},
        {"timestamp", T::kTime},
        {"red", T::kRed},
        {"green", T::kGreen},
        {"blue", T::kBlue},
        {"rgb", T::kPackedRgb},
        {"rgba", T::kPackedRgb},
    };
    for (const auto& [known, target] : kNames) {
        if (known == name) return target;
    }
    return T::kNone;
}

CloudBuilder::CloudBuilder(std::size_t n, const std::vector<CloudTarget>& targets) {
    using T = CloudTarget;
    const Eigen::Vector3d nan_point =
        Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    cloud_.points.assign(n, nan_point);
    if (has_target(targets, {T::kNormalX, T::kNormalY, T::kNormalZ})) {
        cloud_.normals.assign(n, Eigen::Vector3d::Zero());
    }
    if (has_target(targets, {T::kIntensity})) cloud_.intensities.assign(n, 0.0f);
    if (has_target(targets, {T::kRing})) cloud_.rings.assign(n, 0);
    if (has_target(targets, {T::kTime})) times_s_.assign(n, 0.0);
    if (has_target(targets, {T::kRed, T::kGreen, T::kBlue, T::kPackedRgb})) {
        cloud_.colors.assign(n, Rgb8::Zero());
    }
}

PointCloud CloudBuilder::finish() {
    if (!times_s_.empty()) {
        double earliest = std::numeric_limits<double>::infinity();
        for (const double t : times_s_)
            earliest = std::isfinite(t) ? std::min(earliest, t) : earliest;
        const bool absolute = std::isfinite(earliest) && earliest > kAbsoluteTimeThresholdS;
        cloud_.stamp_s = absolute ? earliest : 0.0;
        cloud_.times_s.resize(times_s_.size());
        for (std::size_t i = 0; i < times_s_.size(); ++i) {
            cloud_.times_s[i] = static_cast<float>(times_s_[i] - cloud_.stamp_s);
        }
    }
    return std::move(cloud_);
}

std::uint32_t packed_rgb(float value) {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof(bits));
    return bits;
}

float rgb_as_float(const Rgb8& color) {
    const std::uint32_t bits =
        (std::uint32_t{color[0]} << 16) | (std::uint32_t{color[1]} << 8) | std::uint32_t{color[2]};
    float value;
    std::memcpy(&value, &bits, sizeof(value));
    return value;
}

}  // namespace scantling::io::detail
