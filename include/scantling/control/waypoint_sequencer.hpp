#pragma once
/// @file
/// Flies a waypoint list (SPEC §4; D5.2 §II.1): keeps the current waypoint, advances when the
/// vehicle is within its WP_tol (reporting each waypoint reached), and gives the position
/// controller its target: the current waypoint itself (follower off) or the Virtual Target
/// Point on the segment from the previous waypoint (follower on, vtp_follower.hpp). The first
/// waypoint's "previous" is the vehicle's start position. After the last waypoint (or with an
/// empty path) the target stays at the last waypoint (or the start): the vehicle holds there.
///
/// Frames: world (metres, radians). Thread-safety: mutable; one instance per mission.
/// Cost: O(1) per update (plus the waypoints reached in it).

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include <scantling/control/vtp_follower.hpp>
#include <scantling/planning/waypoints.hpp>

namespace scantling::control {

struct TrackingConfig {
    bool use_vtp = true;  ///< follower on (target the VTP) or off (target the waypoint)
    VtpConfig vtp{};      ///< δ, λ (SPEC §4: 2.0 m, 0.2 m)

    /// Throws ConfigError naming "<prefix>.vtp.<field>".
    void validate(std::string_view prefix = "tracking") const;
};

/// What the position controller should chase now.
struct TrackingTarget {
    Eigen::Vector3d p_target_world_m = Eigen::Vector3d::Zero();
    std::optional<double> yaw_rad;  ///< the current waypoint's, if it has one
    std::optional<VtpResult> vtp;   ///< set when the follower chose the target
};

class WaypointSequencer {
  public:
    /// Throws ConfigError for a bad path (planning::validate), InputError for a non-finite start.
    WaypointSequencer(planning::WaypointPath path, const Eigen::Vector3d& p_start_world_m);

    /// Advances past every waypoint (in order) within its tolerance of `p_world_m` and returns
    /// their indices: the "waypoint reached" events. Throws InputError for a non-finite position.
    std::vector<std::size_t> update(const Eigen::Vector3d& p_world_m);

    /// The target for `p_world_m` under `config` (call after update()). Throws InputError for a
    /// non-finite position, ConfigError for a bad config.
    TrackingTarget target(const Eigen::Vector3d& p_world_m,
                          const TrackingConfig& config = {}) const;

    bool finished() const { return current_ == path_.waypoints.size(); }
    std::size_t current_index() const { return current_; }  ///< == size() when finished
    /// WP_prev: the previous waypoint, or the start position before the first.
    Eigen::Vector3d previous_world_m() const;
    const planning::WaypointPath& path() const { return path_; }

  private:
    planning::WaypointPath path_;
    Eigen::Vector3d p_start_world_m_;
    std::size_t current_ = 0;
};

}  // namespace scantling::control
