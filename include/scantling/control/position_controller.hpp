#pragma once
/// @file
/// The MAV position controller of SPEC §4 (D5.2 §II.1): three independent PIDs, one per world
/// axis, turn the error to a target position into a world-frame velocity command for the
/// low-level velocity loop; an optional P loop turns the heading towards a target yaw.
///
///   u_i = P_i + I_i + D_i of PID_i(target_i, p_i, dt),  i ∈ {x, y, z}
///   v_cmd = u · min(1, max_speed / |u|)   (clamped as a vector: it keeps the error's direction)
///   ψ̇_cmd = clamp(k_ψ · wrap(ψ_target − ψ), ±max_yaw_rate)   (0 without a target yaw)
/// Each axis PID's own limits (±max_speed) serve only its anti-windup and bound its integral
/// (it does not see the vector clamp); the command is built from the unclamped sums because
/// clamping each axis first would bend the flight towards the 45° diagonals whenever two axes
/// saturate (a 20 m × 5 m leg flown at (1, 1) m/s).
/// The flip side: far from the target the vector clamp shrinks a small cross-track correction
/// in proportion to the large along-track error, which is what the VTP follower (target at
/// most δ ahead, vtp_follower.hpp) is for. The target is the current waypoint (follower off)
/// or the VTP (follower on; waypoint_sequencer.hpp chooses).
///
/// Frames: positions in the world frame (metres), the command a world-frame velocity (m/s)
/// and a yaw rate about world z (rad/s). Thread-safety: mutable (the PIDs' states); one
/// instance per vehicle. Cost: O(1) per update. Deterministic.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

#include <scantling/control/pid.hpp>

namespace scantling::control {

/// SPEC §4 and the seeds give no gains (RESULTS-TO-REPRODUCE item 12): these are chosen for a
/// small quadrotor whose velocity loop follows its command with a first-order lag τ ≈ 0.3 s
/// (sim/mav_dynamics.hpp), and which must hold a sweep line in a steady wind. Per axis the
/// plant is x/u = 1 / (s (τ s + 1)); the closed loop's characteristic polynomial is
/// τ s³ + (1 + kd) s² + kp s + ki.
struct PositionControllerConfig {
    /// kp, 1/s. Twice the critically damped P-only gain 1/(4τ) = 0.83: the integral and
    /// derivative below restore the damping, and a stiffer loop halves the offset a wind
    /// leaves before the integral catches up (a hovering MAV drifts at c τ/(1 + c τ) of the
    /// wind: 0.54 m/s in 5 m/s with the simulator's drag, held by kp at 0.27 m at first).
    /// Also kp · δ = 4 m/s ≥ max_speed: chasing a VTP δ = 2 m ahead flies at full speed.
    double kp_per_s = 2.0;
    /// ki, 1/s². Cancels a steady wind's offset with time constant ~kp/ki = 4 s, slow enough
    /// to leave ≤ 6 cm of overshoot after a 0.3, 1 or 5 m step (tests/control/pid_test.cpp).
    double ki_per_s2 = 0.5;
    /// kd, s: damping on the measured velocity (derivative on measurement: a waypoint switch
    /// or a VTP jump gives no kick).
    double kd_s = 0.3;
    /// τ_f of the derivative's low-pass, s: two 20 Hz set-point periods (the FCU's rate,
    /// RESULTS-TO-REPRODUCE item 15), well under the loop's ~1 s time scale.
    double derivative_filter_s = 0.1;
    /// |v_cmd| limit, m/s: collision prevention's v_max (safety: 1 m/s, a careful indoor
    /// speed), so the safety layer's braking distances hold.
    double max_speed_mps = 1.0;
    /// k_ψ, 1/s: the heading settles in ~1 s, slower than the yaw-rate loop's 0.1 s lag.
    double yaw_gain_per_s = 1.0;
    /// |ψ̇_cmd| limit, rad/s: a half turn in ~6 s keeps the camera images sharp.
    double max_yaw_rate_radps = 0.5;

    /// Throws ConfigError naming "<prefix>.<field>": gains ≥ 0 and finite, limits > 0.
    void validate(std::string_view prefix = "position_controller") const;
};

/// The speed limit that keeps what holds the vehicle on its line: `v_mps` (norm above
/// `max_speed_mps`) loses speed along `error_m` (towards the target: the approach) before
/// across it (the integral's wind compensation and the cross-track correction). Scaling the
/// whole vector instead cut a 5 m/s crosswind's compensation by the ratio of the VTP chase
/// speed (kp δ = 4 m/s) to the limit, leaving the sweep lines 0.12 m downwind (docs/results.md).
/// A zero error scales the whole vector. Pure.
Eigen::Vector3d clamp_along_error(const Eigen::Vector3d& v_mps, const Eigen::Vector3d& error_m,
                                  double max_speed_mps);

struct VelocityCommand {
    Eigen::Vector3d v_cmd_world_mps = Eigen::Vector3d::Zero();
    double yaw_rate_cmd_radps = 0.0;  ///< about world z
    bool speed_clamped = false;       ///< the vector clamp to max_speed acted
};

class PositionController {
  public:
    /// Validates the config (ConfigError).
    explicit PositionController(const PositionControllerConfig& config = {});

    /// The command that takes the vehicle at `p_world_m` (heading `yaw_rad`) towards
    /// `p_target_world_m` (and `target_yaw_rad`, if any), `dt_s` after the previous update.
    /// Throws InputError for non-finite inputs or dt ≤ 0 (never a NaN command).
    VelocityCommand update(const Eigen::Vector3d& p_world_m, double yaw_rad,
                           const Eigen::Vector3d& p_target_world_m,
                           std::optional<double> target_yaw_rad, double dt_s);
    /// Forgets the integrals and derivative histories (e.g. after an operator take-over).
    void reset();

    const PositionControllerConfig& config() const { return config_; }
    const Pid& axis(std::size_t i) const { return axes_.at(i); }  ///< 0 x, 1 y, 2 z

  private:
    double yaw_rate(double yaw_rad, std::optional<double> target_yaw_rad) const;

    PositionControllerConfig config_;
    std::array<Pid, 3> axes_;
};

/// wrap(a) into (−π, π].
double wrap_angle_rad(double angle_rad);

}  // namespace scantling::control
