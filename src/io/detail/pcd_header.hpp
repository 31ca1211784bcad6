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
    std::size_t point_step = 0;  ///< bytes per point record (binary layout)
    PcdDataKind data = PcdDataKind::kBinary;
    std::size_t data_offset = 0;  ///< first byte after the DATA line
    int data_line = 0;            ///< line number of the DATA line
};

/// Parses the header at the start of `bytes`. Throws ParseError naming `path` and the line:
/// empty file, unknown key, missing FIELDS/SIZE/TYPE/WIDTH/HEIGHT/POINTS/DATA, lists of
/// different lengths, unsupported TYPE/SIZE pairs, POINTS != WIDTH * HEIGHT, unknown DATA.
/// VERSION and VIEWPOINT are checked for form and otherwise ignored (points are not moved by
/// the viewpoint, as in PCL); COUNT defaults to 1.
PcdHeader parse_pcd_header(const std::string& bytes, const std::string& path);

/// A field that feeds the cloud: value i lives at byte base + i * stride (binary layouts) or
/// at token `token` of line i (ascii).
struct PcdColumn {
    CloudTarget target = CloudTarget::kNone;
    const PcdField* field = nullptr;
    std::size_t base = 0;
    std::size_t stride = 0;
    std::size_t token = 0;
};

/// The mapped fields in file order. Throws ParseError when x, y or z is missing or a mapped
/// field has COUNT != 1 (or a packed rgb SIZE != 4).
std::vector<PcdColumn> map_pcd_columns(const PcdHeader& header, const std::string& path);
std::vector<CloudTarget> column_targets(const std::vector<PcdColumn>& columns);

/// Body of a DATA ascii file: one point per line, COUNT values per field.
PointCloud read_pcd_ascii(const std::string& bytes, const PcdHeader& header,
                          const std::vector<PcdColumn>& columns, const std::string& path);

}  // namespace scantling::io::detail
