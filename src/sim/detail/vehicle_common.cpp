#include "vehicle_common.hpp"

#include <scantling/core/se3.hpp>

#include "sensor_checks.hpp"

#include <cmath>

namespace scantling::sim::detail {

MotionState next_state(const MotionState& prev, double stamp_s,
                       const Eigen::Isometry3d& T_world_body, const Eigen::Vector3d& v_world,
                       double dt_s) {
    MotionState next;
    next.stamp_s = stamp_s;
    next.T_world_body = T_world_body;
    next.v_world_mps = v_world;
    next.a_world_mps2 = (v_world - prev.v_world_mps) / dt_s;
    const Eigen::Matrix3d R_prev_next =
        prev.T_world_body.linear().transpose() * T_world_body.linear();
    next.omega_body_radps = so3_log(R_prev_next) / dt_s;
    return next;
}

double lag_fraction(double dt_s, double time_constant_s) {
    return time_constant_s > 0.0 ? -std::expm1(-dt_s / time_constant_s) : 1.0;
}

double lag_mean_fraction(double dt_s, double time_constant_s) {
    return time_constant_s > 0.0 ? time_constant_s / dt_s * lag_fraction(dt_s, time_constant_s)
                                 : 0.0;
}

Eigen::Vector3d clamp_norm(const Eigen::Vector3d& v, double max_norm) {
    const double n = v.norm();
    return n > max_norm ? Eigen::Vector3d(v * (max_norm / n)) : v;
}

double yaw_of(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

void require_step(std::string_view prefix, double dt_s) {
    require(std::isfinite(dt_s) && dt_s > 0.0 && dt_s <= 1.0, prefix, "dt_s", dt_s, "in (0, 1] s");
}

}  // namespace scantling::sim::detail
