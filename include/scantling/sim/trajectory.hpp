#pragma once
/// @file
/// Scripted vehicle motion: the ground truth as an analytic function of time (SPEC §10).
///
/// A Trajectory gives the full MotionState at any time, with velocity, acceleration and
/// angular rate equal to the exact time derivatives of the pose (not finite differences), so
/// an IMU can be simulated from it. Scripted trajectories in this module keep the body level
/// (roll = pitch = 0; body x forward, y left, z up) and turn only about world z, so
/// ω_body = (0, 0, ψ̇).
///
/// Thread-safety: `at` is const and may be called concurrently. Determinism: pure functions of t.

#include <Eigen/Core>

#include <scantling/sim/motion_state.hpp>

namespace scantling::sim {

class Trajectory {
  public:
    virtual ~Trajectory() = default;

    /// The state at time `t_s` (seconds from the trajectory start; stamp_s = t_s). Before 0
    /// and after duration_s() the vehicle rests at its start / end pose.
    virtual MotionState at(double t_s) const = 0;

    /// Time from start to end, seconds.
    virtual double duration_s() const = 0;
};

/// A level state: position p, velocity v, acceleration a (world), yaw ψ and yaw rate ψ̇
/// (about world z). Used by the scripted trajectories.
MotionState level_state(double stamp_s, const Eigen::Vector3d& p_world,
                        const Eigen::Vector3d& v_world, const Eigen::Vector3d& a_world,
                        double yaw_rad, double yaw_rate_radps);

/// Smallest-magnitude equivalent of `angle_rad`, in [−π, π).
double wrap_angle(double angle_rad);

}  // namespace scantling::sim
