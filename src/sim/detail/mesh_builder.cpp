#include "mesh_builder.hpp"

#include "polygon_triangulation.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <map>
#include <numbers>

namespace scantling::sim::detail {
namespace {

// In-plane basis (u, v) with u × v = n, u along the loop's first edge.
std::pair<Eigen::Vector3d, Eigen::Vector3d> plane_basis(const Loop3& loop,
                                                        const Eigen::Vector3d& n) {
    Eigen::Vector3d u = loop[1] - loop[0];
    u -= u.dot(n) * n;
    if (u.squaredNorm() == 0.0) u = n.unitOrthogonal();
    u.normalize();
    return {u, n.cross(u)};
}

Loop2 project(const Loop3& loop, const Eigen::Vector3d& origin, const Eigen::Vector3d& u,
              const Eigen::Vector3d& v) {
    Loop2 out;
    out.reserve(loop.size());
    for (const auto& p : loop) out.emplace_back((p - origin).dot(u), (p - origin).dot(v));
    return out;
}

Loop3 shifted(const Loop3& loop, const Eigen::Vector3d& offset) {
    Loop3 out;
    out.reserve(loop.size());
    for (const auto& p : loop) out.push_back(p + offset);
    return out;
}

std::vector<Loop3> shifted(const std::vector<Loop3>& loops, const Eigen::Vector3d& offset) {
    std::vector<Loop3> out;
    for (const auto& loop : loops) out.push_back(shifted(loop, offset));
    return out;
}

// The loop in the order that is counter-clockwise about n (or clockwise).
Loop3 oriented(const Loop3& loop, const Eigen::Vector3d& n, bool counter_clockwise) {
    const auto [u, v] = plane_basis(loop, n);
    const bool ccw = signed_area(project(loop, loop[0], u, v)) > 0.0;
    return ccw == counter_clockwise ? loop : Loop3(loop.rbegin(), loop.rend());
}

// Unit-cube corners i = (x, y, z) bits; quads counter-clockwise seen from outside.
constexpr std::array<std::array<int, 4>, 6> kBoxQuads{
    {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};

}  // namespace

Box box_between(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                const Eigen::Vector3d& w, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    Box box;
    Eigen::Vector3d l = lo, h = hi;
    Eigen::Vector3d w_right = w;
    if (u.cross(v).dot(w) < 0.0) {  // left-handed: flip w so faces stay outward
        w_right = -w;
        l.z() = -hi.z();
        h.z() = -lo.z();
    }
    box.axes.col(0) = u;
    box.axes.col(1) = v;
    box.axes.col(2) = w_right;
    box.centre = origin + box.axes * (0.5 * (l + h));
    box.half_size_m = 0.5 * (h - l);
    return box;
}

int MeshBuilder::surface(const std::string& name, bool textured, double albedo) {
    for (const Surface& s : surfaces_) {
        if (s.name == name) return s.tag;
    }
    const int tag = static_cast<int>(surfaces_.size());
    surfaces_.push_back({tag, name, textured, albedo});
    return tag;
}

void MeshBuilder::add_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c, int tag) {
    const int base = static_cast<int>(vertices_.size());
    vertices_.insert(vertices_.end(), {a, b, c});
    triangles_.emplace_back(base, base + 1, base + 2);
    tags_.push_back(tag);
}

void MeshBuilder::add_quad(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c, const Eigen::Vector3d& d, int tag) {
    add_triangle(a, b, c, tag);
    add_triangle(a, c, d, tag);
}

void MeshBuilder::add_polygon(const Loop3& outer, const std::vector<Loop3>& holes,
                              const Eigen::Vector3d& normal, int tag) {
    const Eigen::Vector3d n = normal.normalized();
    const auto [u, v] = plane_basis(outer, n);
    std::vector<Loop2> holes_2d;
    Loop3 all = outer;
    for (const Loop3& hole : holes) {
        holes_2d.push_back(project(hole, outer[0], u, v));
        all.insert(all.end(), hole.begin(), hole.end());
    }
    for (const auto& t : triangulate_polygon(project(outer, outer[0], u, v), holes_2d)) {
        add_triangle(all[t[0]], all[t[1]], all[t[2]], tag);
    }
}

void MeshBuilder::add_slab(const Loop3& outer, const std::vector<Loop3>& holes,
                           const Eigen::Vector3d& normal, double thickness_m, int tag,
                           bool outline_rim) {
    const Eigen::Vector3d n = normal.normalized();
    const Eigen::Vector3d half = 0.5 * thickness_m * n;
    add_polygon(shifted(outer, half), shifted(holes, half), n, tag);
    add_polygon(shifted(outer, -half), shifted(holes, -half), -n, tag);
    auto add_rim = [&](const Loop3& loop) {  // loop counter-clockwise about n around material
        for (std::size_t i = 0; i < loop.size(); ++i) {
            const Eigen::Vector3d& a = loop[i];
            const Eigen::Vector3d& b = loop[(i + 1) % loop.size()];
            add_quad(a - half, b - half, b + half, a + half, tag);
        }
    };
    if (outline_rim) add_rim(oriented(outer, n, true));
    for (const Loop3& hole : holes) add_rim(oriented(hole, n, false));
}

void MeshBuilder::add_box(const Box& box, int tag) {
    std::array<Eigen::Vector3d, 8> corners;
    for (int i = 0; i < 8; ++i) {
        const Eigen::Vector3d sign(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0);
        corners[i] = box.centre + box.axes * sign.cwiseProduct(box.half_size_m);
    }
    for (const auto& q : kBoxQuads) {
        add_quad(corners[q[0]], corners[q[1]], corners[q[2]], corners[q[3]], tag);
    }
}

void MeshBuilder::add_cylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& axis,
                               const Eigen::Vector3d& radial, double radius_m, double length_m,
                               int segments, bool outward, bool caps, int tag) {
    const Loop3 bottom = circle_points(base, axis, radial, radius_m, segments);
    const Loop3 top = shifted(bottom, length_m * axis);
    for (int k = 0; k < segments; ++k) {
        const int k1 = (k + 1) % segments;
        if (outward) {
            add_quad(bottom[k], bottom[k1], top[k1], top[k], tag);
        } else {
            add_quad(bottom[k], top[k], top[k1], bottom[k1], tag);
        }
    }
    if (!caps) return;
    add_polygon(bottom, {}, outward ? Eigen::Vector3d(-axis) : axis, tag);
    add_polygon(top, {}, outward ? axis : Eigen::Vector3d(-axis), tag);
}

World MeshBuilder::finish(WorldMetadata metadata) const {
    World world;
    std::map<std::array<double, 3>, int> index_of;
    std::vector<int> remap(vertices_.size());
    for (std::size_t i = 0; i < vertices_.size(); ++i) {
        const Eigen::Vector3d& p = vertices_[i];
        const auto [it, inserted] = index_of.emplace(std::array<double, 3>{p.x(), p.y(), p.z()},
                                                     static_cast<int>(world.mesh.vertices.size()));
        if (inserted) world.mesh.vertices.push_back(p);
        remap[i] = it->second;
    }
    for (std::size_t t = 0; t < triangles_.size(); ++t) {
        const Eigen::Vector3i tri(remap[triangles_[t][0]], remap[triangles_[t][1]],
                                  remap[triangles_[t][2]]);
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
        world.mesh.triangles.push_back(tri);
        world.surface_tags.push_back(tags_[t]);
    }
    metadata.surfaces = surfaces_;
    world.metadata = std::move(metadata);
    return world;
}

Loop3 circle_points(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis,
                    const Eigen::Vector3d& radial, double radius_m, int segments) {
    const Eigen::Vector3d e2 = axis.cross(radial);
    Loop3 ring;
    ring.reserve(static_cast<std::size_t>(segments));
    for (int k = 0; k < segments; ++k) {
        const double angle = 2.0 * std::numbers::pi * k / segments;
        ring.push_back(centre + radius_m * (std::cos(angle) * radial + std::sin(angle) * e2));
    }
    return ring;
}

Loop3 rectangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                double u0, double u1, double v0, double v1) {
    return {origin + u0 * u + v0 * v, origin + u1 * u + v0 * v, origin + u1 * u + v1 * v,
            origin + u0 * u + v1 * v};
}

}  // namespace scantling::sim::detail
