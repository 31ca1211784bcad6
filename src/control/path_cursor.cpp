// The ROV's moving target along its path (path_cursor.hpp).
#include <scantling/control/path_cursor.hpp>

#include <algorithm>

namespace scantling::control {

PathCursor::PathCursor(const Eigen::Vector3d& p_start_world_m, double start_yaw_rad,
                       double speed_mps)
    : p_first_m_(p_start_world_m), first_yaw_rad_(start_yaw_rad), speed_mps_(speed_mps) {}

void PathCursor::restart(const Eigen::Vector3d& p_world_m, double yaw_rad) {
    p_first_m_ = p_world_m;
    first_yaw_rad_ = yaw_rad;
    next_ = 0;
    progress_m_ = 0.0;
    moving_ = false;
}

Eigen::Vector3d PathCursor::leg_start(const planning::WaypointPath& path) const {
    return next_ == 0 ? p_first_m_ : path.waypoints[next_ - 1].p_world_m;
}

bool PathCursor::advance(const planning::WaypointPath& path,
                         const Eigen::Vector3d& p_vehicle_world_m, double dt_s, bool hold) {
    moving_ = false;
    if (done(path)) return false;
    const planning::Waypoint& goal = path.waypoints[next_];
    const double length_m = (goal.p_world_m - leg_start(path)).norm();
    if (!hold && progress_m_ < length_m) {
        progress_m_ = std::min(length_m, progress_m_ + speed_mps_ * dt_s);
        moving_ = progress_m_ < length_m;
    }
    const bool at_end = progress_m_ >= length_m;
    if (!at_end || (p_vehicle_world_m - goal.p_world_m).norm() > goal.tolerance_m) return false;
    ++next_;
    progress_m_ = 0.0;
    return true;
}

GuidanceTarget PathCursor::target(const planning::WaypointPath& path) const {
    GuidanceTarget target;
    if (path.waypoints.empty()) {
        target.p_world_m = p_first_m_;
        target.yaw_rad = first_yaw_rad_;
        return target;
    }
    const std::size_t goal_index = std::min(next_, path.waypoints.size() - 1);
    const planning::Waypoint& goal = path.waypoints[goal_index];
    const Eigen::Vector3d start = done(path) ? goal.p_world_m : leg_start(path);
    const Eigen::Vector3d leg = goal.p_world_m - start;
    const double length_m = leg.norm();
    const double share = length_m > 0.0 ? std::min(1.0, progress_m_ / length_m) : 1.0;
    target.p_world_m = start + share * leg;
    target.yaw_rad = goal.yaw_rad.value_or(first_yaw_rad_);
    if (moving_ && length_m > 0.0) {
        const Eigen::Vector3d v = speed_mps_ * leg / length_m;
        target.v_horizontal_mps = v.head<2>();
        target.v_vertical_mps = v.z();
    }
    return target;
}

}  // namespace scantling::control
