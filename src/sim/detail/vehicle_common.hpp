#pragma once
// Helpers shared by the vehicle models (MAV, ROV, crawler, legged base).

#include <Eigen/Geometry>
#include <cstdint>
#include <string_view>

#include <scantling/sim/motion_state.hpp>

namespace scantling::sim::detail {

/// The state after one fixed step of dt_s ending at `stamp_s`: pose and velocity as given;
/// acceleration and angular rate are the means over the step, (v − v_prev) / dt and
/// log(R_prevᵀ R) / dt, so integrating them from `prev` reproduces the new pose and velocity.
MotionState next_state(const MotionState& prev, double stamp_s,
                       const Eigen::Isometry3d& T_world_body, const Eigen::Vector3d& v_world,
                       double dt_s);

/// 1 − exp(−dt / τ): the fraction of the way a first-order lag moves towards its input in one
/// step (1 for τ = 0, i.e. no lag).
double lag_fraction(double dt_s, double time_constant_s);

/// Mean over one step of a first-order lag's remaining deviation, as a fraction of the
/// deviation at the step start: (τ / dt)(1 − exp(−dt / τ)); 0 for τ = 0. The exact mean of the
/// lagged value is input + (start − input) · this.
double lag_mean_fraction(double dt_s, double time_constant_s);

/// `v` shortened to at most `max_norm` (direction kept).
Eigen::Vector3d clamp_norm(const Eigen::Vector3d& v, double max_norm);

/// The yaw of `R` (heading of body x in the world xy plane).
double yaw_of(const Eigen::Matrix3d& R);

/// Checks shared by every vehicle config: dt_s > 0.
void require_step(std::string_view prefix, double dt_s);

/// Time of step `k` from `start_s` without accumulating rounding (k · dt, not Σ dt).
inline double stamp_at(double start_s, std::int64_t k, double dt_s) {
    return start_s + static_cast<double>(k) * dt_s;
}

}  // namespace scantling::sim::detail
