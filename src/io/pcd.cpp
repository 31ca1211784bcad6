#include <scantling/core/error.hpp>
#include <scantling/io/pcd.hpp>

#include <algorithm>
#include <bit>

#include "detail/cloud_builder.hpp"
#include "detail/lzf.hpp"
#include "detail/pcd_header.hpp"
#include "detail/text_lines.hpp"

namespace scantling::io {
namespace {

using detail::CloudTarget;
using detail::PcdField;
using detail::PcdHeader;
using Column = detail::PcdColumn;

constexpr double kNanosecondsToSeconds = 1e-9;
// An LZF back reference of 3 bytes expands to at most 264: nothing compresses better.
constexpr std::size_t kMaxLzfRatio = 88;

double time_scale(const PcdField& field) {
    return detail::is_integer(field.type) ? kNanosecondsToSeconds : 1.0;
}

template <typename T>
void decode_typed(const unsigned char* data, const Column& c, std::size_t n, double scale,
                  detail::CloudBuilder& builder) {
    const unsigned char* value = data + c.base;
    for (std::size_t i = 0; i < n; ++i, value += c.stride) {
        builder.set(c.target, i, scale * detail::load_scalar<T>(value, std::endian::little));
    }
}

// The type switch sits outside the per-point loop: this is the hot path of binary files.
void decode_column(const unsigned char* data, const Column& c, std::size_t n,
                   detail::CloudBuilder& builder) {
    using S = detail::ScalarType;
    if (c.target == CloudTarget::kPackedRgb) {
        for (std::size_t i = 0; i < n; ++i) {
            builder.set_packed_rgb(i, detail::load_scalar<std::uint32_t>(
                                          data + c.base + i * c.stride, std::endian::little));
        }
        return;
    }
    const double s = c.target == CloudTarget::kTime ? time_scale(*c.field) : 1.0;
    switch (c.field->type) {
        case S::kI8:
            return decode_typed<std::int8_t>(data, c, n, s, builder);
        case S::kU8:
            return decode_typed<std::uint8_t>(data, c, n, s, builder);
        case S::kI16:
            return decode_typed<std::int16_t>(data, c, n, s, builder);
        case S::kU16:
            return decode_typed<std::uint16_t>(data, c, n, s, builder);
        case S::kI32:
            return decode_typed<std::int32_t>(data, c, n, s, builder);
        case S::kU32:
            return decode_typed<std::uint32_t>(data, c, n, s, builder);
        case S::kI64:
            return decode_typed<std::int64_t>(data, c, n, s, builder);
        case S::kU64:
            return decode_typed<std::uint64_t>(data, c, n, s, builder);
        case S::kF32:
            return decode_typed<float>(data, c, n, s, builder);
        case S::kF64:
            return decode_typed<double>(data, c, n, s, builder);
    }
}

/// `compressed`: PCL stores binary_compressed data field by field (all x, then all y, ...).
PointCloud decode_binary(const unsigned char* data, const PcdHeader& header,
                         std::vector<Column> columns, bool column_major) {
    detail::CloudBuilder builder(header.points, detail::column_targets(columns));
    for (Column& c : columns) {
        c.base = column_major ? c.field->offset * header.points : c.field->offset;
        c.stride = column_major ? c.field->size * c.field->count : header.point_step;
        decode_column(data, c, header.points, builder);
    }
    return builder.finish();
}

[[noreturn]] void fail_short(const std::string& path, std::size_t file_size,
                             const std::string& what) {
    throw ParseError(path, {file_size, std::nullopt, std::nullopt}, "file ends early: " + what);
}

PointCloud read_binary(const std::string& bytes, const PcdHeader& header,
                       std::vector<Column> columns, const std::string& path) {
    const std::size_t available = bytes.size() - header.data_offset;
    if (header.points > available / header.point_step) {
        fail_short(path, bytes.size(),
                   "expected " + std::to_string(header.points) + " points of " +
                       std::to_string(header.point_step) + " bytes from byte " +
                       std::to_string(header.data_offset) + ", found " + std::to_string(available) +
                       " bytes");
    }
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data()) + header.data_offset;
    return decode_binary(data, header, std::move(columns), false);
}

PointCloud read_compressed(const std::string& bytes, const PcdHeader& header,
                           std::vector<Column> columns, const std::string& path) {
    const std::size_t start = header.data_offset;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    if (bytes.size() - start < 8)
        fail_short(path, bytes.size(), "expected the 8-byte compressed block sizes");
    const std::size_t compressed =
        detail::load_scalar<std::uint32_t>(data + start, std::endian::little);
    const std::size_t raw =
        detail::load_scalar<std::uint32_t>(data + start + 4, std::endian::little);
    if (header.points > 0 && raw / header.points != header.point_step) {
        throw ParseError(path, {start + 4, std::nullopt, std::nullopt},
                         "uncompressed size " + std::to_string(raw) + ", expected POINTS * " +
                             std::to_string(header.point_step) + " bytes");
    }
    if (compressed > bytes.size() - start - 8) {
        fail_short(path, bytes.size(),
                   "compressed block of " + std::to_string(compressed) + " bytes starts at byte " +
                       std::to_string(start + 8));
    }
    if (raw > compressed * kMaxLzfRatio) {
        throw ParseError(path, {start + 4, std::nullopt, std::nullopt},
                         "uncompressed size " + std::to_string(raw) + " is impossible for " +
                             std::to_string(compressed) + " compressed bytes");
    }
    std::vector<std::uint8_t> unpacked(header.points * header.point_step);
    detail::lzf_decompress({data + start + 8, compressed}, unpacked, path, start + 8);
    return decode_binary(unpacked.data(), header, std::move(columns), true);
}

}  // namespace

PointCloud read_pcd(const std::string& path) {
    const std::string bytes = detail::read_whole_file(path);
    const PcdHeader header = detail::parse_pcd_header(bytes, path);
    std::vector<Column> columns = detail::map_pcd_columns(header, path);
    switch (header.data) {
        case detail::PcdDataKind::kAscii:
            return detail::read_pcd_ascii(bytes, header, columns, path);
        case detail::PcdDataKind::kBinary:
            return read_binary(bytes, header, std::move(columns), path);
        case detail::PcdDataKind::kBinaryCompressed:
            return read_compressed(bytes, header, std::move(columns), path);
    }
    return {};
}

}  // namespace scantling::io
