// The simple worlds: a flat (optionally stiffened) plate, an isolated cylinder (SPEC §9, §10)
// and any mesh file.
#include <scantling/core/se3.hpp>
#include <scantling/io/mesh_io.hpp>
#include <scantling/sim/world_builders.hpp>

#include "detail/defect_placement.hpp"
#include "detail/mesh_builder.hpp"
#include "detail/plate_holes.hpp"
#include "detail/tank_parts.hpp"

#include <fmt/format.h>

namespace scantling::sim {
namespace {

using detail::MeshBuilder;

const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();
const Eigen::Vector3d kZ = Eigen::Vector3d::UnitZ();

std::vector<int> tags_named(const World& world, std::string_view name) {
    return {find_surface(world.metadata, name)};
}

}  // namespace

World build_plate(const PlateConfig& config) {
    config.validate("plate");
    MeshBuilder builder;
    const double hx = 0.5 * config.length_m, hy = 0.5 * config.width_m;
    const double z = -0.5 * config.thickness_m;  // mid-plane: the top face is z = 0
    builder.add_slab({{-hx, -hy, z}, {hx, -hy, z}, {hx, hy, z}, {-hx, hy, z}},
                     detail::plate_hole_loops(config, z), kZ, config.thickness_m,
                     builder.surface("plate"));
    WorldMetadata metadata;
    metadata.name = "plate";
    if (config.stiffener_spacing_m > 0.0) {
        // The top face seen as a wall: longitudinals along x, v across y.
        const detail::Wall top{"plate", {-hx, -hy, 0}, {hx, -hy, 0}, {hx, hy, 0}, {-hx, hy, 0}, kZ,
                               {}};
        for (const double v : detail::even_positions(config.width_m, config.stiffener_spacing_m)) {
            const int number = static_cast<int>(metadata.longitudinals.size()) + 1;
            metadata.longitudinals.push_back(
                detail::add_longitudinal(builder, top, v, config.stiffener, number));
        }
    }
    World world = builder.finish(std::move(metadata));
    world.obstacles = detail::plate_obstacle_truths(config);
    detail::place_defects(world, config.defects, tags_named(world, "plate"), "plate.defects");
    return world;
}

World build_cylinder(const CylinderConfig& config) {
    config.validate("cylinder");
    MeshBuilder builder;
    builder.add_cylinder(Eigen::Vector3d::Zero(), kZ, kX, config.radius_m, config.height_m,
                         config.segments, true, config.closed, builder.surface("cylinder"));
    WorldMetadata metadata;
    metadata.name = "cylinder";
    World world = builder.finish(std::move(metadata));
    detail::place_defects(world, config.defects, tags_named(world, "cylinder"), "cylinder.defects");
    return world;
}

World build_mesh_world(const MeshWorldConfig& config) {
    config.validate("mesh");
    World world;
    world.mesh = io::read_mesh(config.path);
    for (auto& v : world.mesh.vertices) v *= config.scale;
    const Eigen::Matrix3d R =
        rotation_from_euler_zyx(config.rpy_rad.x(), config.rpy_rad.y(), config.rpy_rad.z());
    transform_in_place(world.mesh, make_isometry(R, config.position_m));
    world.surface_tags.assign(world.mesh.num_triangles(), 0);
    world.metadata.name = "mesh";
    world.metadata.surfaces.push_back({0, "mesh", true, 0.5});
    detail::place_defects(world, config.defects, tags_named(world, "mesh"), "mesh.defects");
    return world;
}

}  // namespace scantling::sim
