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
};

/// Throws ParseError naming `path` and the line: empty file, first line not "ply", unknown
/// or missing format, unknown type or keyword, property outside an element, no end_header.
PlyHeader parse_ply_header(const std::string& bytes, const std::string& path);

const PlyElement* find_element(const PlyHeader& header, const std::string& name);

}  // namespace scantling::io::detail
