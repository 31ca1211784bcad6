#pragma once
/// @file
/// Truncated-least-squares estimators of TEASER++'s decoupled solver (private to registration):
/// GNC-TLS rotation, exact scalar TLS by adaptive voting, and exact TLS over a yaw angle.
/// TLS cost of a residual r with bound c: min(r² / c², 1).

#include <Eigen/Core>
#include <span>
#include <vector>

namespace scantling::registration::detail {

struct GncSettings {
    double noise_bound = 0.1;      ///< TLS bound on the residual norm, > 0
    int max_iterations = 100;      ///< >= 1
    double factor = 1.4;           ///< μ growth per iteration, > 1
    double cost_threshold = 1e-6;  ///< stop when the weighted cost changes less than this
};

struct RotationEstimate {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    std::vector<char> inliers;  ///< per measurement: final GNC weight > 0
    int iterations = 0;
};

/// GNC-TLS (Yang, Antonante, Tzoumas & Carlone, RA-L 2020) for R in target_k ≈ R source_k:
/// alternate a weighted Horn fit and the closed-form TLS weights of the surrogate with
/// parameter μ, μ growing by `factor` each step (TEASER++'s GNCTLSRotationSolver).
RotationEstimate gnc_tls_rotation(std::span<const Eigen::Vector3d> source,
                                  std::span<const Eigen::Vector3d> target,
                                  const GncSettings& settings);

/// Exact minimiser of Σ min((x − v_k)² / c², 1) over x (TEASER++'s adaptive voting): sweeps the
/// interval endpoints v_k ± c in order, keeping running sums of the consensus set. O(n log n).
/// `values` must not be empty.
double scalar_tls(std::span<const double> values, double bound);

/// Exact minimiser of Σ min(|target_k − R_z(θ) source_k|² / c², 1) over the yaw θ (radians,
/// in (−π, π]): each measurement fits on an arc of θ; a sweep over the arc ends finds the best
/// consensus set, whose least-squares yaw is closed-form. O(n log n).
double yaw_tls(std::span<const Eigen::Vector3d> source, std::span<const Eigen::Vector3d> target,
               double bound);

}  // namespace scantling::registration::detail
