#pragma once
// Small analytic worlds for the sensor tests: a box room, plates and occluder boxes, with
// surface metadata (albedo, texture) per tag.

#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/return_model.hpp>
#include <scantling/sim/sensor_mount.hpp>
#include <scantling/sim/world.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <limits>
#include <string>
#include <utility>

namespace scantling::sim::testing {

/// Adds surface `name` and returns its tag.
inline int add_surface(World& world, std::string name, bool textured = true, double albedo = 0.5) {
    const int tag = static_cast<int>(world.metadata.surfaces.size());
    world.metadata.surfaces.push_back(Surface{tag, std::move(name), textured, albedo});
    return tag;
}

/// Adds the quad a-b-c-d (two triangles) with `tag`.
inline void add_quad(World& world, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                     const Eigen::Vector3d& c, const Eigen::Vector3d& d, int tag) {
    const int base = static_cast<int>(world.mesh.vertices.size());
    for (const Eigen::Vector3d& p : {a, b, c, d}) world.mesh.vertices.push_back(p);
    world.mesh.triangles.emplace_back(base, base + 1, base + 2);
    world.mesh.triangles.emplace_back(base, base + 2, base + 3);
    world.surface_tags.insert(world.surface_tags.end(), 2, tag);
}

/// Adds the face `axis = (high ? hi : lo)[axis]` of the box [lo, hi].
inline void add_box_face(World& world, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                         int axis, bool high, int tag) {
    const int a = (axis + 1) % 3;
    const int b = (axis + 2) % 3;
    Eigen::Vector3d corner[4];
    for (int k = 0; k < 4; ++k) {
        corner[k][axis] = high ? hi[axis] : lo[axis];
        corner[k][a] = (k == 1 || k == 2) ? hi[a] : lo[a];
        corner[k][b] = (k >= 2) ? hi[b] : lo[b];
    }
    add_quad(world, corner[0], corner[1], corner[2], corner[3], tag);
}

/// Adds all six faces of the box [lo, hi] with one tag (an occluder).
inline void add_box(World& world, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int tag) {
    for (int axis = 0; axis < 3; ++axis) {
        add_box_face(world, lo, hi, axis, false, tag);
        add_box_face(world, lo, hi, axis, true, tag);
    }
}

/// Box room [lo, hi] with walls tagged 0..5 = (-x, +x, -y, +y, -z, +z).
inline World box_room(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, bool textured = true,
                      double albedo = 0.5) {
    World world;
    const char* names[6] = {"wall_-x", "wall_+x", "wall_-y", "wall_+y", "floor", "ceiling"};
    for (int w = 0; w < 6; ++w) {
        const int tag = add_surface(world, names[w], textured, albedo);
        add_box_face(world, lo, hi, w / 2, w % 2 == 1, tag);
    }
    return world;
}

/// Square plate z = z_m, |x|, |y| <= half_size_m.
inline World plate_at_z(double z_m, double half_size_m, bool textured, double albedo = 0.5) {
    World world;
    const int tag = add_surface(world, "plate", textured, albedo);
    const double h = half_size_m;
    add_quad(world, {-h, -h, z_m}, {h, -h, z_m}, {h, h, z_m}, {-h, h, z_m}, tag);
    return world;
}

/// Distance from `origin` (inside the box) along unit `direction` to the box's boundary.
inline double box_exit_range(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                             const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    double t = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (direction[a] > 0.0) t = std::min(t, (hi[a] - origin[a]) / direction[a]);
        if (direction[a] < 0.0) t = std::min(t, (lo[a] - origin[a]) / direction[a]);
    }
    return t;
}

/// A world with its ray caster, viewable by sensors.
struct TestScene {
    World world;
    RayCaster caster;

    explicit TestScene(World w) : world(std::move(w)), caster(world.mesh, world.surface_tags) {}
    SceneView view() const { return SceneView{caster, world.metadata}; }
};

/// The same config with noise and dropouts off.
inline ReturnModel noiseless(ReturnModel model) {
    model.sigma_m = model.sigma_per_m = model.sigma_per_m2 = 0.0;
    model.dropout_probability = model.weak_dropout_probability = 0.0;
    return model;
}

}  // namespace scantling::sim::testing
