#pragma once
// Maps the per-point fields of PCD and PLY files onto PointCloud members, so both readers
// share one naming convention and one set of conversions.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include <scantling/core/point_cloud.hpp>

namespace scantling::io::detail {

/// The PointCloud member a file field feeds; kNone = skipped (curvature, padding, ...).
enum class CloudTarget : std::uint8_t {
    kNone,
    kX,
    kY,
    kZ,
    kNormalX,
    kNormalY,
    kNormalZ,
    kIntensity,
    kRing,
    kTime,
    kRed,
    kGreen,
    kBlue,
    kPackedRgb,
};

/// Target of a field name: x y z; normal_x.. or nx..; intensity / scalar_intensity /
/// reflectance; ring; time / t / timestamp; red green blue (PLY), rgb / rgba (PCD, packed).
CloudTarget cloud_target(std::string_view field_name);

/// Collects values for `num_points` points; only the fields in `targets` are allocated.
class CloudBuilder {
  public:
    CloudBuilder(std::size_t num_points, const std::vector<CloudTarget>& targets);

    /// Stores `value` for point `i`. Times are in seconds; colour channels in 0..255.
    void set(CloudTarget target, std::size_t i, double value);
    /// 0x00RRGGBB (PCL's packed rgb, alpha ignored).
    void set_packed_rgb(std::size_t i, std::uint32_t value);

    /// The cloud. Absolute time stamps (> 1e5 s, e.g. UNIX time) become `stamp_s` = earliest
    /// stamp plus float offsets, which keeps microsecond resolution.
    PointCloud finish();

  private:
    PointCloud cloud_;
    std::vector<double> times_s_;
};

inline std::uint8_t to_channel(double value) {
    if (!(value > 0.0)) return 0;
    return static_cast<std::uint8_t>(std::lround(std::min(value, 255.0)));
}

inline std::uint16_t to_ring(double value) {
    if (!(value > 0.0)) return 0;
    return static_cast<std::uint16_t>(std::min(value, 65535.0));
}

// Inline: the readers call set() once per value with a loop-invariant target, so the compiler
// can hoist the switch out of their loops.
inline void CloudBuilder::set(CloudTarget target, std::size_t i, double value) {
    using T = CloudTarget;
    switch (target) {
        case T::kX:
            cloud_.points[i].x() = value;
            break;
        case T::kY:
            cloud_.points[i].y() = value;
            break;
        case T::kZ:
            cloud_.points[i].z() = value;
            break;
        case T::kNormalX:
            cloud_.normals[i].x() = value;
            break;
        case T::kNormalY:
            cloud_.normals[i].y() = value;
            break;
        case T::kNormalZ:
            cloud_.normals[i].z() = value;
            break;
        case T::kIntensity:
            cloud_.intensities[i] = static_cast<float>(value);
            break;
        case T::kRing:
            cloud_.rings[i] = to_ring(value);
            break;
        case T::kTime:
            times_s_[i] = value;
            break;
        case T::kRed:
            cloud_.colors[i][0] = to_channel(value);
            break;
        case T::kGreen:
            cloud_.colors[i][1] = to_channel(value);
            break;
        case T::kBlue:
            cloud_.colors[i][2] = to_channel(value);
            break;
        case T::kPackedRgb:
            set_packed_rgb(i, static_cast<std::uint32_t>(value));
            break;
        case T::kNone:
            break;
    }
}

inline void CloudBuilder::set_packed_rgb(std::size_t i, std::uint32_t value) {
    cloud_.colors[i] = Rgb8(static_cast<std::uint8_t>((value >> 16) & 0xffu),
                            static_cast<std::uint8_t>((value >> 8) & 0xffu),
                            static_cast<std::uint8_t>(value & 0xffu));
}

/// The 4 bytes of a packed rgb/rgba value as 0xAARRGGBB (PCL stores it in a float or uint32).
std::uint32_t packed_rgb(float value);
float rgb_as_float(const Rgb8& color);

}  // namespace scantling::io::detail
