#pragma once
/// @file
/// Go-to-point and go-home missions (SPEC §4; D5.2 §II.1): the operator records points by name
/// during a flight (e.g. "A", "manhole") and later sends the vehicle to one; go-home returns to
/// the take-off point.
///
/// Frames: world (z up, metres, radians). Thread-safety: `RecordedPoints` is a plain value
/// (not synchronised: one owner, the mission manager); the planners are pure functions.
/// Cost: O(log n) per look-up.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include <scantling/planning/waypoints.hpp>

namespace scantling::planning {

/// A point the operator recorded: where, and the heading then (optional).
struct RecordedPoint {
    Eigen::Vector3d p_world_m = Eigen::Vector3d::Zero();
    std::optional<double> yaw_rad;
};

/// Named points. Recording a name again replaces it (the operator re-marks a point).
class RecordedPoints {
  public:
    /// Throws InputError for an empty name or a non-finite position or yaw.
    void record(const std::string& name, const RecordedPoint& point);
    /// Throws InputError naming the unknown point and the known ones:
    /// "recorded point 'B' is unknown (recorded: A, manhole)".
    const RecordedPoint& at(std::string_view name) const;
    bool contains(std::string_view name) const;
    std::vector<std::string> names() const;  ///< sorted
    std::size_t size() const { return points_.size(); }

  private:
    std::map<std::string, RecordedPoint, std::less<>> points_;
};

/// SPEC gives only WP_tol.
struct GoToConfig {
    double waypoint_tolerance_m = kDefaultWaypointToleranceM;  ///< WP_tol (SPEC §4: 0.20 m)

    /// Throws ConfigError naming "<prefix>.waypoint_tolerance_m".
    void validate(std::string_view prefix = "go_to") const;
};

/// One waypoint at the recorded point `name` (with its yaw, if recorded). Throws InputError
/// for an unknown name, ConfigError for a bad config.
WaypointPath plan_go_to_point(const RecordedPoints& points, std::string_view name,
                              const GoToConfig& config = {});

/// One waypoint at the take-off point (yaw left to the controller). Throws InputError for a
/// non-finite point, ConfigError for a bad config.
WaypointPath plan_go_home(const Eigen::Vector3d& p_takeoff_world_m, const GoToConfig& config = {});

}  // namespace scantling::planning
