// validate_layout: every size a PCD header implies, computed with overflow checks and bounded by
// the bytes present before the readers allocate or divide anything (issue 10: a COUNT of 2^62
// wrapped point_step to 0 and killed every cloud-reading command with SIGFPE).
#include <scantling/core/checked_arithmetic.hpp>
#include <scantling/core/error.hpp>

#include <algorithm>
#include <bit>
#include <set>
#include <string_view>

#include "detail/pcd_header.hpp"

namespace scantling::io::detail {
namespace {

// PCL's writers up to 1.8 stretch a binary file to getpagesize() + data bytes, which leaves up
// to a page of zeros after the data; 64 KiB is the largest page size in use (arm64, ppc64).
constexpr std::size_t kMaxPaddingBytes = 64 * 1024;
constexpr std::size_t kCompressedSizesBytes = 8;  // uint32 compressed, uint32 uncompressed
// An LZF back reference of 3 bytes expands to at most 264: nothing compresses better.
constexpr std::uint64_t kMaxLzfRatio = 88;
// An ascii value takes a character and a separator (the last line may lack its newline).
constexpr std::uint64_t kMinAsciiBytesPerValue = 2;

[[noreturn]] void fail_line(const std::string& path, int line, const std::string& what) {
    throw ParseError(path, {std::nullopt, line, std::nullopt}, what);
}

[[noreturn]] void fail_byte(const std::string& path, std::uint64_t byte, const std::string& what) {
    throw ParseError(path, {byte, std::nullopt, std::nullopt}, what);
}

void check_unique_names(const PcdHeader& header, const std::string& path) {
    std::set<std::string_view> seen;
    for (const PcdField& field : header.fields) {
        if (field.name == "_") continue;  // PCL names every padding field "_"
        if (!seen.insert(field.name).second) {
            fail_line(path, header.fields_line,
                      "field '" + field.name + "' appears twice in FIELDS, expected unique names");
        }
    }
}

/// Offsets inside the point record, point_step = sum of SIZE x COUNT, values_per_point = sum of
/// COUNT (<= point_step since every SIZE >= 1, so it cannot overflow once point_step did not).
void assign_offsets(PcdHeader& header, const std::string& path) {
    std::uint64_t offset = 0;
    header.values_per_point = 0;
    for (PcdField& field : header.fields) {
        field.offset = offset;
        const auto field_bytes = checked_multiply(field.size, field.count);
        const auto end = field_bytes ? checked_add(offset, *field_bytes) : std::nullopt;
        if (!end) {
            fail_line(path, header.count_line,
                      "field '" + field.name + "' has SIZE " + std::to_string(field.size) +
                          " x COUNT " + std::to_string(field.count) +
                          ": the point record exceeds 2^64 bytes");
        }
        offset = *end;
        header.values_per_point += field.count;
    }
    header.point_step = offset;
}

void check_points(const PcdHeader& header, const std::string& path) {
    const auto product = checked_multiply(header.width, header.height);
    if (product && *product == header.points) return;
    fail_line(path, header.points_line,
              "POINTS = " + std::to_string(header.points) +
                  ", expected WIDTH * HEIGHT = " + std::to_string(header.width) + " * " +
                  std::to_string(header.height) + (product ? "" : " (which exceeds 2^64)"));
}

/// Bytes after the data: harmless page padding, or a sign that the header describes less data
/// than the file holds (a SIZE, COUNT or POINTS that would be decoded with the wrong stride).
void check_tail(const std::string& bytes, std::size_t end, const std::string& path) {
    const std::string_view tail = std::string_view(bytes).substr(end);
    const bool padding =
        tail.size() <= kMaxPaddingBytes && std::all_of(tail.begin(), tail.end(), [](char c) {
            return c == '\0' || c == '\n' || c == '\r' || c == ' ';
        });
    if (padding) return;
    fail_byte(path, end,
              std::to_string(tail.size()) +
                  " bytes follow the declared data: POINTS, SIZE or COUNT in the header "
                  "disagree with the data");
}

void check_binary(const PcdHeader& header, const std::string& bytes, const std::string& path) {
    const std::uint64_t available = bytes.size() - header.data_offset;
    const auto data_bytes = checked_multiply_within(header.points, header.point_step, available);
    if (!data_bytes) {
        fail_byte(path, bytes.size(),
                  "file ends early: expected " + std::to_string(header.points) + " points of " +
                      std::to_string(header.point_step) + " bytes from byte " +
                      std::to_string(header.data_offset) + ", found " + std::to_string(available) +
                      " bytes");
    }
    check_tail(bytes, header.data_offset + *data_bytes, path);
}

std::uint32_t load_u32(const std::string& bytes, std::size_t at) {
    return load_scalar<std::uint32_t>(reinterpret_cast<const unsigned char*>(bytes.data()) + at,
                                      std::endian::little);
}

void check_compressed(PcdHeader& header, const std::string& bytes, const std::string& path) {
    const std::size_t start = header.data_offset;
    if (bytes.size() - start < kCompressedSizesBytes) {
        fail_byte(path, bytes.size(),
                  "file ends early: expected the 8-byte compressed block sizes");
    }
    const std::uint64_t compressed = load_u32(bytes, start);
    const std::uint64_t raw = load_u32(bytes, start + 4);
    const auto expected_raw = checked_multiply(header.points, header.point_step);
    if (!expected_raw || raw != *expected_raw) {
        fail_byte(path, start + 4,
                  "uncompressed size " + std::to_string(raw) + ", expected POINTS * " +
                      std::to_string(header.point_step) + " bytes");
    }
    if (compressed > bytes.size() - start - kCompressedSizesBytes) {
        fail_byte(path, bytes.size(),
                  "file ends early: compressed block of " + std::to_string(compressed) +
                      " bytes starts at byte " + std::to_string(start + kCompressedSizesBytes));
    }
    if (raw > compressed * kMaxLzfRatio) {
        fail_byte(path, start + 4,
                  "uncompressed size " + std::to_string(raw) + " is impossible for " +
                      std::to_string(compressed) + " compressed bytes");
    }
    header.compressed_size = compressed;
    check_tail(bytes, start + kCompressedSizesBytes + compressed, path);
}

/// A cheap bound first; only a body that fails it is walked, to say where it goes wrong.
void check_ascii(const PcdHeader& header, const std::string& bytes, const std::string& path) {
    if (header.points == 0) return;  // the reader refuses any line as "more points"
    const std::uint64_t available = bytes.size() - header.data_offset;
    const auto row_bytes = checked_multiply(header.values_per_point, kMinAsciiBytesPerValue);
    const auto needed = row_bytes ? checked_multiply(header.points, *row_bytes) : std::nullopt;
    if (needed && *needed <= available + 1) return;
    check_ascii_rows(bytes, header, path);
    fail_line(path, header.data_line,
              "POINTS = " + std::to_string(header.points) + " lines of " +
                  std::to_string(header.values_per_point) + " values cannot fit in the " +
                  std::to_string(available) + " bytes of data");
}

}  // namespace

void validate_layout(PcdHeader& header, const std::string& bytes, const std::string& path) {
    check_unique_names(header, path);
    assign_offsets(header, path);
    check_points(header, path);
    switch (header.data) {
        case PcdDataKind::kAscii:
            return check_ascii(header, bytes, path);
        case PcdDataKind::kBinary:
            return check_binary(header, bytes, path);
        case PcdDataKind::kBinaryCompressed:
            return check_compressed(header, bytes, path);
    }
}

}  // namespace scantling::io::detail
