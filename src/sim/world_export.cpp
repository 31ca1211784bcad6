#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/io/mesh_io.hpp>
#include <scantling/io/output_transaction.hpp>
#include <scantling/io/ply.hpp>
#include <scantling/sim/world_export.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <system_error>

namespace scantling::sim {
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

}  // namespace

void WorldExportConfig::validate(std::string_view prefix) const {
    if (!(std::isfinite(map_spacing_m) && map_spacing_m > 0.0)) {
        throw ConfigError(
            fmt::format("{}.map_spacing_m = {}, expected > 0", prefix, map_spacing_m));
    }
}

std::string metadata_to_json(const WorldMetadata& metadata, std::span<const int> surface_tags) {
    Json j;
    j["name"] = metadata.name;
    j["surfaces"] = array_of(metadata.surfaces);
    j["compartments"] = array_of(metadata.compartments);
    j["connections"] = array_of(metadata.connections);
    j["frames"] = array_of(metadata.frames);
    j["longitudinals"] = array_of(metadata.longitudinals);
    j["landmarks"] = array_of(metadata.landmarks);
    j["defects"] = array_of(metadata.defects);
    if (!surface_tags.empty()) j["triangle_surface_tags"] = run_lengths(surface_tags);
    return j.dump(2) + "\n";
}

PointCloud sample_map(const World& world, double spacing_m, std::uint64_t seed) {
    Rng rng(seed);
    return sample_surface_spacing(world.mesh, spacing_m, rng);
}

void write_world(const std::string& directory, const World& world,
                 const WorldExportConfig& config) {
    config.validate();
    check_valid(world, "write_world");
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    if (error) throw FileError(directory, "cannot create the directory: " + error.message());
    const std::filesystem::path dir(directory);
    io::OutputTransaction outputs;  // the three files or none
    outputs.write((dir / "map.ply").string(), [&](const std::string& path) {
        io::write_ply(path, sample_map(world, config.map_spacing_m, config.seed));
    });
    outputs.write((dir / "mesh.ply").string(),
                  [&](const std::string& path) { io::write_mesh(path, world.mesh); });
    const std::string json = metadata_to_json(world.metadata, world.surface_tags);
    outputs.write_stream((dir / "metadata.json").string(), [&](std::ostream& out) { out << json; });
    outputs.commit();
}

}  // namespace scantling::sim
