#include <scantling/sim/trajectory.hpp>

#include <cmath>
#include <numbers>

namespace scantling::sim {

MotionState level_state(double stamp_s, const Eigen::Vector3d& p_world,
                        const Eigen::Vector3d& v_world, const Eigen::Vector3d& a_world,
                        double yaw_rad, double yaw_rate_radps) {
    MotionState state;
    state.stamp_s = stamp_s;
    state.T_world_body.linear() =
        Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    state.T_world_body.translation() = p_world;
    state.v_world_mps = v_world;
    state.a_world_mps2 = a_world;
    state.omega_body_radps = Eigen::Vector3d(0.0, 0.0, yaw_rate_radps);
    return state;
}

double wrap_angle(double angle_rad) {
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    const double wrapped = angle_rad - kTwoPi * std::floor((angle_rad + std::numbers::pi) / kTwoPi);
    return wrapped >= std::numbers::pi ? wrapped - kTwoPi : wrapped;
}

}  // namespace scantling::sim
