#include <scantling/core/error.hpp>

#include <algorithm>

#include "detail/pcd_header.hpp"
#include "detail/text_lines.hpp"

namespace scantling::io::detail {
namespace {

constexpr double kNanosecondsToSeconds = 1e-9;

bool all_digits(std::string_view token) {
    return !token.empty() &&
           std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; });
}

double parse_value(std::string_view token, const PcdField& field, const LineContext& where) {
    switch (field.type_char) {
        case 'I':
            return static_cast<double>(parse_int(token, where));
        case 'U':
            return static_cast<double>(parse_uint(token, where));
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
        return static_cast<std::uint32_t>(parse_uint(token, where));
    }
    return packed_rgb(static_cast<float>(parse_double(token, where, NonFinite::kAllow)));
}

struct AsciiPoint {
    const PcdHeader& header;
    const std::string& path;
    std::vector<CloudTarget> field_targets;  // per field in FIELDS
    CloudBuilder builder;

    void parse(const std::vector<std::string_view>& tokens, const TextLine& line, std::size_t i) {
        const LineContext where{path, line};
        std::size_t t = 0;
        for (std::size_t f = 0; f < header.fields.size(); ++f) {
            const PcdField& field = header.fields[f];
            const CloudTarget target = field_targets[f];
            if (target == CloudTarget::kPackedRgb) {
                builder.set_packed_rgb(i, parse_packed_rgb(tokens[t++], field, where));
                continue;
            }
            for (std::size_t k = 0; k < field.count; ++k) {
                const double value = parse_value(tokens[t++], field, where);
                const bool ns = target == CloudTarget::kTime && field.type_char != 'F';
                builder.set(target, i, ns ? value * kNanosecondsToSeconds : value);
            }
        }
    }
};

std::vector<CloudTarget> field_targets(const PcdHeader& header) {
    std::vector<CloudTarget> targets;
    for (const PcdField& field : header.fields) targets.push_back(cloud_target(field.name));
    return targets;
}

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
    throw ParseError(path, {std::nullopt, line, std::nullopt}, what);
}

}  // namespace

PointCloud read_pcd_ascii(const std::string& bytes, const PcdHeader& header,
                          const std::vector<PcdColumn>& columns, const std::string& path) {
    if (header.points > bytes.size() - header.data_offset) {
        fail(path, header.data_line,
             "POINTS = " + std::to_string(header.points) + " but only " +
                 std::to_string(bytes.size() - header.data_offset) + " bytes of data follow");
    }
    std::size_t values_per_line = 0;
    for (const PcdField& field : header.fields) values_per_line += field.count;
    AsciiPoint point{header, path, field_targets(header),
                     CloudBuilder(header.points, column_targets(columns))};
    LineReader reader(bytes, header.data_offset, header.data_line + 1);
    TextLine line{{}, header.data_line, 0};
    std::vector<std::string_view> tokens;
    std::size_t i = 0;
    while (reader.next(line)) {
        const std::string_view text = trim(line.text);
        if (text.empty()) continue;
        if (i == header.points) {
            fail(path, line.number, "more points than POINTS = " + std::to_string(header.points));
        }
        split_tokens(text, tokens);
        expect_token_count(tokens, values_per_line, {path, line}, "one per field element");
        point.parse(tokens, line, i++);
    }
    if (i < header.points) {
        fail(path, line.number,
             "file ends after " + std::to_string(i) +
                 " points, expected POINTS = " + std::to_string(header.points));
    }
    return point.builder.finish();
}

}  // namespace scantling::io::detail
