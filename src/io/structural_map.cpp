// The structural map: kind names, the JSON writer and the queries (structural_map.hpp).
#include <scantling/io/structural_map.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>

namespace scantling::io {
namespace {

using Json = nlohmann::ordered_json;  // insertion order: deterministic text

Json vec(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json to_json(const Surface& s) {
    return {{"tag", s.tag}, {"name", s.name}, {"textured", s.textured}, {"albedo", s.albedo}};
}

Json to_json(const Compartment& c) {
    return {{"id", c.id},
            {"name", c.name},
            {"level", c.level},
            {"min", vec(c.bounds.min)},
            {"max", vec(c.bounds.max)}};
}

Json to_json(const Connection& c) {
    return {{"id", c.id},
            {"kind", std::string(to_string(c.kind))},
            {"compartment_a", c.compartment_a},
            {"compartment_b", c.compartment_b},
            {"centre", vec(c.centre)},
            {"normal", vec(c.normal)},
            {"width_m", c.width_m},
            {"height_m", c.height_m}};
}

Json to_json(const FrameLine& f) {
    return {{"number", f.number},
            {"point", vec(f.point)},
            {"axis", vec(f.axis)},
            {"surface", f.surface}};
}

Json to_json(const Landmark& l) {
    return {{"id", l.id},
            {"kind", std::string(to_string(l.kind))},
            {"position", vec(l.position)},
            {"compartment", l.compartment},
            {"frame", l.frame},
            {"longitudinal", l.longitudinal},
            {"connection", l.connection}};
}

Json to_json(const Defect& d) {
    return {{"id", d.id},
            {"kind", std::string(to_string(d.kind))},
            {"centre", vec(d.centre)},
            {"normal", vec(d.normal)},
            {"direction", vec(d.direction)},
            {"radius_m", d.radius_m},
            {"surface_tag", d.surface_tag},
            {"compartment", d.compartment}};
}

template <typename T>
Json array_of(const std::vector<T>& items) {
    Json out = Json::array();
    for (const T& item : items) out.push_back(to_json(item));
    return out;
}

Json run_lengths(std::span<const int> tags) {
    Json runs = Json::array();
    for (std::size_t i = 0; i < tags.size();) {
        std::size_t j = i;
        while (j < tags.size() && tags[j] == tags[i]) ++j;
        runs.push_back(Json::array({tags[i], j - i}));
        i = j;
    }
    return runs;
}

bool contains(const Aabb& box, const Eigen::Vector3d& p) {
    return (p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all();
}

double volume(const Aabb& box) { return (box.max - box.min).prod(); }

/// Number of the line of `lines` with the smallest distance(line) (the first on ties).
template <typename Distance>
std::optional<int> nearest(const std::vector<FrameLine>& lines, Distance distance) {
    std::optional<int> best;
    double best_m = std::numeric_limits<double>::infinity();
    for (const FrameLine& line : lines) {
        const double d_m = distance(line);
        if (d_m < best_m) {
            best_m = d_m;
            best = line.number;
        }
    }
    return best;
}

}  // namespace

std::string_view to_string(ConnectionKind kind) {
    switch (kind) {
        case ConnectionKind::Manhole:
            return "manhole";
        case ConnectionKind::LevelTransition:
            return "level_transition";
        case ConnectionKind::Entry:
            return "entry";
    }
    return "unknown";
}

std::string_view to_string(LandmarkKind kind) {
    switch (kind) {
        case LandmarkKind::FrameLongitudinal:
            return "frame_longitudinal";
        case LandmarkKind::ManholeCentre:
            return "manhole_centre";
    }
    return "unknown";
}

std::string_view to_string(DefectKind kind) {
    switch (kind) {
        case DefectKind::Corrosion:
            return "corrosion";
        case DefectKind::Crack:
            return "crack";
    }
    return "unknown";
}

std::string structural_map_to_json(const StructuralMap& map, std::span<const int> surface_tags) {
    Json j;
    j["name"] = map.name;
    j["surfaces"] = array_of(map.surfaces);
    j["compartments"] = array_of(map.compartments);
    j["connections"] = array_of(map.connections);
    j["frames"] = array_of(map.frames);
    j["longitudinals"] = array_of(map.longitudinals);
    j["landmarks"] = array_of(map.landmarks);
    j["defects"] = array_of(map.defects);
    if (!surface_tags.empty()) j["triangle_surface_tags"] = run_lengths(surface_tags);
    return j.dump(2) + "\n";
}

std::optional<int> compartment_at(const StructuralMap& map, const Eigen::Vector3d& p_world) {
    std::optional<int> best;
    double best_m3 = std::numeric_limits<double>::infinity();
    for (const Compartment& c : map.compartments) {
        // `!best`: a box too large for a finite volume still counts.
        if (contains(c.bounds, p_world) && (!best || volume(c.bounds) < best_m3)) {
            best_m3 = volume(c.bounds);
            best = c.id;
        }
    }
    return best;
}

const Compartment* find_compartment(const StructuralMap& map, int id) {
    for (const Compartment& c : map.compartments) {
        if (c.id == id) return &c;
    }
    return nullptr;
}

std::optional<int> nearest_frame(const StructuralMap& map, const Eigen::Vector3d& p_world) {
    return nearest(map.frames,
                   [&](const FrameLine& f) { return std::abs((p_world - f.point).dot(f.axis)); });
}

std::optional<int> nearest_longitudinal(const StructuralMap& map, const Eigen::Vector3d& p_world) {
    return nearest(map.longitudinals, [&](const FrameLine& l) {
        const Eigen::Vector3d d = p_world - l.point;
        return (d - d.dot(l.axis) * l.axis).norm();
    });
}

}  // namespace scantling::io
