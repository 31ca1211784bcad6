#pragma once
/// @file
/// Export of a world as a recording's `world/` folder (issue 3): the "CAD map" point cloud,
/// the mesh and the metadata as JSON.

#include <cstdint>
#include <string>
#include <string_view>

#include <scantling/core/point_cloud.hpp>
#include <scantling/sim/world.hpp>

namespace scantling::sim {

struct WorldExportConfig {
    double map_spacing_m = 0.02;  ///< mean spacing of the CAD-map samples (i.i.d., not a grid)
    std::uint64_t seed = 0;       ///< seed of the map sampling

    /// Throws ConfigError("<prefix>.map_spacing_m = 0, expected > 0").
    void validate(std::string_view prefix = "world_export") const;
};

/// The CAD map: round(area / spacing²) points drawn uniformly over the whole mesh (hidden faces
/// included), each with its triangle's normal, world frame. Deterministic for a given seed.
PointCloud sample_map(const World& world, double spacing_m, std::uint64_t seed);

/// Writes `<directory>/map.ply` (CAD map with normals), `<directory>/mesh.ply` (binary PLY)
/// and `<directory>/metadata.json` (io::structural_map_to_json with the surface tags), creating the
/// directory if needed; each file is written atomically. Throws ConfigError for a bad
/// config, InputError for an invalid world, FileError when a file cannot be written.
void write_world(const std::string& directory, const World& world,
                 const WorldExportConfig& config = {});

}  // namespace scantling::sim
