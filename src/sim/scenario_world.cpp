// The world of a scenario: its builder, then the obstacles on the crawler's surface
// (scenario.hpp build_world).
#include <filesystem>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/sim/scenario.hpp>

#include "detail/scenario_parts.hpp"

namespace scantling::sim {
namespace {

/// `path` relative to `base_directory` unless absolute (or no base is given).
std::string resolve_path(const std::string& path, const std::string& base_directory) {
    const std::filesystem::path file(path);
    if (path.empty() || file.is_absolute() || base_directory.empty()) return path;
    return (std::filesystem::path(base_directory) / file).string();
}

World build_base_world(const WorldSpec& spec, const std::string& base_directory) {
    switch (spec.type) {
        case WorldType::kBallastTankMockup:
            return build_ballast_tank_mockup(spec.ballast_tank_mockup);
        case WorldType::kBallastTankLarge:
            return build_ballast_tank_large(spec.ballast_tank_large);
        case WorldType::kStorageTank:
            return build_storage_tank(spec.storage_tank);
        case WorldType::kDistillationColumn:
            return build_distillation_column(spec.distillation_column);
        case WorldType::kCylinder:
            return build_cylinder(spec.cylinder);
        case WorldType::kPlate:
            return build_plate(spec.plate);
        case WorldType::kShipHull:
            return build_ship_hull(spec.ship_hull);
        case WorldType::kMoebius:
            return build_moebius(spec.moebius);
        case WorldType::kUrban:
            return build_urban(spec.urban);
        case WorldType::kShipHullMesh: {
            HullMeshDockConfig config = spec.ship_hull_mesh;
            config.path = resolve_path(config.path, base_directory);
            return build_hull_mesh_in_dock(config);
        }
        case WorldType::kMesh: {
            MeshWorldConfig config = spec.mesh;
            config.path = resolve_path(config.path, base_directory);
            return build_mesh_world(config);
        }
    }
    throw ConfigError("world.type: unknown value");
}

}  // namespace

World build_world(const WorldSpec& spec, const std::string& base_directory) {
    World world = build_base_world(spec, base_directory);
    if (spec.obstacles.empty()) return world;
    // Placed on the surface of the bare world: obstacles never stand on each other.
    const auto surface = detail::crawler_surface(spec, world);
    add_surface_obstacles(world, *surface, spec.obstacles, "world.obstacles");
    return world;
}

}  // namespace scantling::sim
