#include <scantling/control/waypoint_sequencer.hpp>

#include <utility>

#include <fmt/format.h>

#include <scantling/core/error.hpp>

namespace scantling::control {
namespace {

void require_finite(const Eigen::Vector3d& p, std::string_view what) {
    if (!p.allFinite()) {
        throw InputError(fmt::format("waypoint_sequencer: {} = ({}, {}, {}), expected finite", what,
                                     p.x(), p.y(), p.z()));
    }
}

}  // namespace

void TrackingConfig::validate(std::string_view prefix) const {
    vtp.validate(fmt::format("{}.vtp", prefix));
}

WaypointSequencer::WaypointSequencer(planning::WaypointPath path,
                                     const Eigen::Vector3d& p_start_world_m)
    : path_(std::move(path)), p_start_world_m_(p_start_world_m) {
    planning::validate(path_, "waypoint_sequencer.path");
    require_finite(p_start_world_m_, "p_start_world_m");
}

Eigen::Vector3d WaypointSequencer::previous_world_m() const {
    return current_ == 0 ? p_start_world_m_ : path_.waypoints[current_ - 1].p_world_m;
}

std::vector<std::size_t> WaypointSequencer::update(const Eigen::Vector3d& p_world_m) {
    require_finite(p_world_m, "p_world_m");
    std::vector<std::size_t> reached;
    while (!finished()) {
        const planning::Waypoint& wp = path_.waypoints[current_];
        if ((p_world_m - wp.p_world_m).norm() > wp.tolerance_m) break;
        reached.push_back(current_++);
    }
    return reached;
}

TrackingTarget WaypointSequencer::target(const Eigen::Vector3d& p_world_m,
                                         const TrackingConfig& config) const {
    config.validate();
    require_finite(p_world_m, "p_world_m");
    if (finished()) {  // hold at the last waypoint (or where the vehicle started)
        if (path_.waypoints.empty()) return {p_start_world_m_, std::nullopt, std::nullopt};
        const planning::Waypoint& last = path_.waypoints.back();
        return {last.p_world_m, last.yaw_rad, std::nullopt};
    }
    const planning::Waypoint& wp = path_.waypoints[current_];
    if (!config.use_vtp) return {wp.p_world_m, wp.yaw_rad, std::nullopt};
    const VtpResult vtp = virtual_target_point(p_world_m, previous_world_m(), wp.p_world_m,
                                               wp.tolerance_m, config.vtp);
    return {vtp.vtp_world_m, wp.yaw_rad, vtp};
}

}  // namespace scantling::control
