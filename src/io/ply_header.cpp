#include <scantling/core/checked_arithmetic.hpp>
#include <scantling/core/error.hpp>

#include <optional>
#include <set>
#include <string_view>

#include "detail/ply_header.hpp"
#include "detail/text_lines.hpp"

namespace scantling::io::detail {
namespace {

using Tokens = std::vector<std::string_view>;

// An ascii value takes a character and a separator (space or newline).
constexpr std::uint64_t kMinAsciiBytesPerValue = 2;

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
    throw ParseError(path, {std::nullopt, line, std::nullopt}, what);
}

std::optional<ScalarType> ply_type(std::string_view name) {
    using S = ScalarType;
    static constexpr std::pair<std::string_view, ScalarType> kTypes[] = {
        {"char", S::kI8},   {"int8", S::kI8},     {"uchar", S::kU8},   {"uint8", S::kU8},
        {"short", S::kI16}, {"int16", S::kI16},   {"ushort", S::kU16}, {"uint16", S::kU16},
        {"int", S::kI32},   {"int32", S::kI32},   {"uint", S::kU32},   {"uint32", S::kU32},
        {"float", S::kF32}, {"float32", S::kF32}, {"double", S::kF64}, {"float64", S::kF64},
        {"int64", S::kI64}, {"uint64", S::kU64},
    };
    for (const auto& [known, type] : kTypes) {
        if (known == name) return type;
    }
    return std::nullopt;
}

ScalarType require_type(std::string_view name, const std::string& path, int line) {
    const auto type = ply_type(name);
    if (!type) fail(path, line, "unknown PLY type '" + std::string(name) + "'");
    return *type;
}

PlyFormat parse_format(const Tokens& tokens, const std::string& path, const TextLine& line) {
    expect_token_count(tokens, 3, {path, line},
                       "format <ascii|binary_little_endian|binary_big_endian> 1.0");
    if (tokens[2] != "1.0")
        fail(path, line.number, "unsupported PLY version " + std::string(tokens[2]));
    if (tokens[1] == "ascii") return PlyFormat::kAscii;
    if (tokens[1] == "binary_little_endian") return PlyFormat::kBinaryLittleEndian;
    if (tokens[1] == "binary_big_endian") return PlyFormat::kBinaryBigEndian;
    fail(path, line.number,
         "unknown PLY format '" + std::string(tokens[1]) +
             "', expected ascii, binary_little_endian or binary_big_endian");
}

PlyProperty parse_property(const Tokens& tokens, const std::string& path, const TextLine& line) {
    PlyProperty property;
    if (tokens.size() > 1 && tokens[1] == "list") {
        expect_token_count(tokens, 5, {path, line},
                           "property list <count type> <item type> <name>");
        property.is_list = true;
        property.count_type = require_type(tokens[2], path, line.number);
        if (!is_integer(property.count_type))
            fail(path, line.number, "list count type must be an integer type");
        property.type = require_type(tokens[3], path, line.number);
        property.name = tokens[4];
        property.line = line.number;
        return property;
    }
    expect_token_count(tokens, 3, {path, line}, "property <type> <name>");
    property.type = require_type(tokens[1], path, line.number);
    property.name = tokens[2];
    property.line = line.number;
    return property;
}

PlyElement parse_element(const Tokens& tokens, const std::string& path, const TextLine& line) {
    expect_token_count(tokens, 3, {path, line}, "element <name> <count>");
    return {std::string(tokens[1]),
            static_cast<std::size_t>(parse_uint(tokens[2], {path, line})),
            {},
            line.number};
}

struct HeaderParser {
    const std::string& path;
    PlyHeader header;
    bool has_format = false;

    /// Returns true at end_header.
    bool line(const TextLine& line) {
        const Tokens tokens = split_tokens(line.text);
        if (tokens.empty()) return false;
        const std::string_view keyword = tokens[0];
        if (keyword == "comment" || keyword == "obj_info") return false;
        if (keyword == "end_header") return true;
        if (keyword == "format") {
            header.format = parse_format(tokens, path, line);
            has_format = true;
        } else if (keyword == "element") {
            header.elements.push_back(parse_element(tokens, path, line));
        } else if (keyword == "property") {
            if (header.elements.empty()) fail(path, line.number, "property before any element");
            header.elements.back().properties.push_back(parse_property(tokens, path, line));
        } else {
            fail(path, line.number, "unknown PLY header keyword '" + std::string(keyword) + "'");
        }
        return false;
    }
};

void check_unique_names(const PlyHeader& header, const std::string& path) {
    std::set<std::string_view> elements;
    for (const PlyElement& element : header.elements) {
        if (!elements.insert(element.name).second) {
            fail(path, element.line, "element '" + element.name + "' declared twice");
        }
        std::set<std::string_view> properties;
        for (const PlyProperty& property : element.properties) {
            if (properties.insert(property.name).second) continue;
            fail(path, property.line,
                 "property '" + property.name + "' declared twice in element '" + element.name +
                     "'");
        }
    }
}

/// The least bytes one row of `element` takes: a list may be empty but has its count.
std::uint64_t min_row_bytes(const PlyElement& element, PlyFormat format) {
    std::uint64_t bytes = 0;
    for (const PlyProperty& p : element.properties) {
        bytes += format == PlyFormat::kAscii ? kMinAsciiBytesPerValue
                                             : scalar_size(p.is_list ? p.count_type : p.type);
    }
    return bytes;  // <= 8 x the properties of a header held in memory: cannot overflow
}

}  // namespace

void validate_layout(PlyHeader& header, std::size_t data_bytes, const std::string& path) {
    check_unique_names(header, path);
    std::optional<std::uint64_t> needed = 0;
    for (const PlyElement& element : header.elements) {
        const auto rows = checked_multiply(element.count, min_row_bytes(element, header.format));
        needed = rows ? checked_add(*needed, *rows) : std::nullopt;
        if (!needed) break;
    }
    // The last ascii row may lack its newline.
    const std::uint64_t slack = header.format == PlyFormat::kAscii ? 1 : 0;
    header.counts_fit = needed && *needed <= data_bytes + slack;
}

PlyHeader parse_ply_header(const std::string& bytes, const std::string& path) {
    if (bytes.empty()) fail(path, 1, "empty file, expected a PLY header starting with 'ply'");
    LineReader reader(bytes);
    TextLine line;
    reader.next(line);
    if (trim(line.text) != "ply") fail(path, 1, "bad magic, expected the first line to be 'ply'");
    HeaderParser parser{path, {}};
    while (reader.next(line)) {
        if (!parser.line(line)) continue;
        if (!parser.has_format) fail(path, line.number, "PLY header lacks the format line");
        parser.header.data_offset = reader.position();
        parser.header.data_line = line.number + 1;
        validate_layout(parser.header, bytes.size() - reader.position(), path);
        return parser.header;
    }
    fail(path, line.number, "PLY header has no end_header line");
}

const PlyElement* find_element(const PlyHeader& header, const std::string& name) {
    for (const PlyElement& element : header.elements) {
        if (element.name == name) return &element;
    }
    return nullptr;
}

}  // namespace scantling::io::detail
