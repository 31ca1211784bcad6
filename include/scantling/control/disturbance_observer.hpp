#pragma once
/// @file
/// Wind compensation for a velocity-commanded vehicle: a disturbance observer (an extended
/// state observer) under the position loop, in the place of an autopilot velocity loop's
/// integral (PX4's MPC velocity PID has one; the simulated low level, sim/mav_dynamics.hpp,
/// has none).
///
/// Model of the vehicle, per world axis: its velocity follows the command with a first-order
/// lag τ, less its own linear drag c v (calm air), plus an unknown acceleration d (the wind's
/// drag c w, gusts, a tether, model errors):
///   v̇ = sat((u − v) / τ) − c v + d
/// where sat limits the loop's acceleration to its authority a_max (as a vector). The observer
/// estimates v̂ and d̂ from the estimated velocity v (the state estimate, at the command rate) and
/// the command u in force since the previous observation:
///   v̂̇ = sat((u − v̂) / τ) − c v̂ + d̂ + L₁ (v − v̂),   d̂̇ = L₂ (v − v̂)
/// with both error poles at −ω (L₁ = 2ω − 1/τ − c, L₂ = ω²; ω ≥ (1/τ + c)/2), integrated with
/// explicit Euler at the observation interval (ω dt ≪ 1 at a 200 Hz command; a gap longer
/// than `max_gap_s` restarts v̂ at the measurement and keeps d̂).
/// The compensated command u = v_desired (1 + c τ) − τ d̂ turns the vehicle into the
/// undisturbed lag v̇ = (1/τ + c)(v_desired − v) for disturbances slower than ω: the position
/// PIDs above then fly as in calm air, and their integral no longer has to learn the wind (4 s)
/// from a position error that it first lets grow (0.27 m at the start of a mission in 5 m/s of
/// wind, docs/results.md). The vehicle's own drag is modelled rather than observed, so a stop
/// from cruise speed is not slowed by the observer's lag behind a drag that changes as fast as
/// the velocity; and the loop's acceleration limit is modelled, so the slower response to a
/// large step (0 → 2 m/s: 7 m/s² asked, 4 given) is not taken for a disturbance (which would
/// then overshoot the step: 2.7 m/s commanded, 0.2 m deeper into a wall's margin, measured).
/// |u − v_desired| is limited to `max_compensation_mps`.
///
/// Where it sits: after the safety layer, whose output is the velocity the vehicle should fly
/// (collision prevention limits the desired velocity, not the wind's share of the command).
///
/// Frames and units: world frame; velocities m/s, d̂ m/s², times s. Input contract: finite
/// velocities and times, else InputError (state unchanged). Thread-safety: mutable, one per
/// vehicle. Cost: O(1). Deterministic.

#include <Eigen/Core>
#include <optional>
#include <string_view>

namespace scantling::control {

struct DisturbanceObserverConfig {
    /// τ of the vehicle's velocity loop, s, > 0: identified from a velocity step on the
    /// vehicle (the simulator's MAV: 0.3 s). A wrong τ changes only the transients: in a
    /// steady disturbance d̂ settles at (true τ / this τ) · d, so τ d̂ is exact either way
    /// (tests/control/disturbance_observer_test.cpp, ±30 %).
    double velocity_time_constant_s = 0.3;
    /// c of the vehicle's linear drag, 1/s, ≥ 0: identified from the speed a held command
    /// reaches in calm air, v/u = 1/(1 + c τ) (the simulator's MAV: 0.4, 89 %). An error
    /// here, like one in τ, changes only the transients.
    double drag_coefficient_per_s = 0.4;
    /// a_max, m/s², > 0: the velocity loop's acceleration authority (the simulator's MAV: 4).
    double max_accel_mps2 = 4.0;
    /// ω, rad/s, ≥ (1/τ + c)/2: d̂ settles in ~5/ω = 1.25 s, and a 1 m/s gust with 2 s correlation
    /// is followed with a 0.5 s lag; faster would pass the estimate's velocity noise (a few
    /// cm/s at 200 Hz) into the command as ω² τ of acceleration noise.
    double bandwidth_radps = 4.0;
    /// |u − v_desired| limit, m/s, ≥ 0: 1.5 m/s holds a 12 m/s wind against the simulator's
    /// drag.
    double max_compensation_mps = 1.5;
    /// An observation interval longer than this restarts v̂ at the measurement, s, > 0
    /// (an IMU gap: Euler over it would be unstable).
    double max_gap_s = 0.1;

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "disturbance_observer") const;
};

class DisturbanceObserver {
  public:
    /// Validates the config (ConfigError).
    explicit DisturbanceObserver(const DisturbanceObserverConfig& config = {});

    /// The vehicle's (estimated) velocity at `t_s`, under the command returned by the last
    /// `command()` (zero before the first). A repeated or earlier time is ignored.
    void observe(const Eigen::Vector3d& v_world_mps, double t_s);
    /// The command that makes the vehicle follow `v_desired_world_mps` as the undisturbed lag;
    /// it is the command in force until the next observation.
    Eigen::Vector3d command(const Eigen::Vector3d& v_desired_world_mps);
    /// Forgets everything: the next observation starts again from d̂ = 0.
    void reset();

    /// d̂, m/s².
    const Eigen::Vector3d& disturbance_mps2() const { return d_hat_mps2_; }
    /// What `command()` adds to `v_desired_world_mps`: c τ v_desired − τ d̂, limited, m/s.
    Eigen::Vector3d compensation_mps(const Eigen::Vector3d& v_desired_world_mps) const;
    const DisturbanceObserverConfig& config() const { return config_; }

  private:
    DisturbanceObserverConfig config_;
    Eigen::Vector3d v_hat_mps_ = Eigen::Vector3d::Zero();
    Eigen::Vector3d d_hat_mps2_ = Eigen::Vector3d::Zero();
    Eigen::Vector3d u_mps_ = Eigen::Vector3d::Zero();  ///< the command in force
    std::optional<double> last_t_s_;
};

}  // namespace scantling::control
