#pragma once
/// @file
/// Planar legged base (confined-space robot of SPEC §1, §10): body-frame velocity commands
/// (forward, lateral, yaw rate), level trunk, optional foot-step bounce.
///
/// Model: the commanded body velocity, rotated into the world with the current yaw, is
/// tracked by a first-order loop (time constant τ) whose acceleration is limited to
/// max_accel_mps2 (as the MAV, without wind); the yaw rate follows its command with the
/// same lag. Bounce: z = z0 + A s sin φ with the gait phase φ advancing at 2π step_frequency_hz
/// and s = min(1, horizontal speed / max_speed_mps), so the trunk bobs only while walking.
///
/// State semantics as mav_dynamics.hpp (horizontal position is the trapezoidal integral of
/// the velocity; z is the bounce formula and v_z its derivative, so integration reproduces z
/// to O(dt²)). Determinism: no randomness; same inputs give bit-identical states.
/// Thread-safety: mutable; one per vehicle. Cost: O(1) per step.

#include <Eigen/Geometry>
#include <cstdint>
#include <string_view>

#include <scantling/sim/motion_state.hpp>

namespace scantling::sim {

struct LeggedBaseConfig {
    double dt_s = 0.005;                    ///< fixed step (200 Hz)
    double velocity_time_constant_s = 0.3;  ///< τ of velocity and yaw-rate tracking
    double max_speed_mps = 1.0;             ///< horizontal command clip
    double max_accel_mps2 = 1.5;            ///< horizontal acceleration limit
    double max_yaw_rate_radps = 1.0;        ///< command clip
    double bounce_amplitude_m = 0.01;       ///< A (0: no bounce)
    double step_frequency_hz = 2.0;         ///< gait frequency of the bounce

    /// Throws ConfigError naming the field ("legged_base.step_frequency_hz = 0, ...").
    void validate(std::string_view prefix = "legged_base") const;
};

struct LeggedCommand {
    double forward_mps = 0.0;  ///< along body x
    double lateral_mps = 0.0;  ///< along body y (left)
    double yaw_rate_radps = 0.0;
};

class LeggedBase {
  public:
    /// Starts at rest at the position and yaw of `T_world_body_start` (level); its z is the
    /// nominal trunk height z0. Throws ConfigError / InputError (non-finite start).
    LeggedBase(const LeggedBaseConfig& config, const Eigen::Isometry3d& T_world_body_start,
               double start_s = 0.0);

    /// Advances one step of config().dt_s (InputError for a non-finite command).
    const MotionState& step(const LeggedCommand& command);

    const MotionState& state() const { return state_; }
    double yaw_rad() const { return yaw_rad_; }
    const LeggedBaseConfig& config() const { return config_; }

  private:
    Eigen::Vector2d next_velocity(const Eigen::Vector2d& v_cmd) const;
    void advance_yaw(double yaw_rate_cmd_radps);
    /// Advances the gait phase; returns the bounce height offset and its rate (m, m/s).
    Eigen::Vector2d advance_bounce(double speed0_mps, double speed1_mps);

    LeggedBaseConfig config_;
    MotionState state_;
    double start_s_ = 0.0;
    double z0_m_ = 0.0;
    double yaw_rad_ = 0.0;
    double yaw_rate_radps_ = 0.0;
    double phase_rad_ = 0.0;
    std::int64_t steps_ = 0;
};

}  // namespace scantling::sim
