#pragma once
/// @file
/// Gauss-Newton step and result statistics shared by ICP and constrained ICP (private).

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>

#include <scantling/registration/result.hpp>

#include "icp_covariance.hpp"
#include "linearize.hpp"

namespace scantling::registration::detail {

/// The Gauss-Newton step delta = −B (Bᵀ H B)⁻¹ Bᵀ b, slightly damped so that directions
/// without any constraint (H has exact zeros there, and so has b) get a zero step instead of
/// NaN.
Vector6d solve_step(const LinearSystem& system, const DofBasis& basis);

/// True when the step moves less than both tolerances.
bool is_small_step(const Vector6d& delta, double translation_m, double rotation_rad);

/// "too_few_correspondences: 3 < min_correspondences = 10".
std::string too_few_status(std::size_t count, int min_correspondences);

struct IterationSettings {
    int max_iterations = 30;
    double translation_tolerance_m = 1e-3;
    double rotation_tolerance_rad = 1e-3;
    int min_correspondences = 10;
    double degeneracy_threshold = 1e-2;
    DofBasis basis = Matrix6d::Identity();
    CovarianceSettings covariance;  ///< model of the result's covariance (Hessian by default)
    /// Called with each new estimate (may be empty). A non-empty answer stops the iteration:
    /// the initial pose is returned, converged = false, status = "cap_hit: <answer>".
    std::function<std::string(const Eigen::Isometry3d&)> cap_violation;
};

/// Fills num_inliers, fitness, rmse_m, information, covariance and degeneracy from the system
/// linearised at the final estimate; `record` holds its scores (kClusteredSandwich only).
void fill_statistics(RegistrationResult& result, const LinearSystem& system,
                     const ScoreRecord* record, std::size_t source_size,
                     const IterationSettings& settings);

/// Gauss-Newton iterations from `T_init`: linearise, step, until a small step, too few
/// correspondences, max_iterations or a cap. Statistics describe the returned pose.
RegistrationResult iterate(const Problem& problem, std::size_t source_size,
                           const Eigen::Isometry3d& T_init, const IterationSettings& settings);

}  // namespace scantling::registration::detail
