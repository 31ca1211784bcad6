// The real hull of a mesh file standing in a dry dock or at a quay (issue 3, item 1
// `ship_hull`: the DTC hull of the shared data scaled to full size), and the surroundings
// shared with the parametric hull.
#include <scantling/core/error.hpp>
#include <scantling/io/mesh_io.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/world_hull.hpp>

#include "detail/defect_placement.hpp"
#include "detail/hull_surroundings.hpp"
#include "detail/mesh_builder.hpp"

#include <fmt/format.h>

namespace scantling::sim {
namespace {

constexpr std::string_view kPrefix = "ship_hull_mesh";
const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();
const Eigen::Vector3d kZ = Eigen::Vector3d::UnitZ();
// A keel block goes where the hull's centreline bottom is this close to the keel: the flat
// keel, not the rising bow and stern.
constexpr double kOnKeel_m = 0.05;
constexpr double kSiteMargin_m = 1.0;

// Scales the hull to metres and moves it to the hull frame: keel at z = 0, centred on y = 0,
// starting at x = 0.
void to_hull_frame(TriangleMesh& hull, double scale) {
    for (auto& v : hull.vertices) v *= scale;
    const Aabb b = compute_bounds(hull);
    const Eigen::Vector3d shift(-b.min.x(), -0.5 * (b.min.y() + b.max.y()), -b.min.z());
    for (auto& v : hull.vertices) v += shift;
}

std::vector<double> block_positions(const TriangleMesh& hull, const Aabb& b,
                                    const HullSurroundingsConfig& c) {
    const RayCaster caster(hull);
    const double below = c.keel_block_height_m;
    std::vector<double> xs;
    for (const double x : detail::centred_positions(b.min.x() + 0.5 * c.keel_block_length_m,
                                                    b.max.x() - 0.5 * c.keel_block_length_m,
                                                    c.keel_block_spacing_m)) {
        const RayHit hit = caster.cast({x, 0.0, b.min.z() - below}, kZ, below + kOnKeel_m);
        if (hit.hit) xs.push_back(x);
    }
    return xs;
}

// Appends `part`'s triangles, tags and vertices to `world`.
void append(World& world, const World& part) {
    const int base = static_cast<int>(world.mesh.vertices.size());
    world.mesh.vertices.insert(world.mesh.vertices.end(), part.mesh.vertices.begin(),
                               part.mesh.vertices.end());
    for (const Eigen::Vector3i& t : part.mesh.triangles) {
        world.mesh.triangles.push_back((t.array() + base).matrix());
    }
    world.surface_tags.insert(world.surface_tags.end(), part.surface_tags.begin(),
                              part.surface_tags.end());
}

WorldMetadata metadata_of(const HullMeshDockConfig& c, const Aabb& hull) {
    WorldMetadata m;
    m.name = std::string(kPrefix);
    m.compartments.push_back({0, "site", {}, 0});
    for (int k = 0; hull.min.x() + k * c.frame_spacing_m <= hull.max.x() + 1e-9; ++k) {
        m.frames.push_back({k, {hull.min.x() + k * c.frame_spacing_m, 0.0, 0.0}, kX, "hull"});
    }
    return m;
}

}  // namespace

World build_hull_mesh_in_dock(const HullMeshDockConfig& config) {
    config.validate(kPrefix);
    World world;
    world.mesh = io::read_mesh(config.path);
    to_hull_frame(world.mesh, config.scale);
    world.surface_tags.assign(world.mesh.num_triangles(), 0);
    const Aabb b = compute_bounds(world.mesh);
    detail::MeshBuilder builder;
    builder.surface("hull");  // tag 0, the hull's
    const auto& s = config.surroundings;
    const detail::HullExtent extent{b.min.x(), b.max.x(), b.max.y(), b.min.z(),
                                    s.environment == HullEnvironment::kDryDock
                                        ? block_positions(world.mesh, b, s)
                                        : std::vector<double>{}};
    detail::add_surroundings(builder, extent, s);
    const World surroundings = builder.finish(metadata_of(config, b));
    append(world, surroundings);
    world.metadata = surroundings.metadata;
    Aabb site = compute_bounds(world.mesh);
    site.min.array() -= kSiteMargin_m;
    site.max.array() += kSiteMargin_m;
    world.metadata.compartments[0].bounds = site;
    const int hull_tag = 0;
    detail::place_defects(world, config.defects, std::span<const int>(&hull_tag, 1),
                          fmt::format("{}.defects", kPrefix));
    return world;
}

void HullMeshDockConfig::validate(std::string_view prefix) const {
    if (path.empty()) {
        throw ConfigError(
            fmt::format("{}.path = \"\", expected a mesh file (OBJ, STL, PLY)", prefix));
    }
    detail::require_positive(prefix, "scale", scale);
    detail::require_positive(prefix, "frame_spacing_m", frame_spacing_m);
    surroundings.validate(fmt::format("{}.surroundings", prefix));
    defects.validate(fmt::format("{}.defects", prefix));
}

}  // namespace scantling::sim
