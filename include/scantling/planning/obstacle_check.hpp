#pragma once
/// @file
/// Refuses a bad mission request (SPEC §4; D5.2 §II.1): a waypoint inside, or too close to, a
/// known obstacle. Given the known map as points (e.g. the structural map or a prior scan of
/// the tank), every waypoint must be at least `clearance_m` from the nearest map point; the
/// first that is not is named with its distance, so the operator can fix the request before
/// the flight instead of watching collision prevention stall the vehicle at it.
///
/// Only the waypoints are checked, not the straight legs between them: a leg that grazes an
/// obstacle is left to the safety layer (safety/collision_prevention.hpp), which brakes and
/// repels on the live LiDAR sweep. A clearance of collision prevention's d_min (0.8 m) keeps a
/// waypoint reachable without the repulsion fighting the controller.
///
/// Frames: the map and the path in the same (world) frame, metres. Thread-safety: pure
/// function. Cost: O(m log m) to index the map, O(log m) per waypoint.

#include <string_view>
#include <vector>

#include <scantling/core/point_cloud.hpp>
#include <scantling/planning/waypoints.hpp>

namespace scantling::planning {

/// Each waypoint's distance to the nearest map point, m, in path order (+inf for an empty
/// map: nothing is known to be in the way). Non-finite map points are skipped (no-returns).
/// Throws ConfigError for a bad path (planning::validate) or a clearance not finite ≥ 0, and
/// ConfigError naming the first waypoint closer than `clearance_m`:
/// "mission.waypoints[3] = (1.00, 2.00, 3.00) is 0.12 m from the map, expected >= clearance
/// 0.50 m".
std::vector<double> check_path_clear(const WaypointPath& path, const PointCloud& map_world,
                                     double clearance_m, std::string_view prefix = "mission");

}  // namespace scantling::planning
