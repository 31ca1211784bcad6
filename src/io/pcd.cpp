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
constexpr std::size_t kCompressedSizesBytes = 8;  // uint32 compressed, uint32 uncompressed

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

// validate_layout (in parse_pcd_header) checked that POINTS x point_step bytes are present.
PointCloud read_binary(const std::string& bytes, const PcdHeader& header,
                       std::vector<Column> columns) {
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data()) + header.data_offset;
    return decode_binary(data, header, std::move(columns), false);
}

// validate_layout checked the block sizes: the uncompressed size is POINTS x point_step and at
// most 88 times the compressed block, which lies inside the file.
PointCloud read_compressed(const std::string& bytes, const PcdHeader& header,
                           std::vector<Column> columns, const std::string& path) {
    const std::size_t start = header.data_offset + kCompressedSizesBytes;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data()) + start;
    std::vector<std::uint8_t> unpacked(header.points * header.point_step);
    detail::lzf_decompress({data, header.compressed_size}, unpacked, path, start);
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
            return read_binary(bytes, header, std::move(columns));
        case detail::PcdDataKind::kBinaryCompressed:
            return read_compressed(bytes, header, std::move(columns), path);
    }
    return {};
}

}  // namespace scantling::io
