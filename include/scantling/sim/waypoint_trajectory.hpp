#pragma once
/// @file
/// Waypoint missions as scripted trajectories (SPEC §4 missions, §10 vehicles): straight legs
/// between waypoints, each flown rest to rest with a speed profile (speed_profile.hpp), the
/// vehicle stopping on every waypoint as a waypoint-following MAV/ROV does; optional dwell.
///
/// Yaw (body level, turning about world z):
/// - `YawMode::kWaypoint`: each waypoint gives the heading; the yaw changes along the leg in
///   step with the position (ψ = ψ_i + Δψ · s(t)/D, the shorter way round). Legs without
///   translation turn on the spot.
/// - `YawMode::kFaceTravel`: the vehicle turns on the spot to face the next leg (in the
///   horizontal plane) and then flies it straight; vertical legs keep the heading. Only the
///   first waypoint's yaw is used (initial heading).
/// Each leg's duration is the smallest satisfying all four limits (speed, acceleration, yaw
/// rate, yaw acceleration), so position and yaw arrive together.
///
/// Cost: construction O(n); `at` O(log n). Thread-safety and determinism: see trajectory.hpp.

#include <Eigen/Core>
#include <cstddef>
#include <string_view>
#include <vector>

#include <scantling/sim/speed_profile.hpp>
#include <scantling/sim/trajectory.hpp>

namespace scantling::sim {

struct Waypoint {
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< world frame
    double yaw_rad = 0.0;  ///< heading at the waypoint (kFaceTravel: first waypoint only)
    double dwell_s = 0.0;  ///< time at rest on arrival (on the first waypoint: before leaving)
};

enum class YawMode { kWaypoint, kFaceTravel };

struct WaypointTrajectoryConfig {
    std::vector<Waypoint> waypoints;    ///< at least one
    double max_speed_mps = 1.0;         ///< along each leg
    double max_accel_mps2 = 0.5;        ///< along each leg
    double max_yaw_rate_radps = 0.5;    ///< |ψ̇|
    double max_yaw_accel_radps2 = 0.5;  ///< |ψ̈|
    ProfileShape shape = ProfileShape::kSmooth;
    YawMode yaw_mode = YawMode::kWaypoint;

    /// Throws ConfigError naming the field, e.g. "waypoint_trajectory.waypoints[2].dwell_s =
    /// -1, expected >= 0" or "waypoint_trajectory.waypoints = 0, expected >= 1 waypoint".
    void validate(std::string_view prefix = "waypoint_trajectory") const;
};

class WaypointTrajectory : public Trajectory {
  public:
    /// Validates the config (ConfigError) and plans every leg.
    explicit WaypointTrajectory(WaypointTrajectoryConfig config);

    MotionState at(double t_s) const override;
    double duration_s() const override;

    /// Time at which the vehicle comes to rest on waypoint `i` (before its dwell); 0 for the
    /// first. Throws InputError for i >= number of waypoints.
    double arrival_time_s(std::size_t i) const;

    const WaypointTrajectoryConfig& config() const { return config_; }

  private:
    /// One rest-to-rest motion (or a dwell): p = p0 + dp σ, ψ = yaw0 + dyaw σ, σ in [0, 1].
    struct Leg {
        double start_s = 0.0;
        double duration_s = 0.0;
        Eigen::Vector3d p0 = Eigen::Vector3d::Zero();
        Eigen::Vector3d dp = Eigen::Vector3d::Zero();
        double yaw0_rad = 0.0;
        double dyaw_rad = 0.0;
        RestToRestProfile sigma;  ///< normalised profile (distance 1, or 0 for a dwell)
    };

    void add_motion(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, double yaw0, double yaw1);
    void add_dwell(const Eigen::Vector3d& p, double yaw, double dwell_s);
    double end_time_s() const;

    WaypointTrajectoryConfig config_;
    std::vector<Leg> legs_;
    std::vector<double> arrival_s_;
};

}  // namespace scantling::sim
