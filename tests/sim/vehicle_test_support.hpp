#pragma once
// Helpers shared by the trajectory and vehicle tests: numerical-derivative checks of a
// trajectory, and small analytic meshes for the crawler.

#include <scantling/core/se3.hpp>
#include <scantling/core/triangle_mesh.hpp>
#include <scantling/sim/trajectory.hpp>

#include "../core/analytic_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace scantling::sim::testing {

// Central differences of a C² motion: truncation O(h²) and round-off O(ε |p| / h) (first
// derivative) or O(ε |p| / h²) (second); with |p| ~ 10 m both stay below these tolerances.
constexpr double kVelocityStepS = 1e-4;
constexpr double kAccelStepS = 1e-3;
constexpr double kVelocityTolMps = 1e-6;
constexpr double kAccelTolMps2 = 1e-5;
constexpr double kRateTolRadps = 1e-6;

/// v, a and ω of `trajectory` at `t_s` agree with central differences of its pose.
inline void expect_consistent_derivatives(const Trajectory& trajectory, double t_s) {
    const double h = kVelocityStepS;
    const MotionState m = trajectory.at(t_s);
    const MotionState before = trajectory.at(t_s - h);
    const MotionState after = trajectory.at(t_s + h);
    const Eigen::Vector3d v_num =
        (after.T_world_body.translation() - before.T_world_body.translation()) / (2.0 * h);
    EXPECT_LT((v_num - m.v_world_mps).norm(), kVelocityTolMps) << "t = " << t_s;
    const Eigen::Vector3d omega_num =
        so3_log(before.T_world_body.linear().transpose() * after.T_world_body.linear()) / (2.0 * h);
    EXPECT_LT((omega_num - m.omega_body_radps).norm(), kRateTolRadps) << "t = " << t_s;
    const double H = kAccelStepS;
    const Eigen::Vector3d p0 = m.T_world_body.translation();
    const Eigen::Vector3d a_num = (trajectory.at(t_s + H).T_world_body.translation() - 2.0 * p0 +
                                   trajectory.at(t_s - H).T_world_body.translation()) /
                                  (H * H);
    EXPECT_LT((a_num - m.a_world_mps2).norm(), kAccelTolMps2) << "t = " << t_s;
}

/// Checks `expect_consistent_derivatives` at `n` evenly spread interior times.
inline void expect_consistent_derivatives_along(const Trajectory& trajectory, int n) {
    const double T = trajectory.duration_s();
    for (int i = 1; i < n; ++i) expect_consistent_derivatives(trajectory, T * i / n);
}

using scantling::testing::grid_plate;
using scantling::testing::open_cylinder;

}  // namespace scantling::sim::testing
