#pragma once
/// @file
/// Multirotor (MAV) tracking velocity commands in wind (SPEC §4, §10): the "simulated low
/// level" under the position controller and the trajectory follower.
///
/// Translational model (world frame, per step of dt, wind w held over the step):
///   v̇ = (v_cmd − v) / τ + c (w − v)
/// i.e. a first-order velocity loop (time constant τ) plus linear aerodynamic drag (c, 1/s)
/// against the air-relative velocity. It is integrated exactly while the loop's demand
/// |v_cmd − v| / τ is within max_accel_mps2; beyond that the loop gives max_accel_mps2 towards
/// v_cmd (plus drag), constant over the step. The command is first clipped to max_speed_mps
/// (and the yaw rate to max_yaw_rate_radps). With v_cmd held and no gusts, the steady state is
///   v_ss = (v_cmd + c τ w) / (1 + c τ)          (`mav_steady_velocity_mps`),
/// so a hovering MAV (v_cmd = 0) drifts downwind at c τ / (1 + c τ) of the wind speed until a
/// position loop corrects it. Wind = constant + gusts (disturbance.hpp).
/// Yaw: the yaw rate follows its command with a first-order lag (yaw_rate_time_constant_s).
///
/// Attitude (as a quadrotor, whose thrust is along body z): the thrust direction is the
/// specific thrust a − a_drag + g e_z (a = the step's acceleration), followed with a
/// first-order lag of attitude_time_constant_s (the attitude loop's bandwidth; without it a
/// velocity step would tilt the body within one step and the gyro would see a spike of
/// tilt / dt). Body z is that direction; body x the projection of (cos ψ, sin ψ, 0)
/// orthogonal to it. So the MAV tilts into its acceleration and into the wind while hovering.
/// The tilt is reported only: the translation does not depend on it.
///
/// State semantics: pose and velocity at `stamp_s`; acceleration and angular rate are the
/// means over the step that ended at `stamp_s` (what an IMU integrating over its sample
/// period reports); position is the trapezoidal integral of velocity, so integrating them
/// reproduces the trajectory exactly. The initial state has zero acceleration and rate.
///
/// Determinism: the same config, seed, start and command sequence give bit-identical states.
/// Thread-safety: mutable; one instance per simulated vehicle. Cost: O(1) per step.

#include <Eigen/Geometry>
#include <cstdint>
#include <string_view>

#include <scantling/sim/disturbance.hpp>
#include <scantling/sim/motion_state.hpp>

namespace scantling::sim {

struct MavDynamicsConfig {
    double dt_s = 0.005;                     ///< fixed step (200 Hz)
    double velocity_time_constant_s = 0.3;   ///< τ of the velocity loop
    double yaw_rate_time_constant_s = 0.1;   ///< lag of the yaw rate (0: none)
    double max_speed_mps = 5.0;              ///< command clip, |v_cmd|
    double max_accel_mps2 = 4.0;             ///< the loop's acceleration authority
    double max_yaw_rate_radps = 1.0;         ///< command clip, |ψ̇_cmd|
    double drag_coefficient_per_s = 0.4;     ///< c: drag acceleration per m/s of airspeed
    double attitude_time_constant_s = 0.05;  ///< lag of the tilt behind the thrust (0: none)
    double gravity_mps2 = 9.81;              ///< for the tilt only
    GustConfig wind{};                       ///< world frame, m/s (default: calm)

    /// Throws ConfigError naming the field ("mav.velocity_time_constant_s = 0, expected > 0").
    void validate(std::string_view prefix = "mav") const;
};

/// Velocity command: world-frame velocity and yaw rate (about world z).
struct MavCommand {
    Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();
    double yaw_rate_radps = 0.0;
};

/// Steady-state velocity for a held (clipped) command in a constant wind (file comment).
Eigen::Vector3d mav_steady_velocity_mps(const MavDynamicsConfig& config,
                                        const Eigen::Vector3d& v_cmd_world_mps,
                                        const Eigen::Vector3d& wind_world_mps);

class MavDynamics {
  public:
    /// Starts at rest at the position and yaw of `T_world_body_start` (level), at `start_s`.
    /// Throws ConfigError for a bad config, InputError for a non-finite start pose.
    MavDynamics(const MavDynamicsConfig& config, const Eigen::Isometry3d& T_world_body_start,
                std::uint64_t seed, double start_s = 0.0);

    /// Advances one step of config().dt_s under `command` (InputError if not finite).
    const MotionState& step(const MavCommand& command);

    const MotionState& state() const { return state_; }
    /// Wind acting during the next step, world frame, m/s.
    Eigen::Vector3d wind_world_mps() const { return wind_.value(); }
    double yaw_rad() const { return yaw_rad_; }
    double yaw_rate_radps() const { return yaw_rate_radps_; }
    std::int64_t steps() const { return steps_; }
    const MavDynamicsConfig& config() const { return config_; }

  private:
    Eigen::Vector3d next_velocity(const Eigen::Vector3d& v_cmd, const Eigen::Vector3d& wind) const;
    Eigen::Matrix3d attitude(const Eigen::Vector3d& thrust_dir, double yaw_rad) const;
    void advance_yaw(double yaw_rate_cmd_radps);
    void advance_tilt(const Eigen::Vector3d& thrust_mps2);

    MavDynamicsConfig config_;
    GustProcess wind_;
    MotionState state_;
    Eigen::Vector3d thrust_dir_ = Eigen::Vector3d::UnitZ();  ///< lagged, unit
    double start_s_ = 0.0;
    double yaw_rad_ = 0.0;
    double yaw_rate_radps_ = 0.0;
    std::int64_t steps_ = 0;
};

}  // namespace scantling::sim
