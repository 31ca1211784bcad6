#pragma once
/// @file
/// Ground truth of the obstacles on a world's surface (issue 15, item 2): the weld beads,
/// bolts and brackets a scenario places on the crawler's surface (surface_obstacles.hpp), the
/// holes cut through a plate and the plate's outline. A stop-and-map perception is scored
/// against these per class (precision and recall).
///
/// Frame: world, metres. Each obstacle is a capsule lying on the surface: its axis segment a–b
/// lies on the surface and radius_m bounds (or, for a hole, fills) its footprint.

#include <Eigen/Core>
#include <string>
#include <string_view>

namespace scantling::sim {

enum class ObstacleKind { kWeldBead, kBolt, kBracket, kHole, kPlateEdge };

/// "weld_bead", "bolt", "bracket", "hole", "plate_edge".
std::string_view to_string(ObstacleKind kind);

/// Ground truth of one obstacle on a surface as a capsule lying on the surface: the segment a–b
/// (a == b for a round or compact one) swept by radius_m in the surface's tangent plane.
struct ObstacleTruth {
    ObstacleKind kind = ObstacleKind::kBolt;
    std::string name{};                                   ///< unique in the world, e.g. "bolt_2"
    Eigen::Vector3d a_world_m = Eigen::Vector3d::Zero();  ///< on the surface
    Eigen::Vector3d b_world_m = Eigen::Vector3d::Zero();
    double radius_m = 0.0;  ///< footprint half-width, > 0
    /// > 0 proud of the surface (positive obstacle); < 0 a negative one (hole, plate edge).
    double height_m = 0.0;
    bool positive() const { return height_m > 0.0; }
    /// Distance from p to the capsule's axis segment minus radius_m (<= 0 inside the footprint).
    double footprint_distance_m(const Eigen::Vector3d& p_world_m) const;
};

}  // namespace scantling::sim
