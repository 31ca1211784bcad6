#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/io/mesh_io.hpp>
#include <scantling/io/output_transaction.hpp>
#include <scantling/io/ply.hpp>
#include <scantling/io/structural_map.hpp>
#include <scantling/sim/world_export.hpp>

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <system_error>

namespace scantling::sim {

void WorldExportConfig::validate(std::string_view prefix) const {
    if (!(std::isfinite(map_spacing_m) && map_spacing_m > 0.0)) {
        throw ConfigError(
            fmt::format("{}.map_spacing_m = {}, expected > 0", prefix, map_spacing_m));
    }
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
    const std::string json = io::structural_map_to_json(world.metadata, world.surface_tags);
    outputs.write_stream((dir / "metadata.json").string(), [&](std::ostream& out) { out << json; });
    outputs.commit();
}

}  // namespace scantling::sim
