#pragma once
/// @file
/// 4-DoF underwater vehicle (ROV, Blueye X3 class) in a current (SPEC §5, §10): surge, sway,
/// heave and yaw; roll and pitch are passively stable and stay zero.
///
/// Body frame: x forward (surge), y left (sway), z up (heave, positive upwards). Commands are
/// water-relative body velocities. Per axis i (ν = water-relative velocity or yaw rate):
///   Ṫ = (T_cmd − T) / τ_T            first-order thruster response (τ_T = 0: immediate)
///   ν̇ = T − ν / τ_i + (Rᵀ a_push)_i   linear damping with time constant τ_i, and the
///                                      external pushes (contacts, RovPush) over their windows
/// with the feed-forward T_cmd = ν_cmd / τ_i, so ν settles on the command. For τ_T = 0 this
/// is a first-order response with time constant τ_i; otherwise a two-pole one,
///   ν(t) = ν_cmd (1 − (τ_i e^(−t/τ_i) − τ_T e^(−t/τ_T)) / (τ_i − τ_T)) from rest.
/// Both are integrated exactly (closed form) over each step. Coriolis, added-mass coupling and
/// quadratic damping are neglected (a kinematic-plus-lag model, enough for guidance tests).
/// The vehicle is carried by the current: v_world = R_z(ψ) ν_xyz + current_world, current =
/// constant + slowly varying (disturbance.hpp; default correlation 60 s).
///
/// State semantics as mav_dynamics.hpp: pose and velocity at `stamp_s`, acceleration and
/// angular rate the means over the step that ended there; position is the trapezoidal
/// integral of the velocity.
/// Determinism: same config, seed, start and commands give bit-identical states.
/// Thread-safety: mutable; one instance per vehicle. Cost: O(1) per step.

#include <Eigen/Geometry>
#include <cstdint>
#include <string_view>
#include <vector>

#include <scantling/sim/disturbance.hpp>
#include <scantling/sim/motion_state.hpp>

namespace scantling::sim {

/// An out-of-view contact (issue 14 item 6): an external acceleration on the vehicle over a
/// short window (a bump into an appendage lasts tens of milliseconds), added to its
/// water-relative velocity, so the vehicle is really pushed and its IMU sees the spike.
struct RovPush {
    double start_s = 0.0;                                               ///< simulated time, s, >= 0
    double duration_s = 0.05;                                           ///< s, > 0
    Eigen::Vector3d acceleration_world_mps2 = Eigen::Vector3d::Zero();  ///< finite
};

/// Pushes a scenario may list (a bound for hostile files).
inline constexpr std::size_t kMaxRovPushes = 1000;

struct RovDynamicsConfig {
    double dt_s = 0.01;  ///< fixed step (100 Hz)
    /// Damping time constants τ_i (surge, sway, heave, yaw), seconds.
    Eigen::Vector4d damping_time_constant_s{1.0, 1.0, 0.8, 0.5};
    double thrust_time_constant_s = 0.2;  ///< τ_T, thruster spin-up (0: immediate)
    /// Command clip per axis (surge m/s, sway m/s, heave m/s, yaw rad/s); Blueye X3: ~1 m/s.
    Eigen::Vector4d max_command{1.0, 0.5, 0.5, 1.0};
    /// Current, world frame, m/s (default: still water; slow variation when sigma > 0).
    GustConfig current{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 60.0};
    std::vector<RovPush> pushes;  ///< contacts, in any order (default: none)

    /// Throws ConfigError naming the field ("rov.damping_time_constant_s[2] = 0, ...").
    void validate(std::string_view prefix = "rov") const;
};

/// Water-relative body-frame velocity command.
struct RovCommand {
    double surge_mps = 0.0;
    double sway_mps = 0.0;
    double heave_mps = 0.0;  ///< positive up
    double yaw_rate_radps = 0.0;
};

class RovDynamics {
  public:
    /// Starts at rest relative to the water at the position and yaw of `T_world_body_start`
    /// (level). Throws ConfigError / InputError (non-finite start).
    RovDynamics(const RovDynamicsConfig& config, const Eigen::Isometry3d& T_world_body_start,
                std::uint64_t seed, double start_s = 0.0);

    /// Advances one step of config().dt_s (InputError for a non-finite command).
    const MotionState& step(const RovCommand& command);

    const MotionState& state() const { return state_; }
    /// Water-relative (surge, sway, heave, yaw rate) at `state().stamp_s`.
    const Eigen::Vector4d& water_velocity() const { return nu_; }
    /// Current acting during the next step, world frame, m/s.
    Eigen::Vector3d current_world_mps() const { return current_.value(); }
    double yaw_rad() const { return yaw_rad_; }
    const RovDynamicsConfig& config() const { return config_; }

  private:
    Eigen::Vector3d world_velocity() const;
    /// Adds the pushes overlapping [stamp, stamp + dt_s) to the water-relative velocity.
    void add_pushes(double dt_s);

    RovDynamicsConfig config_;
    GustProcess current_;
    MotionState state_;
    Eigen::Vector4d nu_ = Eigen::Vector4d::Zero();      ///< water-relative velocities
    Eigen::Vector4d thrust_ = Eigen::Vector4d::Zero();  ///< per axis, per unit mass
    double start_s_ = 0.0;
    double yaw_rad_ = 0.0;
    std::int64_t steps_ = 0;
};

}  // namespace scantling::sim
