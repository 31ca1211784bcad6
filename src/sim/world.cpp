#include <scantling/core/error.hpp>
#include <scantling/sim/world.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace scantling::sim {
namespace {

// A point this close to a defect's plane counts as on it (sensor hits carry ~mm noise only
// when noise is added after the lookup).
constexpr double kDefectPlaneTolerance_m = 0.01;

void check_index(int index, std::size_t size, std::string_view what, std::string_view field,
                 std::size_t item, bool allow_outside = false) {
    const bool outside_ok = allow_outside && index == Connection::kOutside;
    if (!outside_ok && (index < 0 || static_cast<std::size_t>(index) >= size)) {
        throw InputError(fmt::format("{}: {} {} = {}, expected an index below {}", what, field,
                                     item, index, size));
    }
}

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) {
    const Eigen::Vector3d ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (p - (a + t * ab)).norm();
}

void check_obstacles(const std::vector<ObstacleTruth>& obstacles, std::string_view what) {
    std::set<std::string_view> names;
    for (std::size_t i = 0; i < obstacles.size(); ++i) {
        const ObstacleTruth& o = obstacles[i];
        const bool finite = o.a_world_m.allFinite() && o.b_world_m.allFinite() &&
                            std::isfinite(o.radius_m) && std::isfinite(o.height_m);
        if (!finite || !(o.radius_m > 0.0) || o.height_m == 0.0) {
            throw InputError(
                fmt::format("{}: obstacle {} '{}': radius_m = {}, height_m = {}, expected finite, "
                            "radius_m > 0 and height_m != 0",
                            what, i, o.name, o.radius_m, o.height_m));
        }
        if (!names.insert(o.name).second) {
            throw InputError(fmt::format("{}: obstacle {}: name '{}' repeated", what, i, o.name));
        }
    }
}

}  // namespace

void check_valid(const World& world, std::string_view what) {
    check_valid(world.mesh, what);
    const WorldMetadata& m = world.metadata;
    if (world.surface_tags.size() != world.mesh.num_triangles()) {
        throw InputError(fmt::format("{}: {} surface tags for {} triangles", what,
                                     world.surface_tags.size(), world.mesh.num_triangles()));
    }
    for (std::size_t i = 0; i < world.surface_tags.size(); ++i) {
        check_index(world.surface_tags[i], m.surfaces.size(), what, "surface tag of triangle", i);
    }
    for (std::size_t i = 0; i < m.connections.size(); ++i) {
        const Connection& c = m.connections[i];
        check_index(c.compartment_a, m.compartments.size(), what, "compartment_a of connection", i);
        check_index(c.compartment_b, m.compartments.size(), what, "compartment_b of connection", i,
                    true);
    }
    for (std::size_t i = 0; i < m.landmarks.size(); ++i) {
        check_index(m.landmarks[i].compartment, m.compartments.size(), what,
                    "compartment of landmark", i);
    }
    for (std::size_t i = 0; i < m.defects.size(); ++i) {
        check_index(m.defects[i].surface_tag, m.surfaces.size(), what, "surface_tag of defect", i);
        check_index(m.defects[i].compartment, m.compartments.size(), what, "compartment of defect",
                    i, true);
    }
    check_obstacles(world.obstacles, what);
}

int find_surface(const WorldMetadata& metadata, std::string_view name) {
    for (const Surface& s : metadata.surfaces) {
        if (s.name == name) return s.tag;
    }
    return -1;
}

int defect_at(const WorldMetadata& metadata, const Eigen::Vector3d& p, int surface_tag) {
    for (const Defect& d : metadata.defects) {
        if (d.surface_tag != surface_tag) continue;
        if (std::abs((p - d.centre).dot(d.normal)) > kDefectPlaneTolerance_m) continue;
        const double distance_m = d.kind == DefectKind::Crack
                                      ? distance_to_segment(p, d.centre - d.radius_m * d.direction,
                                                            d.centre + d.radius_m * d.direction)
                                      : (p - d.centre).norm();
        // Cracks are hairlines: count a hit within a crack "width" of 1 cm.
        const double reach_m = d.kind == DefectKind::Crack ? kDefectPlaneTolerance_m : d.radius_m;
        if (distance_m <= reach_m) return d.id;
    }
    return -1;
}

}  // namespace scantling::sim
