#pragma once
/// @file
/// Statistics of a Stein-ICP particle set (private): circular helpers, mean, covariance and
/// per-DoF KDE modes.

#include <Eigen/Core>
#include <span>

#include <scantling/core/se3.hpp>
#include <scantling/registration/stein_icp.hpp>

namespace scantling::registration::detail {

/// True for the angle DoFs (roll, pitch, yaw) of a particle.
constexpr bool is_angle(int dof) { return dof >= 3; }

/// `angle_rad` wrapped to [−π, π].
double wrap_angle(double angle_rad);

/// a − b, wrapped when `circular`.
inline double difference(double a, double b, bool circular) {
    return circular ? wrap_angle(a - b) : a - b;
}

/// Fills mean, covariance, mode, num_modes and T_target_source of `result` from its particles.
/// `free_dofs` lists the DoFs that moved (the others are copied from the first particle).
void summarize_particles(SteinIcpResult& result, std::span<const int> free_dofs,
                         double min_mode_fraction);

}  // namespace scantling::registration::detail
