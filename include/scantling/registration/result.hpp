#pragma once
/// @file
/// What every registration method returns (CONVENTIONS §5): the transform, whether it can be
/// trusted, quality figures, and the uncertainty the method can give.
///
/// Twists, information and covariance use the (rho, omega) order of core/se3.hpp, translation
/// first (metres), rotation last (radians), and the LEFT perturbation in the target frame:
/// the true transform is `se3_exp(epsilon) * T_target_source` with epsilon ~ N(0, covariance).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <scantling/core/se3.hpp>

namespace scantling::registration {

/// Directions of the pose that the geometry does not constrain (SPEC §11 "degeneracy
/// awareness"): a single plane leaves its two in-plane translations and the rotation about its
/// normal free; a long corridor leaves the translation along it.
struct DegeneracyReport {
    /// Eigenvalues of the Hessian, ascending, each divided by the largest (so in [0, 1]).
    /// Before the decomposition the Hessian is moved to the centroid of the correspondences and
    /// its rotation part scaled by their RMS radius, so the six values share one unit
    /// (metres of displacement) and do not depend on where the frame origin is.
    Vector6d eigenvalues = Vector6d::Zero();
    /// Unit twists (rho, omega) at the target-frame origin, one per eigenvalue below the
    /// threshold, weakest first. A motion along one barely changes the cost.
    std::vector<Vector6d> weak_directions;
    bool degenerate = false;  ///< true when weak_directions is not empty
};

struct RegistrationResult {
    /// Maps source points into the target frame: `p_target = T_target_source * p_source`.
    Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
    /// True only when the iteration met its convergence test with enough correspondences and no
    /// cap was hit. "Did not converge" is data, not an exception.
    bool converged = false;
    int iterations = 0;           ///< pose updates applied
    std::size_t num_inliers = 0;  ///< source points with a correspondence at the final pose
    double fitness = 0.0;         ///< num_inliers / source size, in [0, 1]
    double rmse_m = 0.0;          ///< RMS of the inliers' residual distances, metres
    /// Inverse covariance in the target frame, (rho, omega) order: for ICP the inverse of
    /// `covariance` (in the free directions) when there is one, otherwise the Hessian of the final
    /// cost scaled by the residual variance (and, for the clustered model, its design effect; see
    /// icp.hpp), which still shows the weak directions.
    Matrix6d information = Matrix6d::Zero();
    /// The pose's covariance when the problem is well conditioned (not degenerate); empty
    /// otherwise, because an unconstrained direction has no finite variance, and for ICP's
    /// clustered model also when the scan spans too few cells (icp.hpp).
    std::optional<Matrix6d> covariance;
    DegeneracyReport degeneracy;  ///< from the final Hessian
    /// Why it stopped: "converged", "max_iterations", "too_few_correspondences: ...",
    /// "cap_hit: ..." (constrained ICP; the prior was returned).
    std::string status;
};

}  // namespace scantling::registration
