// Reader of the structural map (structural_map.hpp): bounded JSON parsing, then every field
// checked and converted, naming "<file>: <list>[<i>].<key>" in each error.
#include <scantling/io/structural_map.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <system_error>

#include <scantling/core/error.hpp>

#include "detail/json_fields.hpp"

namespace scantling::io {
namespace {

using detail::Fields;
using detail::Json;

/// The bytes of `path`, refusing a file over kMaxStructuralMapBytes before reading it.
std::string read_bounded(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw FileError(path, "no such file");
    // A FIFO or device would have no size to check (and could be endless).
    if (!std::filesystem::is_regular_file(path, ec)) throw FileError(path, "not a regular file");
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw FileError(path, "cannot read the size: " + ec.message());
    if (size > kMaxStructuralMapBytes) {
        throw ParseError(path, FileLocation{},
                         fmt::format("{} bytes is more than the {} MiB a structural map may have",
                                     size, kMaxStructuralMapBytes >> 20));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FileError(path, "cannot open file for reading");
    std::string text(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), static_cast<std::streamsize>(size));
    if (static_cast<std::uintmax_t>(in.gcount()) != size) throw FileError(path, "read failed");
    return text;
}

/// `index`'s id must be the index (duplicates are named as such: clearer than "expected 3").
void check_id(const Fields& f, const char* key, int id, std::size_t index) {
    if (id >= 0 && static_cast<std::size_t>(id) < index) {
        f.fail(key, fmt::format("= {} repeats the id of item {} (ids are unique)", id, id));
    }
    if (id < 0 || static_cast<std::size_t>(id) != index) {
        f.fail(key,
               fmt::format("= {}, expected {} (ids are the positions in the list)", id, index));
    }
}

/// `value` must be -1 (`none_allowed`) or an index below `size`.
void check_index(const Fields& f, const char* key, int value, std::size_t size, const char* what,
                 bool none_allowed) {
    if (none_allowed && value == -1) return;
    if (value < 0 || static_cast<std::size_t>(value) >= size) {
        f.fail(key, fmt::format("= {}: no such {} (the map has {})", value, what, size));
    }
}

/// `number` must be -1 or the number of one of `lines`.
void check_number(const Fields& f, const char* key, int number, const std::vector<FrameLine>& lines,
                  const char* what) {
    const auto same = [number](const FrameLine& l) { return l.number == number; };
    if (number != -1 && std::none_of(lines.begin(), lines.end(), same)) {
        f.fail(key, fmt::format("= {}: no such {} number", number, what));
    }
}

Surface read_surface(const Fields& f, const std::vector<Surface>& so_far, const StructuralMap&) {
    f.require({"tag", "name", "textured", "albedo"});
    Surface s{.tag = f.integer("tag"),
              .name = f.text("name"),
              .textured = f.boolean("textured"),
              .albedo = f.number("albedo")};
    check_id(f, "tag", s.tag, so_far.size());
    if (!(s.albedo >= 0.0 && s.albedo <= 1.0)) {
        f.fail("albedo", fmt::format("= {}, expected in [0, 1]", s.albedo));
    }
    return s;
}

Compartment read_compartment(const Fields& f, const std::vector<Compartment>& so_far,
                             const StructuralMap&) {
    f.require({"id", "name", "level", "min", "max"});
    Compartment c{.id = f.integer("id"),
                  .name = f.text("name"),
                  .bounds = {f.vector("min"), f.vector("max")},
                  .level = f.integer("level")};
    check_id(f, "id", c.id, so_far.size());
    if (!(c.bounds.min.array() <= c.bounds.max.array()).all()) {
        f.fail("min", "is above max in some axis (expected min <= max)");
    }
    return c;
}

Connection read_connection(const Fields& f, const std::vector<Connection>& so_far,
                           const StructuralMap& map) {
    f.require({"id", "kind", "compartment_a", "compartment_b", "centre", "normal", "width_m",
               "height_m"});
    Connection c{.id = f.integer("id"),
                 .kind = f.kind<ConnectionKind>(
                     "kind", {ConnectionKind::Manhole, ConnectionKind::LevelTransition,
                              ConnectionKind::Entry}),
                 .compartment_a = f.integer("compartment_a"),
                 .compartment_b = f.integer("compartment_b"),
                 .centre = f.vector("centre"),
                 .normal = f.unit_vector("normal"),
                 .width_m = f.non_negative("width_m"),
                 .height_m = f.non_negative("height_m")};
    check_id(f, "id", c.id, so_far.size());
    const std::size_t n = map.compartments.size();
    check_index(f, "compartment_a", c.compartment_a, n, "compartment", false);
    check_index(f, "compartment_b", c.compartment_b, n, "compartment (-1 = outside)", true);
    return c;
}

FrameLine read_frame_line(const Fields& f, const std::vector<FrameLine>& so_far,
                          const StructuralMap& map) {
    f.require({"number", "point", "axis", "surface"});
    FrameLine l{.number = f.integer("number"),
                .point = f.vector("point"),
                .axis = f.unit_vector("axis"),
                .surface = f.text("surface")};
    if (l.number < 0) f.fail("number", fmt::format("= {}, expected >= 0", l.number));
    const auto same = [&l](const FrameLine& other) { return other.number == l.number; };
    if (std::any_of(so_far.begin(), so_far.end(), same)) {
        f.fail("number",
               fmt::format("= {} repeats an earlier number (numbers are unique)", l.number));
    }
    const auto named = [&l](const Surface& s) { return s.name == l.surface; };
    if (std::none_of(map.surfaces.begin(), map.surfaces.end(), named)) {
        f.fail("surface",
               fmt::format("= \"{}\": no surface has that name", detail::shortened(l.surface)));
    }
    return l;
}

Landmark read_landmark(const Fields& f, const std::vector<Landmark>& so_far,
                       const StructuralMap& map) {
    f.require({"id", "kind", "position", "compartment", "frame", "longitudinal", "connection"});
    Landmark l{.id = f.integer("id"),
               .kind = f.kind<LandmarkKind>(
                   "kind", {LandmarkKind::FrameLongitudinal, LandmarkKind::ManholeCentre}),
               .position = f.vector("position"),
               .compartment = f.integer("compartment"),
               .frame = f.integer("frame"),
               .longitudinal = f.integer("longitudinal"),
               .connection = f.integer("connection")};
    check_id(f, "id", l.id, so_far.size());
    check_index(f, "compartment", l.compartment, map.compartments.size(), "compartment", false);
    check_number(f, "frame", l.frame, map.frames, "frame");
    check_number(f, "longitudinal", l.longitudinal, map.longitudinals, "longitudinal");
    check_index(f, "connection", l.connection, map.connections.size(), "connection", true);
    return l;
}

Defect read_defect(const Fields& f, const std::vector<Defect>& so_far, const StructuralMap& map) {
    f.require(
        {"id", "kind", "centre", "normal", "direction", "radius_m", "surface_tag", "compartment"});
    Defect d{.id = f.integer("id"),
             .kind = f.kind<DefectKind>("kind", {DefectKind::Corrosion, DefectKind::Crack}),
             .centre = f.vector("centre"),
             .normal = f.unit_vector("normal"),
             .direction = f.unit_vector("direction"),
             .radius_m = f.non_negative("radius_m"),
             .surface_tag = f.integer("surface_tag"),
             .compartment = f.integer("compartment")};
    check_id(f, "id", d.id, so_far.size());
    check_index(f, "surface_tag", d.surface_tag, map.surfaces.size(), "surface", false);
    check_index(f, "compartment", d.compartment, map.compartments.size(),
                "compartment (-1 = outside all)", true);
    return d;
}

/// The list `key` of `top`, each item read by `read(fields, items so far, map so far)`.
template <typename T, typename Reader>
std::vector<T> read_list(const Fields& top, const char* key, const StructuralMap& map,
                         Reader read) {
    const Json& list = top.array(key);
    std::vector<T> items;
    items.reserve(list.size());
    for (std::size_t i = 0; i < list.size(); ++i) {
        const Fields item = top.item(key, i);
        items.push_back(read(item, items, map));
    }
    return items;
}

/// [[tag, count], ...]: tags of listed surfaces, counts >= 1 (dropped after the check).
void check_tag_runs(const Fields& top, std::size_t num_surfaces) {
    const Json& runs = top.array("triangle_surface_tags");
    for (std::size_t i = 0; i < runs.size(); ++i) {
        const auto [tag, count] = top.int_pair("triangle_surface_tags", i);
        const std::string where = fmt::format("[{}]", i);
        if (tag < 0 || static_cast<std::size_t>(tag) >= num_surfaces) {
            top.fail("triangle_surface_tags",
                     where + fmt::format(": tag {} is not a surface (the map has {})", tag,
                                         num_surfaces));
        }
        if (count < 1) {
            top.fail("triangle_surface_tags",
                     where + fmt::format(": count {}, expected >= 1", count));
        }
    }
}

}  // namespace

StructuralMap parse_structural_map(std::string_view text, const std::string& name) {
    const Json root = detail::parse_bounded_json(
        text, name, {.max_values = kMaxStructuralMapValues, .max_depth = kMaxStructuralMapDepth});
    const Fields top(name, root, "");
    top.require({"name", "surfaces", "compartments", "connections", "frames", "longitudinals",
                 "landmarks", "defects"},
                {"triangle_surface_tags"});
    StructuralMap map;
    map.name = top.text("name");
    // In this order each list refers only to lists read before it.
    map.surfaces = read_list<Surface>(top, "surfaces", map, read_surface);
    map.compartments = read_list<Compartment>(top, "compartments", map, read_compartment);
    map.connections = read_list<Connection>(top, "connections", map, read_connection);
    map.frames = read_list<FrameLine>(top, "frames", map, read_frame_line);
    map.longitudinals = read_list<FrameLine>(top, "longitudinals", map, read_frame_line);
    map.landmarks = read_list<Landmark>(top, "landmarks", map, read_landmark);
    map.defects = read_list<Defect>(top, "defects", map, read_defect);
    if (top.find("triangle_surface_tags")) check_tag_runs(top, map.surfaces.size());
    return map;
}

StructuralMap read_structural_map(const std::string& path) {
    return parse_structural_map(read_bounded(path), path);
}

}  // namespace scantling::io
