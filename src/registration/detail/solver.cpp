#include "solver.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Cholesky>

namespace scantling::registration::detail {
namespace {

// Levenberg damping relative to the Hessian's mean diagonal: far below any constraint worth
// using (the degeneracy threshold is 1e-2) yet large against rounding noise (~1e-16 relative)
// along exact null directions, where b is zero up to that noise: the step there stays ~1e-8.
constexpr double kRelativeDamping = 1e-8;
// A radius below this (metres) means coincident correspondences: rotations are then scaled by 1 m.
constexpr double kMinRadiusM = 1e-9;

Eigen::MatrixXd reduced(const Matrix6d& M, const DofBasis& B) { return B.transpose() * M * B; }

}  // namespace

Vector6d solve_step(const LinearSystem& system, const DofBasis& basis) {
    Eigen::MatrixXd H = reduced(system.H, basis);
    const double mean_diagonal = H.trace() / static_cast<double>(H.rows());
    H.diagonal().array() += kRelativeDamping * std::max(mean_diagonal, 1e-300);
    const Eigen::VectorXd b = basis.transpose() * system.b;
    return -(basis * H.ldlt().solve(b));
}

bool is_small_step(const Vector6d& delta, double translation_m, double rotation_rad) {
    return delta.head<3>().norm() < translation_m && delta.tail<3>().norm() < rotation_rad;
}

std::string too_few_status(std::size_t count, int min_correspondences) {
    return fmt::format("too_few_correspondences: {} < min_correspondences = {}", count,
                       min_correspondences);
}

void fill_statistics(RegistrationResult& result, const LinearSystem& system,
                     const ScoreRecord* record, std::size_t source_size,
                     const IterationSettings& settings) {
    const std::size_t n = system.count;
    result.num_inliers = n;
    result.fitness =
        source_size == 0 ? 0.0 : static_cast<double>(n) / static_cast<double>(source_size);
    result.rmse_m = n == 0 ? 0.0 : std::sqrt(system.distance_sq_sum_m2 / static_cast<double>(n));
    const double count = std::max(static_cast<double>(n), 1.0);
    const Eigen::Vector3d centroid = system.q_sum / count;
    const double radius_sq = system.q_norm_sq_sum / count - centroid.squaredNorm();
    const double radius = std::max(std::sqrt(std::max(radius_sq, 0.0)), kMinRadiusM);
    result.degeneracy = analyze_degeneracy(system.H, centroid, radius,
                                           settings.degeneracy_threshold, settings.basis);
    const Uncertainty u = estimate_uncertainty(system, settings.basis, settings.covariance, record,
                                               result.degeneracy.degenerate);
    result.information = u.information;
    result.covariance = u.covariance;
}

// Each loop linearises once, at the pose the last step produced, so the final statistics come
// from the returned pose without an extra pass; the linearisation known to be the last one
// (small step or last iteration) also records the scores of the clustered covariance.
RegistrationResult iterate(const Problem& problem, std::size_t source_size,
                           const Eigen::Isometry3d& T_init, const IterationSettings& settings) {
    const auto enough = [&](const LinearSystem& s) {
        return s.count >= static_cast<std::size_t>(settings.min_correspondences);
    };
    ScoreRecord scores{.cell_size_m = settings.covariance.cell_size_m, .scores = {}};
    ScoreRecord* record =
        settings.covariance.model == IcpCovariance::kClusteredSandwich ? &scores : nullptr;
    RegistrationResult result;
    result.T_target_source = T_init;
    result.status = "max_iterations";
    const LinearSystem initial = linearize(problem, T_init);
    LinearSystem system = initial;
    bool scored = false;  // `record` belongs to `system`
    while (enough(system) && result.iterations < settings.max_iterations) {
        const Vector6d delta = solve_step(system, settings.basis);
        const Eigen::Isometry3d T = se3_exp(delta) * result.T_target_source;
        ++result.iterations;
        const std::string cap = settings.cap_violation ? settings.cap_violation(T) : "";
        if (!cap.empty()) {
            result.T_target_source = T_init;
            result.status = "cap_hit: " + cap;
            if (record) linearize(problem, T_init, record);
            fill_statistics(result, initial, record, source_size, settings);
            return result;
        }
        result.T_target_source = T;
        const bool small =
            is_small_step(delta, settings.translation_tolerance_m, settings.rotation_tolerance_rad);
        const bool last = small || result.iterations == settings.max_iterations;
        system = linearize(problem, T, last ? record : nullptr);
        scored = last;
        if (small) {
            result.converged = true;
            result.status = "converged";
            break;
        }
    }
    if (!enough(system)) {
        result.converged = false;
        result.status = too_few_status(system.count, settings.min_correspondences);
    }
    if (record && !scored) system = linearize(problem, result.T_target_source, record);
    fill_statistics(result, system, record, source_size, settings);
    return result;
}

}  // namespace scantling::registration::detail
