#pragma once
/// @file
/// The point the ROV's guidance chases (control/rov_guidance.hpp, mission/rov_stack.hpp): a
/// target that moves along the survey path at the survey speed, leg by leg, and waits at each leg's
/// end until the vehicle is within the waypoint's tolerance. The legs are read from the path at
/// every tick, so the hull-relative adaptation's moves (planning/hull_relative_adapter.hpp) take
/// effect at once. Thread-safety: one cursor per vehicle. Deterministic. Cost: O(1) per tick.
#include <Eigen/Core>
#include <cstddef>

#include <scantling/control/rov_guidance.hpp>
#include <scantling/planning/waypoints.hpp>

namespace scantling::control {

class PathCursor {
  public:
    /// The first leg runs from `p_start_world_m` to the path's first waypoint.
    PathCursor(const Eigen::Vector3d& p_start_world_m, double start_yaw_rad, double speed_mps);

    /// Restarts on a new path (the re-inspection) from where the vehicle is.
    void restart(const Eigen::Vector3d& p_world_m, double yaw_rad);

    /// Advances the target by speed · dt unless `hold` (the guidance paused, a back-off) and
    /// returns it; passes a waypoint once the target is at its end and `p_vehicle_world_m` is
    /// within its tolerance. Returns whether a waypoint was reached in this call.
    bool advance(const planning::WaypointPath& path, const Eigen::Vector3d& p_vehicle_world_m,
                 double dt_s, bool hold);

    /// The target for the guidance; zero velocity when held or waiting at a leg's end.
    GuidanceTarget target(const planning::WaypointPath& path) const;

    /// The waypoint flown to (path.size() when done).
    std::size_t next_index() const { return next_; }
    bool done(const planning::WaypointPath& path) const { return next_ >= path.waypoints.size(); }

  private:
    Eigen::Vector3d leg_start(const planning::WaypointPath& path) const;

    Eigen::Vector3d p_first_m_;  ///< where the first leg starts
    double first_yaw_rad_ = 0.0;
    double speed_mps_ = 0.0;
    std::size_t next_ = 0;
    double progress_m_ = 0.0;  ///< along the current leg
    bool moving_ = false;      ///< the target moved in the last advance
};

}  // namespace scantling::control
