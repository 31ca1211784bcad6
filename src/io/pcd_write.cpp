#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/pcd.hpp>

#include <charconv>

#include "detail/binary_scalar.hpp"
#include "detail/cloud_builder.hpp"
#include "detail/text_lines.hpp"

namespace scantling::io {
namespace {

struct BinarySink {
    std::string& out;
    void real(double v) { detail::append_le(out, static_cast<float>(v)); }
    void ring(std::uint16_t v) { detail::append_le(out, v); }
    void rgb(const Rgb8& c) { detail::append_le(out, detail::rgb_as_float(c)); }
    void end_point() {}
};

struct AsciiSink {
    std::string& out;
    void real(double v) {
        detail::append_number(out, static_cast<float>(v));
        out += ' ';
    }
    void ring(std::uint16_t v) { append_uint(v); }
    // PCL convention: a float-typed packed rgb is written as the integer value of its bits.
    void rgb(const Rgb8& c) { append_uint(detail::packed_rgb(detail::rgb_as_float(c))); }
    void end_point() { out.back() = '\n'; }

    void append_uint(std::uint32_t v) {
        char buffer[16];
        out.append(buffer, std::to_chars(buffer, buffer + sizeof(buffer), v).ptr);
        out += ' ';
    }
};

template <typename Sink>
void emit_point(const PointCloud& cloud, std::size_t i, Sink& sink) {
    for (int axis = 0; axis < 3; ++axis) sink.real(cloud.points[i][axis]);
    if (cloud.has_normals()) {
        for (int axis = 0; axis < 3; ++axis) sink.real(cloud.normals[i][axis]);
    }
    if (cloud.has_intensities()) sink.real(cloud.intensities[i]);
    if (cloud.has_rings()) sink.ring(cloud.rings[i]);
    if (cloud.has_times()) sink.real(cloud.times_s[i]);
    if (cloud.has_colors()) sink.rgb(cloud.colors[i]);
    sink.end_point();
}

struct FieldSpec {
    const char* name;
    const char* size;
    const char* type;
};

std::vector<FieldSpec> field_specs(const PointCloud& cloud) {
    std::vector<FieldSpec> specs{{"x", "4", "F"}, {"y", "4", "F"}, {"z", "4", "F"}};
    if (cloud.has_normals()) {
        specs.insert(specs.end(),
                     {{"normal_x", "4", "F"}, {"normal_y", "4", "F"}, {"normal_z", "4", "F"}});
    }
    if (cloud.has_intensities()) specs.push_back({"intensity", "4", "F"});
    if (cloud.has_rings()) specs.push_back({"ring", "2", "U"});
    if (cloud.has_times()) specs.push_back({"time", "4", "F"});
    if (cloud.has_colors()) specs.push_back({"rgb", "4", "F"});
    return specs;
}

std::string header_text(const PointCloud& cloud, PcdEncoding encoding) {
    const auto specs = field_specs(cloud);
    std::string fields = "FIELDS", sizes = "SIZE", types = "TYPE", counts = "COUNT";
    for (const FieldSpec& s : specs) {
        fields += std::string(" ") + s.name;
        sizes += std::string(" ") + s.size;
        types += std::string(" ") + s.type;
        counts += " 1";
    }
    const std::string n = std::to_string(cloud.size());
    return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n" + fields + "\n" + sizes +
           "\n" + types + "\n" + counts + "\nWIDTH " + n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n" +
           "POINTS " + n + "\nDATA " + (encoding == PcdEncoding::kAscii ? "ascii" : "binary") +
           "\n";
}

std::string body_bytes(const PointCloud& cloud, PcdEncoding encoding) {
    std::string body;
    if (encoding == PcdEncoding::kBinary) {
        body.reserve(cloud.size() * field_specs(cloud).size() * 4);
        BinarySink sink{body};
        for (std::size_t i = 0; i < cloud.size(); ++i) emit_point(cloud, i, sink);
    } else {
        AsciiSink sink{body};
        for (std::size_t i = 0; i < cloud.size(); ++i) emit_point(cloud, i, sink);
    }
    return body;
}

}  // namespace

void write_pcd(const std::string& path, const PointCloud& cloud, PcdEncoding encoding) {
    check_consistent(cloud, "write_pcd " + path);
    const std::string header = header_text(cloud, encoding);
    const std::string body = body_bytes(cloud, encoding);
    write_file_atomically(path, [&](std::ostream& out) {
        out.write(header.data(), static_cast<std::streamsize>(header.size()));
        out.write(body.data(), static_cast<std::streamsize>(body.size()));
    });
}

}  // namespace scantling::io
