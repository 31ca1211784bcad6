#pragma once
// Analytic ground-truth motions for the motion-based sensor tests (written here, independent of
// the simulator's trajectories, so a test does not check code against itself).

#include <scantling/sim/motion_state.hpp>

#include <Eigen/Geometry>
#include <cmath>

namespace scantling::sim::testing {

/// Constant-turn-rate climbing circle: p = (R cos ωt, R sin ωt, c t), attitude
/// R_world_body = Rz(ωt) · R_tilt (a fixed tilt turned with the circle), so the body rate is
/// the constant R_tiltᵀ (0, 0, ω).
struct ClimbingCircle {
    double radius_m = 2.0;
    double rate_radps = 0.5;
    double climb_mps = 0.2;
    Eigen::Matrix3d R_tilt = (Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()) *
                              Eigen::AngleAxisd(-0.1, Eigen::Vector3d::UnitY()))
                                 .toRotationMatrix();

    MotionState at(double t_s) const {
        const double c = std::cos(rate_radps * t_s);
        const double s = std::sin(rate_radps * t_s);
        const double w = rate_radps;
        MotionState m;
        m.stamp_s = t_s;
        m.T_world_body.linear() =
            Eigen::AngleAxisd(w * t_s, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R_tilt;
        m.T_world_body.translation() = Eigen::Vector3d(radius_m * c, radius_m * s, climb_mps * t_s);
        m.v_world_mps = Eigen::Vector3d(-radius_m * w * s, radius_m * w * c, climb_mps);
        m.a_world_mps2 = Eigen::Vector3d(-radius_m * w * w * c, -radius_m * w * w * s, 0.0);
        m.omega_body_radps = R_tilt.transpose() * Eigen::Vector3d(0.0, 0.0, w);
        return m;
    }
};

/// Level motion along the body x axis at constant speed, heading `yaw_rad`, from `start`.
inline MotionState straight_line(double t_s, double speed_mps, double yaw_rad = 0.0,
                                 const Eigen::Vector3d& start = Eigen::Vector3d::Zero()) {
    MotionState m;
    m.stamp_s = t_s;
    m.T_world_body.linear() =
        Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d heading(std::cos(yaw_rad), std::sin(yaw_rad), 0.0);
    m.T_world_body.translation() = start + speed_mps * t_s * heading;
    m.v_world_mps = speed_mps * heading;
    return m;
}

/// Vehicle at rest at `p_world` with the given attitude.
inline MotionState at_rest(double t_s, const Eigen::Vector3d& p_world,
                           const Eigen::Matrix3d& R_world_body = Eigen::Matrix3d::Identity()) {
    MotionState m;
    m.stamp_s = t_s;
    m.T_world_body.linear() = R_world_body;
    m.T_world_body.translation() = p_world;
    return m;
}

}  // namespace scantling::sim::testing
