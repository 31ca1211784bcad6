#pragma once
// PLY header: magic, format, elements and their properties, up to end_header.

#include <bit>
#include <cstddef>
#include <string>
#include <vector>

#include "binary_scalar.hpp"

namespace scantling::io::detail {

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyProperty {
    std::string name;
    ScalarType type = ScalarType::kF32;  ///< value type (item type for lists)
    bool is_list = false;
    ScalarType count_type = ScalarType::kU8;  ///< lists only
    int line = 0;                             ///< header line declaring the property
};

struct PlyElement {
    std::string name;
    std::size_t count = 0;
    std::vector<PlyProperty> properties;
    int line = 0;  ///< header line declaring the element
};

struct PlyHeader {
    PlyFormat format = PlyFormat::kAscii;
    std::vector<PlyElement> elements;
    std::size_t data_offset = 0;  ///< first byte after the end_header line
    int data_line = 0;            ///< line number of the first data line (ascii)
    /// False when the declared rows need more bytes than follow the header (validate_layout):
    /// the body reader then walks the data without storing it, to say where it ends.
    bool counts_fit = true;
};

/// Throws ParseError naming `path` and the line: empty file, first line not "ply", unknown
/// or missing format, unknown type or keyword, property outside an element, no end_header,
/// and what validate_layout refuses.
PlyHeader parse_ply_header(const std::string& bytes, const std::string& path);

/// The one place where the header's sizes are checked against the data: element names and the
/// property names of an element are unique (a repeated one would be read silently), and the
/// rows the elements declare (count x the least bytes a row takes: the sizes of its scalars and
/// list counts in binary, two characters a value in ascii), summed with overflow checks, fit in
/// the `data_bytes` after the header, which sets `counts_fit`. Nothing is allocated from a count
/// before this check passes.
void validate_layout(PlyHeader& header, std::size_t data_bytes, const std::string& path);

const PlyElement* find_element(const PlyHeader& header, const std::string& name);

}  // namespace scantling::io::detail
