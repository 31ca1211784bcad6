// Bolts, brackets and weld beads on a world's crawler surface (surface_obstacles.hpp).
#include <scantling/sim/surface_obstacles.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/sim/scenario_limits.hpp>

#include "detail/mesh_builder.hpp"

namespace scantling::sim {
namespace {

using detail::MeshBuilder;

constexpr int kBoltSegments = 16;
constexpr double kBeadStep_m = 0.05;
constexpr int kMaxBeadPieces = 64;
/// Local x falls back to world z when world x projects shorter than this (see the header).
constexpr double kMinProjection = 0.5;

std::string key(std::string_view prefix, std::string_view field) {
    return fmt::format("{}.{}", prefix, field);
}

void check_size(std::string_view prefix, std::string_view field, double value) {
    if (std::isfinite(value) && value > 0.0 && value <= limits::kMaxSurfaceObstacleSize_m) return;
    throw ConfigError(fmt::format("{} = {}, expected in (0, {}]", key(prefix, field), value,
                                  limits::kMaxSurfaceObstacleSize_m));
}

void check_point(std::string_view prefix, std::string_view field, const Eigen::Vector3d& p) {
    if (p.allFinite() && p.cwiseAbs().maxCoeff() <= limits::kMaxCoordinate_m) return;
    throw ConfigError(fmt::format("{} = [{}, {}, {}], expected finite within {} m",
                                  key(prefix, field), p.x(), p.y(), p.z(),
                                  limits::kMaxCoordinate_m));
}

void check_bead(const SurfaceObstacleConfig& c, std::string_view prefix) {
    check_point(prefix, "from_world", c.from_world);
    check_point(prefix, "to_world", c.to_world);
    const double length_m = (c.to_world - c.from_world).norm();
    if (length_m >= kMinBeadLength_m && length_m <= limits::kMaxWorldExtent_m) return;
    throw ConfigError(fmt::format(
        "{}: the bead is {} m long (from_world to to_world), expected in "
        "[{}, {}] m",
        key(prefix, "to_world"), length_m, kMinBeadLength_m, limits::kMaxWorldExtent_m));
}

/// Local x at a surface point (the rule of the header).
Eigen::Vector3d local_x(const Eigen::Vector3d& n) {
    Eigen::Vector3d u = Eigen::Vector3d::UnitX() - n.x() * n;
    if (u.norm() < kMinProjection) u = Eigen::Vector3d::UnitZ() - n.z() * n;
    return u.normalized();
}

/// A surface point where an obstacle stands, and how deep it reaches into the wall.
struct Foot {
    SurfacePoint at;
    double embed_m = kEmbed_m;
};

/// Places obstacles: projects on the crawler surface and measures the gap to the world's
/// facets (a faceted shell lies inside its analytic cylinder).
class Placer {
  public:
    Placer(const World& world, const SurfaceProjector& surface)
        : surface_(surface), mesh_(world.mesh, false) {}

    /// `near`: p must lie within kMaxOffSurface_m of the surface (false for the points of a
    /// bead's chord, which the bend check judges).
    Foot foot(const Eigen::Vector3d& p, std::string_view field_key, bool near = true) const {
        const SurfacePoint at = surface_.project(p);
        const double off_m = (p - at.point).norm();
        if (near && !(off_m <= kMaxOffSurface_m)) {
            throw ConfigError(
                fmt::format("{} = [{}, {}, {}] is {:.3g} m off the surface, expected within {} m",
                            field_key, p.x(), p.y(), p.z(), off_m, kMaxOffSurface_m));
        }
        return Foot{at, kEmbed_m + gap_m(at.point, field_key)};
    }

  private:
    double gap_m(const Eigen::Vector3d& q, std::string_view field_key) const {
        const double gap = (mesh_.project(q).point - q).norm();
        if (gap <= kMaxOffSurface_m) return gap;
        throw ConfigError(fmt::format(
            "{}: the surface point [{}, {}, {}] is {:.3g} m from the world's mesh (beyond its "
            "edge?), expected within {} m",
            field_key, q.x(), q.y(), q.z(), gap, kMaxOffSurface_m));
    }

    const SurfaceProjector& surface_;
    MeshSurface mesh_;
};

ObstacleTruth add_bolt(MeshBuilder& builder, const Foot& f, const SurfaceObstacleConfig& c,
                       int tag) {
    const Eigen::Vector3d& n = f.at.normal;
    builder.add_cylinder(f.at.point - f.embed_m * n, n, local_x(n), 0.5 * c.diameter_m,
                         c.height_m + f.embed_m, kBoltSegments, true, true, tag);
    return {.kind = ObstacleKind::kBolt,
            .a_world_m = f.at.point,
            .b_world_m = f.at.point,
            .radius_m = 0.5 * c.diameter_m,
            .height_m = c.height_m};
}

ObstacleTruth add_bracket(MeshBuilder& builder, const Foot& f, const SurfaceObstacleConfig& c,
                          int tag) {
    const Eigen::Vector3d& n = f.at.normal;
    const Eigen::Vector3d x0 = local_x(n);
    const double yaw_rad = c.yaw_deg * std::numbers::pi / 180.0;
    const Eigen::Vector3d x = std::cos(yaw_rad) * x0 + std::sin(yaw_rad) * n.cross(x0);
    const Eigen::Vector3d y = n.cross(x);
    detail::Box box;
    box.centre = f.at.point + 0.5 * (c.size_m.z() - f.embed_m) * n;
    box.axes << x, y, n;
    box.half_size_m = 0.5 * Eigen::Vector3d(c.size_m.x(), c.size_m.y(), c.size_m.z() + f.embed_m);
    builder.add_box(box, tag);
    // The capsule bounding the rectangle: its axis along the longer side, reaching the corners.
    const bool along_x = c.size_m.x() >= c.size_m.y();
    const double long_m = along_x ? c.size_m.x() : c.size_m.y();
    const double short_m = along_x ? c.size_m.y() : c.size_m.x();
    const Eigen::Vector3d half_axis = 0.5 * (long_m - short_m) * (along_x ? x : y);
    return {.kind = ObstacleKind::kBracket,
            .a_world_m = f.at.point - half_axis,
            .b_world_m = f.at.point + half_axis,
            .radius_m = short_m / std::numbers::sqrt2,
            .height_m = c.size_m.z()};
}

/// The bead's cross-section at one foot: counter-clockwise about the direction `t` of travel.
std::array<Eigen::Vector3d, 4> bead_section(const Foot& f, const Eigen::Vector3d& d,
                                            const SurfaceObstacleConfig& c) {
    const Eigen::Vector3d& n = f.at.normal;
    const Eigen::Vector3d t = (d - d.dot(n) * n).normalized();
    const Eigen::Vector3d s = 0.5 * c.width_m * n.cross(t);
    const Eigen::Vector3d below = f.at.point - f.embed_m * n;
    const Eigen::Vector3d above = f.at.point + c.height_m * n;
    return {below - s, below + s, above + s, above - s};
}

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) {
    const Eigen::Vector3d ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (p - (a + t * ab)).norm();
}

/// The feet along a bead, from `from` to `to` in pieces of about kBeadStep_m; ConfigError naming
/// `field_key` when the path bends more than width/2 off the chord (its truth is the chord).
std::vector<Foot> bead_feet(const Placer& placer, const Foot& from, const Foot& to, double width_m,
                            const std::string& field_key) {
    const Eigen::Vector3d d = to.at.point - from.at.point;
    if (!(d.norm() >= kMinBeadLength_m)) {
        throw ConfigError(
            fmt::format("{}: the bead's ends are {} m apart on the surface, "
                        "expected >= {} m",
                        field_key, d.norm(), kMinBeadLength_m));
    }
    const int pieces =
        std::clamp(static_cast<int>(std::ceil(d.norm() / kBeadStep_m)), 1, kMaxBeadPieces);
    std::vector<Foot> feet{from};
    double bend_m = 0.0;
    for (int k = 1; k < pieces; ++k) {
        feet.push_back(placer.foot(from.at.point + (d * k) / pieces, field_key, false));
        bend_m =
            std::max(bend_m, distance_to_segment(feet.back().at.point, from.at.point, to.at.point));
    }
    feet.push_back(to);
    if (bend_m <= 0.5 * width_m) return feet;
    throw ConfigError(fmt::format(
        "{}: the bead bends {:.3g} m off its straight line from_world–to_world on this curved "
        "surface, expected within width_m / 2 = {} m; split it into shorter beads",
        field_key, bend_m, 0.5 * width_m));
}

ObstacleTruth add_bead(MeshBuilder& builder, const Placer& placer, const SurfaceObstacleConfig& c,
                       std::string_view prefix, int tag) {
    const Foot from = placer.foot(c.from_world, key(prefix, "from_world"));
    const Foot to = placer.foot(c.to_world, key(prefix, "to_world"));
    const Eigen::Vector3d d = to.at.point - from.at.point;
    std::vector<std::array<Eigen::Vector3d, 4>> sections;
    for (const Foot& f : bead_feet(placer, from, to, c.width_m, key(prefix, "to_world"))) {
        sections.push_back(bead_section(f, d, c));
    }
    for (std::size_t k = 0; k + 1 < sections.size(); ++k) {
        const auto& p = sections[k];
        const auto& q = sections[k + 1];
        for (int i = 0; i < 4; ++i) {
            builder.add_quad(p[i], p[(i + 1) % 4], q[(i + 1) % 4], q[i], tag);
        }
    }
    const auto& first = sections.front();
    const auto& last = sections.back();
    builder.add_quad(first[3], first[2], first[1], first[0], tag);
    builder.add_quad(last[0], last[1], last[2], last[3], tag);
    return {.kind = ObstacleKind::kWeldBead,
            .a_world_m = from.at.point,
            .b_world_m = to.at.point,
            .radius_m = 0.5 * c.width_m,
            .height_m = c.height_m};
}

ObstacleTruth add_obstacle(MeshBuilder& builder, const Placer& placer,
                           const SurfaceObstacleConfig& c, std::string_view prefix, int tag) {
    if (c.kind == ObstacleKind::kWeldBead) return add_bead(builder, placer, c, prefix, tag);
    const Foot f = placer.foot(c.position_world, key(prefix, "position_world"));
    return c.kind == ObstacleKind::kBolt ? add_bolt(builder, f, c, tag)
                                         : add_bracket(builder, f, c, tag);
}

/// Appends `part`'s triangles to `world` under new surfaces (tags shifted past world's).
void append_part(World& world, World part) {
    const int base_tag = static_cast<int>(world.metadata.surfaces.size());
    if (!world.mesh.vertex_normals.empty()) compute_vertex_normals(part.mesh);
    append(world.mesh, part.mesh);
    for (const int tag : part.surface_tags) world.surface_tags.push_back(base_tag + tag);
    for (Surface s : part.metadata.surfaces) {
        s.tag += base_tag;
        world.metadata.surfaces.push_back(std::move(s));
    }
}

}  // namespace

void SurfaceObstacleConfig::validate(std::string_view prefix) const {
    switch (kind) {
        case ObstacleKind::kBolt:
            check_point(prefix, "position_world", position_world);
            check_size(prefix, "diameter_m", diameter_m);
            return check_size(prefix, "height_m", height_m);
        case ObstacleKind::kBracket:
            check_point(prefix, "position_world", position_world);
            check_size(prefix, "size_m[0]", size_m.x());
            check_size(prefix, "size_m[1]", size_m.y());
            check_size(prefix, "size_m[2]", size_m.z());
            if (std::isfinite(yaw_deg) && std::abs(yaw_deg) <= 360.0) return;
            throw ConfigError(
                fmt::format("{} = {}, expected in [-360, 360]", key(prefix, "yaw_deg"), yaw_deg));
        case ObstacleKind::kWeldBead:
            check_size(prefix, "width_m", width_m);
            check_size(prefix, "height_m", height_m);
            return check_bead(*this, prefix);
        case ObstacleKind::kHole:
        case ObstacleKind::kPlateEdge:
            break;
    }
    throw ConfigError(
        fmt::format("{} = {}, expected one of bolt, bracket, weld_bead (holes are "
                    "cut with plate.holes; plate edges come with every plate)",
                    key(prefix, "kind"), to_string(kind)));
}

void validate_surface_obstacles(std::span<const SurfaceObstacleConfig> obstacles,
                                std::string_view list_key) {
    if (obstacles.size() > limits::kMaxSurfaceObstacles) {
        throw ConfigError(fmt::format("{} has {} obstacles, expected at most {}", list_key,
                                      obstacles.size(), limits::kMaxSurfaceObstacles));
    }
    for (std::size_t i = 0; i < obstacles.size(); ++i) {
        obstacles[i].validate(fmt::format("{}[{}]", list_key, i));
    }
}

void add_surface_obstacles(World& world, const SurfaceProjector& surface,
                           std::span<const SurfaceObstacleConfig> obstacles,
                           std::string_view list_key) {
    validate_surface_obstacles(obstacles, list_key);
    if (obstacles.empty()) return;
    const Placer placer(world, surface);
    MeshBuilder builder;
    std::array<int, 5> count{};
    std::vector<ObstacleTruth> truths;
    for (std::size_t i = 0; i < obstacles.size(); ++i) {
        const SurfaceObstacleConfig& c = obstacles[i];
        const std::string name =
            fmt::format("{}_{}", to_string(c.kind), ++count[static_cast<std::size_t>(c.kind)]);
        ObstacleTruth truth = add_obstacle(builder, placer, c, fmt::format("{}[{}]", list_key, i),
                                           builder.surface(name));
        truth.name = name;
        truths.push_back(std::move(truth));
    }
    append_part(world, builder.finish({}));
    world.obstacles.insert(world.obstacles.end(), truths.begin(), truths.end());
}

}  // namespace scantling::sim
