#include <scantling/core/error.hpp>

#include <algorithm>

#include "detail/pcd_header.hpp"
#include "detail/text_lines.hpp"

namespace scantling::io::detail {
namespace {

constexpr double kNanosecondsToSeconds = 1e-9;

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
    throw ParseError(path, {std::nullopt, line, std::nullopt}, what);
}

bool all_digits(std::string_view token) {
    return !token.empty() &&
           std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; });
}

/// An integer the field's declared TYPE and SIZE can hold ("U 1" with 300 is a lying header).
template <typename Int>
Int fitting(Int value, ScalarType type, std::string_view token, const PcdField& field,
            const LineContext& where) {
    if (!integer_fits(type, value)) {
        throw_bad_token(token, where,
                        std::string("a value that fits ") + scalar_type_name(type) + " (field '" +
                            field.name + "')");
    }
    return value;
}

double parse_value(std::string_view token, const PcdField& field, const LineContext& where) {
    switch (field.type_char) {
        case 'I':
            return static_cast<double>(
                fitting(parse_int(token, where), field.type, token, field, where));
        case 'U':
            return static_cast<double>(
                fitting(parse_uint(token, where), field.type, token, field, where));
        default: {
            // A float32 field holds the float nearest to the text, not the nearest double.
            const double value = parse_double(token, where, NonFinite::kAllow);
            return field.size == 4 ? static_cast<float>(value) : value;
        }
    }
}

// PCL writes a float-typed packed rgb as the integer value of its bits; accept plain floats too.
std::uint32_t parse_packed_rgb(std::string_view token, const PcdField& field,
                               const LineContext& where) {
    if (field.type_char != 'F' || all_digits(token)) {
        return static_cast<std::uint32_t>(
            fitting(parse_uint(token, where), ScalarType::kU32, token, field, where));
    }
    return packed_rgb(static_cast<float>(parse_double(token, where, NonFinite::kAllow)));
}

void expect_values(const LineContext& where, const PcdHeader& header) {
    expect_token_count(count_tokens(where.line.text), header.values_per_point, where,
                       "one per field element");
}

struct AsciiPoint {
    const PcdHeader& header;
    const std::string& path;
    std::vector<CloudTarget> field_targets;  // per field in FIELDS
    CloudBuilder builder;

    // Tokens are taken one at a time (TokenCursor): a hostile line of millions of tokens costs
    // no memory, and is counted only to say how many values it held.
    void parse(const TextLine& line, std::size_t i) {
        const LineContext where{path, line};
        TokenCursor cursor(line.text);
        for (std::size_t f = 0; f < header.fields.size(); ++f) parse_field(cursor, where, f, i);
        std::string_view extra;
        if (cursor.next(extra)) expect_values(where, header);
    }

    void parse_field(TokenCursor& cursor, const LineContext& where, std::size_t f, std::size_t i) {
        const PcdField& field = header.fields[f];
        const CloudTarget target = field_targets[f];
        if (target == CloudTarget::kPackedRgb) {
            builder.set_packed_rgb(i, parse_packed_rgb(take(cursor, where), field, where));
            return;
        }
        const bool ns = target == CloudTarget::kTime && field.type_char != 'F';
        for (std::size_t k = 0; k < field.count; ++k) {
            const double value = parse_value(take(cursor, where), field, where);
            builder.set(target, i, ns ? value * kNanosecondsToSeconds : value);
        }
    }

    std::string_view take(TokenCursor& cursor, const LineContext& where) const {
        std::string_view token;
        if (!cursor.next(token)) expect_values(where, header);
        return token;
    }
};

std::vector<CloudTarget> field_targets(const PcdHeader& header) {
    std::vector<CloudTarget> targets;
    for (const PcdField& field : header.fields) targets.push_back(cloud_target(field.name));
    return targets;
}

/// Calls on_row(line) for each non-empty data line; throws at the first line past POINTS or at
/// the end of the data when fewer than POINTS lines hold values.
template <typename OnRow>
void for_each_row(const std::string& bytes, const PcdHeader& header, const std::string& path,
                  OnRow on_row) {
    LineReader reader(bytes, header.data_offset, header.data_line + 1);
    TextLine line{{}, header.data_line, 0};
    std::size_t rows = 0;
    while (reader.next(line)) {
        if (trim(line.text).empty()) continue;
        if (rows == header.points) {
            fail(path, line.number, "more points than POINTS = " + std::to_string(header.points));
        }
        on_row(line, rows++);
    }
    if (rows < header.points) {
        fail(path, line.number,
             "file ends after " + std::to_string(rows) +
                 " points, expected POINTS = " + std::to_string(header.points));
    }
}

}  // namespace

void check_ascii_rows(const std::string& bytes, const PcdHeader& header, const std::string& path) {
    for_each_row(bytes, header, path, [&](const TextLine& line, std::size_t) {
        expect_values({path, line}, header);
    });
}

PointCloud read_pcd_ascii(const std::string& bytes, const PcdHeader& header,
                          const std::vector<PcdColumn>& columns, const std::string& path) {
    // validate_layout bounded POINTS by the bytes present before this allocation.
    AsciiPoint point{header, path, field_targets(header),
                     CloudBuilder(header.points, column_targets(columns))};
    for_each_row(bytes, header, path,
                 [&](const TextLine& line, std::size_t i) { point.parse(line, i); });
    return point.builder.finish();
}

}  // namespace scantling::io::detail
