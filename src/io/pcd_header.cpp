#include <scantling/core/error.hpp>

#include <algorithm>
#include <map>
#include <optional>

#include "detail/pcd_header.hpp"
#include "detail/text_lines.hpp"

namespace scantling::io::detail {
namespace {

using Tokens = std::vector<std::string_view>;

/// Key → (its values, its line). Views point into the caller's buffer.
struct RawHeader {
    std::map<std::string, std::pair<Tokens, TextLine>> entries;
    TextLine last_line;
};

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
    throw ParseError(path, {std::nullopt, line, std::nullopt}, what);
}

bool is_known_key(std::string_view key) {
    for (const char* known : {"VERSION", "FIELDS", "COLUMNS", "SIZE", "TYPE", "COUNT", "WIDTH",
                              "HEIGHT", "VIEWPOINT", "POINTS", "DATA"}) {
        if (key == known) return true;
    }
    return false;
}

RawHeader read_raw_header(const std::string& bytes, const std::string& path) {
    if (bytes.empty()) fail(path, 1, "empty file, expected a PCD header");
    RawHeader raw;
    LineReader reader(bytes);
    TextLine line;
    while (reader.next(line)) {
        raw.last_line = line;
        const std::string_view text = strip_comment(line.text);
        if (text.empty()) continue;
        Tokens tokens = split_tokens(text);
        const std::string key(tokens.front());
        if (!is_known_key(key)) fail(path, line.number, "unknown PCD header key '" + key + "'");
        if (raw.entries.count(key)) fail(path, line.number, "header key " + key + " repeated");
        tokens.erase(tokens.begin());
        raw.entries[key] = {std::move(tokens), line};
        if (key == "DATA") return raw;
    }
    fail(path, raw.last_line.number, "header has no DATA line");
}

const std::pair<Tokens, TextLine>& require(const RawHeader& raw, const std::string& key,
                                           const std::string& path) {
    const auto it = raw.entries.find(key);
    if (it == raw.entries.end()) {
        fail(path, raw.last_line.number, "PCD header lacks the " + key + " line");
    }
    return it->second;
}

int line_of(const RawHeader& raw, const std::string& key) {
    return raw.entries.at(key).second.number;
}

std::size_t single_uint(const RawHeader& raw, const std::string& key, const std::string& path) {
    const auto& [tokens, line] = require(raw, key, path);
    expect_token_count(tokens, 1, {path, line}, key);
    return static_cast<std::size_t>(parse_uint(tokens[0], {path, line}));
}

std::optional<ScalarType> scalar_type(char type, std::size_t size) {
    using S = ScalarType;
    if (type == 'F')
        return size == 4   ? std::optional(S::kF32)
               : size == 8 ? std::optional(S::kF64)
                           : std::nullopt;
    const bool is_signed = type == 'I';
    if (!is_signed && type != 'U') return std::nullopt;
    switch (size) {
        case 1:
            return is_signed ? S::kI8 : S::kU8;
        case 2:
            return is_signed ? S::kI16 : S::kU16;
        case 4:
            return is_signed ? S::kI32 : S::kU32;
        case 8:
            return is_signed ? S::kI64 : S::kU64;
        default:
            return std::nullopt;
    }
}

const std::pair<Tokens, TextLine>& per_field(const RawHeader& raw, const std::string& key,
                                             std::size_t num_fields, const std::string& path) {
    const auto& entry = require(raw, key, path);
    expect_token_count(entry.first, num_fields, {path, entry.second}, "one per field in FIELDS");
    return entry;
}

std::vector<PcdField> parse_fields(const RawHeader& raw, const std::string& path) {
    // COLUMNS is the pre-0.7 name of FIELDS.
    const bool legacy = raw.entries.count("FIELDS") == 0 && raw.entries.count("COLUMNS") > 0;
    const auto& [names, names_line] = require(raw, legacy ? "COLUMNS" : "FIELDS", path);
    if (names.empty()) fail(path, names_line.number, "FIELDS lists no field");
    const auto& [sizes, sizes_line] = per_field(raw, "SIZE", names.size(), path);
    const auto& [types, types_line] = per_field(raw, "TYPE", names.size(), path);
    const bool has_count = raw.entries.count("COUNT") > 0;
    const Tokens* counts = has_count ? &per_field(raw, "COUNT", names.size(), path).first : nullptr;
    std::vector<PcdField> fields(names.size());
    for (std::size_t f = 0; f < names.size(); ++f) {
        PcdField& field = fields[f];
        field.name = names[f];
        field.size = static_cast<std::size_t>(parse_uint(sizes[f], {path, sizes_line}));
        field.type_char = types[f].size() == 1 ? types[f][0] : '?';
        const auto type = scalar_type(field.type_char, field.size);
        if (!type) {
            fail(path, types_line.number,
                 "field '" + field.name + "' has TYPE " + std::string(types[f]) + " with SIZE " +
                     std::string(sizes[f]) + ", expected F (4, 8), I or U (1, 2, 4, 8)");
        }
        field.type = *type;
        if (counts) {
            const TextLine& count_line = raw.entries.at("COUNT").second;
            field.count = static_cast<std::size_t>(parse_uint((*counts)[f], {path, count_line}));
            if (field.count == 0)
                fail(path, count_line.number, "COUNT of '" + field.name + "' is 0");
        }
    }
    return fields;
}

void check_viewpoint(const RawHeader& raw, const std::string& path) {
    const auto it = raw.entries.find("VIEWPOINT");
    if (it == raw.entries.end()) return;
    const auto& [tokens, line] = it->second;
    expect_token_count(tokens, 7, {path, line}, "VIEWPOINT tx ty tz qw qx qy qz");
    for (const auto token : tokens) parse_double(token, {path, line});
}

PcdDataKind parse_data_kind(const RawHeader& raw, const std::string& path) {
    const auto& [tokens, line] = require(raw, "DATA", path);
    expect_token_count(tokens, 1, {path, line}, "DATA ascii|binary|binary_compressed");
    if (tokens[0] == "ascii") return PcdDataKind::kAscii;
    if (tokens[0] == "binary") return PcdDataKind::kBinary;
    if (tokens[0] == "binary_compressed") return PcdDataKind::kBinaryCompressed;
    fail(path, line.number,
         "unknown DATA type '" + std::string(tokens[0]) +
             "', expected ascii, binary or binary_compressed");
}

void check_mapped(const PcdField& field, CloudTarget target, int line, const std::string& path) {
    const bool packed = target == CloudTarget::kPackedRgb;
    if (field.count == 1 && (!packed || field.size == 4)) return;
    fail(path, line,
         "field '" + field.name + "' has COUNT " + std::to_string(field.count) + " and SIZE " +
             std::to_string(field.size) + ", expected COUNT 1" + (packed ? " and SIZE 4" : ""));
}

bool has_target(const std::vector<PcdColumn>& columns, CloudTarget target) {
    return std::any_of(columns.begin(), columns.end(),
                       [&](const PcdColumn& c) { return c.target == target; });
}

// Two fields feeding one member would be decoded silently, the later one winning.
void check_not_mapped_yet(const std::vector<PcdColumn>& columns, const PcdField& field,
                          CloudTarget target, int line, const std::string& path) {
    const auto earlier = std::find_if(columns.begin(), columns.end(),
                                      [&](const PcdColumn& c) { return c.target == target; });
    if (earlier == columns.end()) return;
    fail(path, line,
         "fields '" + earlier->field->name + "' and '" + field.name +
             "' both map to the same cloud member, expected one");
}

}  // namespace

PcdHeader parse_pcd_header(const std::string& bytes, const std::string& path) {
    const RawHeader raw = read_raw_header(bytes, path);
    PcdHeader header;
    header.fields = parse_fields(raw, path);
    header.width = single_uint(raw, "WIDTH", path);
    header.height = single_uint(raw, "HEIGHT", path);
    header.points = single_uint(raw, "POINTS", path);
    check_viewpoint(raw, path);
    header.data = parse_data_kind(raw, path);
    header.fields_line =
        raw.entries.count("FIELDS") ? line_of(raw, "FIELDS") : line_of(raw, "COLUMNS");
    header.count_line = raw.entries.count("COUNT") ? line_of(raw, "COUNT") : line_of(raw, "SIZE");
    header.points_line = line_of(raw, "POINTS");
    const TextLine& data_line = raw.entries.at("DATA").second;
    header.data_line = data_line.number;
    const std::size_t newline = bytes.find('\n', data_line.offset + data_line.text.size());
    header.data_offset = newline == std::string::npos ? bytes.size() : newline + 1;
    validate_layout(header, bytes, path);
    return header;
}

std::vector<PcdColumn> map_pcd_columns(const PcdHeader& header, const std::string& path) {
    std::vector<PcdColumn> columns;
    std::size_t token = 0;
    for (const PcdField& field : header.fields) {
        const CloudTarget target = cloud_target(field.name);
        if (target != CloudTarget::kNone) {
            check_mapped(field, target, header.data_line, path);
            check_not_mapped_yet(columns, field, target, header.fields_line, path);
            columns.push_back({target, &field, 0, 0, token});
        }
        token += field.count;
    }
    if (!has_target(columns, CloudTarget::kX) || !has_target(columns, CloudTarget::kY) ||
        !has_target(columns, CloudTarget::kZ)) {
        fail(path, header.data_line, "FIELDS lacks one of x, y, z");
    }
    return columns;
}

std::vector<CloudTarget> column_targets(const std::vector<PcdColumn>& columns) {
    std::vector<CloudTarget> targets;
    targets.reserve(columns.size());
    for (const PcdColumn& c : columns) targets.push_back(c.target);
    return targets;
}

}  // namespace scantling::io::detail
