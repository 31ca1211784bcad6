// Ground truth of surface obstacles (surface_obstacles_truth.hpp).
#include <scantling/sim/surface_obstacles_truth.hpp>

#include <algorithm>

namespace scantling::sim {

std::string_view to_string(ObstacleKind kind) {
    switch (kind) {
        case ObstacleKind::kWeldBead:
            return "weld_bead";
        case ObstacleKind::kBolt:
            return "bolt";
        case ObstacleKind::kBracket:
            return "bracket";
        case ObstacleKind::kHole:
            return "hole";
        case ObstacleKind::kPlateEdge:
            return "plate_edge";
    }
    return "unknown";
}

double ObstacleTruth::footprint_distance_m(const Eigen::Vector3d& p_world_m) const {
    const Eigen::Vector3d ab = b_world_m - a_world_m;
    const double length2 = ab.squaredNorm();
    // a == b (a round obstacle) degenerates to the distance from the centre.
    const double t =
        length2 > 0.0 ? std::clamp((p_world_m - a_world_m).dot(ab) / length2, 0.0, 1.0) : 0.0;
    return (p_world_m - (a_world_m + t * ab)).norm() - radius_m;
}

}  // namespace scantling::sim
