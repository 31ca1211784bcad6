#pragma once
/// @file
/// The two covariance models of icp.hpp, evaluated at the final linearisation (private).

#include <cstddef>
#include <optional>
#include <span>

#include <scantling/registration/icp.hpp>

#include "linearize.hpp"

namespace scantling::registration::detail {

/// IcpConfig's covariance fields.
struct CovarianceSettings {
    IcpCovariance model = IcpCovariance::kHessian;
    double cell_size_m = 1.0;
    double map_error_sigma_m = 0.0;
};

/// Over the cells c of the valid scores: Σ_c g_c g_cᵀ, Σ_c A_c A_cᵀ (g_c, A_c the sums of the
/// scores and sensitivities in c) and the number G of cells.
struct ClusteredScores {
    Matrix6d outer = Matrix6d::Zero();
    Matrix6d sensitivity_outer = Matrix6d::Zero();
    std::size_t num_cells = 0;
};

/// Groups the valid scores by cell. Cells are summed in lexicographic cell order and the scores
/// of one cell in source order, so the result does not depend on how they were computed.
ClusteredScores cluster_scores(std::span<const CellScore> scores);

struct Uncertainty {
    Matrix6d information = Matrix6d::Zero();
    std::optional<Matrix6d> covariance;
};

/// information and covariance of RegistrationResult for `settings` (icp.hpp), restricted to the
/// span of `basis`. `record` holds the scores of the same linearisation (kClusteredSandwich
/// only). No covariance when `degenerate` or the system is empty.
Uncertainty estimate_uncertainty(const LinearSystem& system, const DofBasis& basis,
                                 const CovarianceSettings& settings, const ScoreRecord* record,
                                 bool degenerate);

}  // namespace scantling::registration::detail
