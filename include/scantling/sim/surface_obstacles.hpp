#pragma once
/// @file
/// Bolts, brackets and weld beads placed on a world's crawler surface (issue 15, item 2), each
/// built as a closed mesh with its own surface and an ObstacleTruth (surface_obstacles_truth.hpp).
///
/// Placement: each position is projected on the crawler's surface (scenario.hpp: the plate's
/// top plane, the outside of a cylinder or storage-tank shell, else the world mesh); the
/// obstacle stands along the surface normal there, sunk kEmbed_m (plus the gap between the
/// surface and its facets) into the wall so that no ray passes between them.
///
/// Local frame at a surface point with normal n: local x is world x projected on the tangent
/// plane, or world z projected when that is shorter than 0.5 (n within 30° of ±world x, e.g. a
/// tank shell at azimuth 0); local y = n × x. So on a plate local x is world x, and on a hull's
/// side (normal ±y) it runs along the hull.
///
/// Determinism: the same world and configs give bit-identical triangles, tags and truths.

#include <Eigen/Core>
#include <span>
#include <string_view>

#include <scantling/core/surface_projector.hpp>
#include <scantling/sim/surface_obstacles_truth.hpp>
#include <scantling/sim/world.hpp>

namespace scantling::sim {

/// One obstacle placed on the crawler's surface (`world.obstacles[i]`); the keys that apply
/// depend on `kind`.
struct SurfaceObstacleConfig {
    ObstacleKind kind = ObstacleKind::kBolt;  ///< kBolt, kBracket or kWeldBead
    /// kBolt, kBracket: world point within kMaxOffSurface_m of the surface, m.
    Eigen::Vector3d position_world = Eigen::Vector3d::Zero();
    double diameter_m = 0.03;  ///< kBolt: cylinder diameter
    double height_m = 0.02;    ///< kBolt, kWeldBead: proud of the surface
    /// kBracket: box sides along local x, local y and the normal (before the yaw), m.
    Eigen::Vector3d size_m{0.12, 0.06, 0.08};
    double yaw_deg = 0.0;  ///< kBracket: turn about the normal from local x, degrees
    /// kWeldBead: the ends, each within kMaxOffSurface_m of the surface, m.
    Eigen::Vector3d from_world = Eigen::Vector3d::Zero();
    Eigen::Vector3d to_world = Eigen::Vector3d::UnitX();
    double width_m = 0.03;  ///< kWeldBead: across the bead

    /// Throws ConfigError naming the field ("<prefix>.diameter_m = 0, expected in (0, 10]"),
    /// also for a kind that cannot be placed (kHole, kPlateEdge: holes are plate.holes) and a
    /// weld bead shorter than kMinBeadLength_m or longer than limits::kMaxWorldExtent_m.
    void validate(std::string_view prefix) const;
};

/// Farthest a position may lie from the crawler's surface, and the projected point from the
/// world's mesh (an obstacle beyond the edge of a plate would float).
inline constexpr double kMaxOffSurface_m = 0.1;
/// Depth an obstacle reaches into the wall below the surface.
inline constexpr double kEmbed_m = 0.002;
inline constexpr double kMinBeadLength_m = 0.01;

/// Throws ConfigError for more than limits::kMaxSurfaceObstacles obstacles (checked first,
/// before anything is sized by the list) or an invalid one ("<list_key>[i].<field>").
void validate_surface_obstacles(std::span<const SurfaceObstacleConfig> obstacles,
                                std::string_view list_key);

/// Builds `obstacles` on `world`: appends each one's triangles under a new surface named like
/// its truth ("bolt_1", "bracket_1", "weld_bead_1": numbered per kind in list order) and its
/// ObstacleTruth to world.obstacles. `surface` is the world's crawler surface (without these
/// obstacles). Truths: a bolt is a = b = its foot, radius diameter/2; a bracket the capsule
/// bounding its rectangle (axis along its longer side, radius = shorter side / √2); a bead
/// a = from, b = to (projected), radius width/2. A weld bead follows the surface in pieces of
/// 5 cm (at most 64 pieces); on a curved surface it must stay within width/2 of its chord a–b.
/// Throws ConfigError naming "<list_key>[i].<field>" for an invalid obstacle, a position more
/// than kMaxOffSurface_m off the surface ("... is 0.35 m off the surface, expected within
/// 0.1 m") or off the world's mesh, or a bead bending off its chord.
/// Cost: O(number of obstacles x surface projection); builds one MeshSurface of the world.
void add_surface_obstacles(World& world, const SurfaceProjector& surface,
                           std::span<const SurfaceObstacleConfig> obstacles,
                           std::string_view list_key = "world.obstacles");

}  // namespace scantling::sim
