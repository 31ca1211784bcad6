#pragma once
/// @file
/// Ground-truth motion of a vehicle at one instant: what vehicles and scripted trajectories
/// produce and what the motion-based sensor models (IMU, VIO, wheel odometry, DVL, pressure)
/// consume.
///
/// Frames: world z up, gravity along −z world. `T_world_body` maps body points into the world;
/// the velocity and acceleration are those of the body origin, expressed in the world frame;
/// the angular rate is that of the body relative to the world, expressed in the body frame
/// (so Ṙ_world_body = R_world_body · hat(omega_body_radps)).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

namespace scantling::sim {

struct MotionState {
    double stamp_s = 0.0;                                            ///< seconds
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();  ///< world ← body
    Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();       ///< body-origin velocity, world
    Eigen::Vector3d a_world_mps2 = Eigen::Vector3d::Zero();      ///< body-origin acceleration
    Eigen::Vector3d omega_body_radps = Eigen::Vector3d::Zero();  ///< angular rate, body frame
    /// A crawler's wheels at `stamp_s`: the forward speed and the turn rate they make, without
    /// the slip (crawler_dynamics.hpp). Wheel encoders see these, not the body's motion; for a
    /// vehicle without them, wheel odometry derives both from the motion.
    std::optional<double> wheel_forward_mps;
    std::optional<double> wheel_yaw_rate_radps;
};

}  // namespace scantling::sim
