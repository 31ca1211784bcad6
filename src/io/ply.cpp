#include <scantling/core/error.hpp>
#include <scantling/io/ply.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "detail/cloud_builder.hpp"
#include "detail/ply_header.hpp"
#include "detail/ply_source.hpp"
#include "detail/text_lines.hpp"

namespace scantling::io {
namespace {

using detail::CloudTarget;
using detail::PlyElement;
using detail::PlyProperty;

constexpr double kNanosecondsToSeconds = 1e-9;
constexpr double kUnitToChannel = 255.0;  // floating-point colours are stored in [0, 1]

struct VertexColumn {
    CloudTarget target = CloudTarget::kNone;
    double scale = 1.0;
};

VertexColumn vertex_column(const PlyProperty& property) {
    const CloudTarget target =
        property.is_list ? CloudTarget::kNone : detail::cloud_target(property.name);
    const bool integer = detail::is_integer(property.type);
    switch (target) {
        case CloudTarget::kTime:
            return {target, integer ? kNanosecondsToSeconds : 1.0};
        case CloudTarget::kRed:
        case CloudTarget::kGreen:
        case CloudTarget::kBlue:
            return {target, integer ? 1.0 : kUnitToChannel};
        // A packed rgb in a float cannot survive the conversion to double: skip it.
        case CloudTarget::kPackedRgb:
            return {integer ? target : CloudTarget::kNone, 1.0};
        default:
            return {target, 1.0};
    }
}

// Two properties feeding one member would be decoded silently, the later one winning.
void check_not_mapped_yet(const std::vector<VertexColumn>& columns, const PlyElement& element,
                          const PlyProperty& property, CloudTarget target,
                          const std::string& path) {
    for (std::size_t j = 0; j < columns.size(); ++j) {
        if (target == CloudTarget::kNone || columns[j].target != target) continue;
        throw ParseError(path, {std::nullopt, property.line, std::nullopt},
                         "properties '" + element.properties[j].name + "' and '" + property.name +
                             "' both map to the same cloud member");
    }
}

std::vector<VertexColumn> vertex_columns(const PlyElement& element, const std::string& path) {
    std::vector<VertexColumn> columns;
    for (const PlyProperty& p : element.properties) {
        const VertexColumn column = vertex_column(p);
        check_not_mapped_yet(columns, element, p, column.target, path);
        columns.push_back(column);
    }
    for (const CloudTarget axis : {CloudTarget::kX, CloudTarget::kY, CloudTarget::kZ}) {
        if (std::none_of(columns.begin(), columns.end(),
                         [&](const VertexColumn& c) { return c.target == axis; })) {
            throw ParseError(path, {std::nullopt, element.line, std::nullopt},
                             "element 'vertex' lacks one of the properties x, y, z");
        }
    }
    return columns;
}

// Exact text of an integer-valued double, also beyond 2^64 where no integer type holds it.
std::string integer_text(double n) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.0f", n);
    return text;
}

/// The list length, bounded by the values the rest of the data can hold before it is used as a
/// loop bound or converted (a uint64 count near 2^64 does not fit a size_t).
template <typename Source>
std::size_t list_length(Source& source, const PlyProperty& property, const std::string& path) {
    const FileLocation where = source.location();
    const double n = source.scalar(property.count_type);
    if (n < 0) {
        throw ParseError(path, where, "negative list length in " + source.context.describe());
    }
    const std::size_t room = source.max_items(property.type);
    if (n > static_cast<double>(room)) {
        throw ParseError(path, where,
                         "list of " + integer_text(n) + " values in " + source.context.describe() +
                             ", but only " + std::to_string(room) + " more fit in the data");
    }
    return static_cast<std::size_t>(n);
}

template <typename Source>
void skip_property(Source& source, const PlyProperty& property, const std::string& path) {
    if (!property.is_list) {
        source.scalar(property.type);
        return;
    }
    const std::size_t n = list_length(source, property, path);
    for (std::size_t k = 0; k < n; ++k) source.scalar(property.type);
}

template <typename Source>
void skip_element(Source& source, const PlyElement& element, const std::string& path) {
    if (element.properties.empty()) return;  // rows without properties hold no data
    for (std::size_t i = 0; i < element.count; ++i) {
        source.context.row = i;
        source.begin_row();
        for (const PlyProperty& p : element.properties) skip_property(source, p, path);
        source.end_row();
    }
}

template <typename Source>
PointCloud read_vertices(Source& source, const PlyElement& element, const std::string& path) {
    const std::vector<VertexColumn> columns = vertex_columns(element, path);
    std::vector<CloudTarget> targets;
    targets.reserve(columns.size());
    for (const VertexColumn& c : columns) targets.push_back(c.target);
    detail::CloudBuilder builder(element.count, targets);
    for (std::size_t i = 0; i < element.count; ++i) {
        source.context.row = i;
        source.begin_row();
        for (std::size_t j = 0; j < columns.size(); ++j) {
            const PlyProperty& p = element.properties[j];
            if (p.is_list) {
                skip_property(source, p, path);
                continue;
            }
            const double value = source.scalar(p.type);
            if (columns[j].target != CloudTarget::kNone)
                builder.set(columns[j].target, i, value * columns[j].scale);
        }
        source.end_row();
    }
    return builder.finish();
}

template <typename Source>
void read_polygon(Source& source, const PlyProperty& property, std::size_t num_vertices,
                  std::vector<int>& corners, const std::string& path) {
    const FileLocation where = source.location();
    const std::size_t n = list_length(source, property, path);
    if (n < 3) {
        throw ParseError(path, where,
                         "polygon with " + std::to_string(n) + " corners in " +
                             source.context.describe() + ", expected at least 3");
    }
    corners.clear();
    for (std::size_t k = 0; k < n; ++k) {
        const FileLocation at = source.location();
        const double v = source.scalar(property.type);
        if (!(v >= 0 && v < static_cast<double>(num_vertices)) || v != std::floor(v)) {
            throw ParseError(path, at,
                             "vertex index " + std::to_string(static_cast<long long>(v)) + " in " +
                                 source.context.describe() + " is outside [0, " +
                                 std::to_string(num_vertices) + ")");
        }
        corners.push_back(static_cast<int>(v));
    }
}

const PlyProperty* index_property(const PlyElement& element, const std::string& path) {
    for (const PlyProperty& p : element.properties) {
        if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) return &p;
    }
    throw ParseError(path, {std::nullopt, element.line, std::nullopt},
                     "element 'face' has no list property vertex_indices");
}

template <typename Source>
void read_faces(Source& source, const PlyElement& element, std::size_t num_vertices,
                std::vector<Eigen::Vector3i>& faces, const std::string& path) {
    const PlyProperty* indices = index_property(element, path);
    std::vector<int> corners;
    faces.reserve(faces.size() + element.count);
    for (std::size_t i = 0; i < element.count; ++i) {
        source.context.row = i;
        source.begin_row();
        for (const PlyProperty& p : element.properties) {
            if (&p != indices) {
                skip_property(source, p, path);
                continue;
            }
            read_polygon(source, p, num_vertices, corners, path);
            for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
                faces.emplace_back(corners[0], corners[k], corners[k + 1]);
            }
        }
        source.end_row();
    }
}

/// The declared rows cannot fit in the data (validate_layout): walk it without storing anything,
/// which throws where it ends (or at the first malformed value on the way).
template <typename Source>
[[noreturn]] void report_short_data(Source& source, const detail::PlyHeader& header,
                                    const std::string& path) {
    for (const PlyElement& element : header.elements) {
        source.context.element = &element;
        skip_element(source, element, path);
    }
    throw ParseError(path, source.location(),
                     "the element counts in the header need more data than the file holds");
}

template <typename Source>
PlyData read_body(Source& source, const detail::PlyHeader& header, const std::string& path) {
    const PlyElement* vertex = detail::find_element(header, "vertex");
    if (!vertex) {
        throw ParseError(path, {std::nullopt, header.data_line - 1, std::nullopt},
                         "PLY header declares no element 'vertex'");
    }
    if (!header.counts_fit) report_short_data(source, header, path);
    PlyData data;
    for (const PlyElement& element : header.elements) {
        source.context.element = &element;
        if (&element == vertex) {
            data.cloud = read_vertices(source, element, path);
        } else if (element.name == "face") {
            read_faces(source, element, vertex->count, data.faces, path);
        } else {
            skip_element(source, element, path);
        }
    }
    source.context.element = nullptr;
    source.finish();
    return data;
}

}  // namespace

PlyData read_ply(const std::string& path) {
    const std::string bytes = detail::read_whole_file(path);
    const detail::PlyHeader header = detail::parse_ply_header(bytes, path);
    if (header.format == detail::PlyFormat::kAscii) {
        detail::AsciiPlySource source(bytes, header.data_offset, header.data_line, path);
        return read_body(source, header, path);
    }
    const bool little = header.format == detail::PlyFormat::kBinaryLittleEndian;
    detail::BinaryPlySource source(bytes, header.data_offset,
                                   little ? std::endian::little : std::endian::big, path);
    return read_body(source, header, path);
}

}  // namespace scantling::io
