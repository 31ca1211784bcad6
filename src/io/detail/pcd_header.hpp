#pragma once
// PCD header (PCL's format, v0.7): the keys up to and including the DATA line.

#include <cstddef>
#include <string>
#include <vector>

#include "binary_scalar.hpp"
#include "cloud_builder.hpp"

namespace scantling::io::detail {

struct PcdField {
    std::string name;
    char type_char = 'F';  ///< 'F', 'I' or 'U' as written in the file
    ScalarType type = ScalarType::kF32;
    std::size_t size = 4;    ///< bytes per element
    std::size_t count = 1;   ///< elements per point (histograms have count > 1)
    std::size_t offset = 0;  ///< byte offset of the field inside one point record
};

enum class PcdDataKind { kAscii, kBinary, kBinaryCompressed };

struct PcdHeader {
    std::vector<PcdField> fields;
    std::size_t width = 0;
    std::size_t height = 0;
    std::size_t points = 0;
    std::size_t point_step = 0;        ///< bytes per point record (binary layout)
    std::size_t values_per_point = 0;  ///< sum of COUNT: values on one ascii line
    PcdDataKind data = PcdDataKind::kBinary;
    std::size_t data_offset = 0;      ///< first byte after the DATA line
    std::size_t compressed_size = 0;  ///< binary_compressed: LZF bytes after the 8-byte sizes
    int fields_line = 0;              ///< line numbers, for messages
    int count_line = 0;               ///< COUNT, or SIZE when COUNT is absent
    int points_line = 0;
    int data_line = 0;
};

/// Parses the header at the start of `bytes` and validates its layout (validate_layout).
/// Throws ParseError naming `path` and the line: empty file, unknown key, missing
/// FIELDS/SIZE/TYPE/WIDTH/HEIGHT/POINTS/DATA, lists of different lengths, unsupported TYPE/SIZE
/// pairs, COUNT 0, unknown DATA. VERSION and VIEWPOINT are checked for form and otherwise
/// ignored (points are not moved by the viewpoint, as in PCL); COUNT defaults to 1.
PcdHeader parse_pcd_header(const std::string& bytes, const std::string& path);

/// The one place where the sizes a header implies are computed and bounded by the data, before
/// anything is allocated or divided: field offsets and point_step (SIZE x COUNT summed, checked
/// for overflow), POINTS == WIDTH * HEIGHT (checked), field names unique ("_" padding aside),
/// and the data: binary holds POINTS x point_step bytes, binary_compressed has sizes that agree
/// with them and fit the file, ascii has room for POINTS lines of values. Bytes after binary
/// data are refused unless they are up to 64 KiB of zeros or whitespace (old PCL writers pad
/// files to a page). Throws ParseError naming the line (header) or the byte (data).
void validate_layout(PcdHeader& header, const std::string& bytes, const std::string& path);

/// Walks an ascii body without storing it and throws where it first disagrees with the header:
/// a line with other than values_per_point values, a line after POINTS rows, or the end of the
/// data before POINTS rows. Returns when the body has exactly POINTS well-formed rows.
void check_ascii_rows(const std::string& bytes, const PcdHeader& header, const std::string& path);

/// A field that feeds the cloud: value i lives at byte base + i * stride (binary layouts) or
/// at token `token` of line i (ascii).
struct PcdColumn {
    CloudTarget target = CloudTarget::kNone;
    const PcdField* field = nullptr;
    std::size_t base = 0;
    std::size_t stride = 0;
    std::size_t token = 0;
};

/// The mapped fields in file order. Throws ParseError when x, y or z is missing, two fields
/// feed the same cloud member (x and x, or intensity and reflectance) or a mapped field has
/// COUNT != 1 (or a packed rgb SIZE != 4).
std::vector<PcdColumn> map_pcd_columns(const PcdHeader& header, const std::string& path);
std::vector<CloudTarget> column_targets(const std::vector<PcdColumn>& columns);

/// Body of a DATA ascii file: one point per line, COUNT values per field.
PointCloud read_pcd_ascii(const std::string& bytes, const PcdHeader& header,
                          const std::vector<PcdColumn>& columns, const std::string& path);

}  // namespace scantling::io::detail
