#pragma once
/// @file
/// The waypoint list every MAV mission is (SPEC §4; D5.2 §II.1): positions in the world frame,
/// each reached when the vehicle is within its tolerance WP_tol (SPEC: e.g. 0.20 m), with an
/// optional heading to hold there.
///
/// Frame: world (right-handed, z up, metres); yaw is about world z, radians, 0 along world x.
/// Thread-safety: plain values. Cost: none beyond the vector.

#include <Eigen/Core>
#include <optional>
#include <string_view>
#include <vector>

namespace scantling::planning {

/// SPEC §4's WP_tol: a waypoint counts as reached within this distance.
inline constexpr double kDefaultWaypointToleranceM = 0.20;

struct Waypoint {
    Eigen::Vector3d p_world_m = Eigen::Vector3d::Zero();  ///< position to reach
    std::optional<double> yaw_rad;  ///< heading to hold (nullopt: the controller keeps its own)
    double tolerance_m = kDefaultWaypointToleranceM;  ///< WP_tol, > 0
};

/// A mission as the controller flies it: the waypoints in order.
struct WaypointPath {
    std::vector<Waypoint> waypoints;
};

/// The heading that looks along `direction_world` projected on the horizontal plane (the
/// camera of a multirotor faces where its body x points). Undefined for a vertical direction:
/// callers check that it has a horizontal part.
double yaw_facing(const Eigen::Vector3d& direction_world);

/// Throws ConfigError ("<prefix>.waypoints[3].tolerance_m = 0, expected finite > 0") for a
/// non-finite position or yaw or a tolerance ≤ 0; an empty path is allowed (nothing to fly).
void validate(const WaypointPath& path, std::string_view prefix = "path");

}  // namespace scantling::planning
