#pragma once
/// @file
/// Robust kernels (M-estimators) for iteratively reweighted least squares.
///
/// A kernel replaces the squared residual r²/2 by a loss rho(r) that grows more slowly for large
/// |r|. IRLS minimises it by solving weighted least squares with w(r) = rho'(r) / r, recomputed
/// at every iteration. All losses satisfy rho(r) ≈ r²/2 and w ≈ 1 for |r| ≪ scale.
///
/// Pure functions: thread-safe, deterministic, O(1).

#include <string_view>

namespace scantling::registration {

enum class RobustKernel {
    kNone,          ///< rho = r²/2, w = 1 (plain least squares)
    kHuber,         ///< quadratic up to `scale`, linear beyond; w = min(1, scale / |r|)
    kCauchy,        ///< rho = s²/2 log(1 + (r/s)²); w = 1 / (1 + (r/s)²)
    kGemanMcClure,  ///< rho = (s² r²/2) / (s² + r²); w = (s² / (s² + r²))²
    kTukey,         ///< biweight: w = (1 − (r/s)²)² inside |r| < s, 0 beyond (hard rejection)
};

/// "none", "huber", "cauchy", "geman_mcclure", "tukey".
std::string_view to_string(RobustKernel kernel);

/// Inverse of to_string; throws ConfigError naming `field` and listing the accepted names.
RobustKernel robust_kernel_from_string(std::string_view name, std::string_view field = "kernel");

/// IRLS weight w(r) = rho'(r) / r, in [0, 1]. `residual` and `scale` share a unit (metres for
/// the ICP family); `scale` must be > 0 (not checked here: this is the hot path, configs check
/// it). For r = 0 the limit 1 is returned.
double robust_weight(RobustKernel kernel, double residual, double scale);

/// The loss rho(r) whose weights robust_weight returns (for cost reporting and tests).
double robust_loss(RobustKernel kernel, double residual, double scale);

}  // namespace scantling::registration
