#pragma once
/// @file
/// Local registration: point-to-point, point-to-plane and generalized ICP (GICP) with robust
/// kernels, one Gauss-Newton solver on SE(3).
///
/// Each iteration finds, for every source point mapped by the current estimate, its nearest
/// target point (k-d tree); pairs farther apart than `max_correspondence_distance_m` are
/// dropped. The weighted normal equations H delta = −b are accumulated in the same pass and
/// solved for the left twist delta = (rho, omega) in the target frame; the estimate becomes
/// `se3_exp(delta) * T`. Residuals and Jacobians: factors.hpp. Robust kernels by IRLS: the
/// weights are recomputed from the residuals at every iteration.
///
/// Uncertainty: at the final estimate, with H the weighted Gauss-Newton Hessian and the
/// residual variance factor s² = Σ w rᵀ Ω r / (N − 6) (Ω = 1 for point-to-point and
/// point-to-plane, the GICP weight otherwise; floored at 1e-10 so exact synthetic data keeps a
/// finite value), information = H / s² and, when the degeneracy report is clean,
/// covariance = s² H⁻¹. This assumes independent residuals and correct correspondences, so it
/// is a lower bound on the real error. Point-to-point treats the matched points as fixed, so its
/// Hessian cannot see sliding along a surface: its covariance and degeneracy report are
/// optimistic. Use point-to-plane or GICP when the uncertainty matters.
///
/// Cost per iteration: one nearest-neighbour query per source point, O(n log m).
/// Thread-safety: the functions only read their inputs; the tree may be shared between calls
/// running concurrently.
/// @note Deterministic: the normal equations are summed over fixed chunks of source points in
/// chunk order (parallel_reduce_ordered), so 1 and N threads give bit-identical results.

#include <string_view>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/registration/result.hpp>
#include <scantling/registration/robust_kernel.hpp>

namespace scantling::registration {

enum class IcpMethod {
    kPointToPoint,  ///< minimises |q − t|²
    kPointToPlane,  ///< minimises (n_t · (q − t))²; needs target normals
    kGeneralized,  ///< GICP: (q − t)ᵀ (C_t + R C_s Rᵀ)⁻¹ (q − t); needs both covariances
};

/// "point_to_point", "point_to_plane", "gicp".
std::string_view to_string(IcpMethod method);

/// Inverse of to_string; throws ConfigError naming `field` and listing the accepted names.
IcpMethod icp_method_from_string(std::string_view name, std::string_view field = "method");

struct IcpConfig {
    IcpMethod method = IcpMethod::kPointToPlane;  ///< converges in a few iterations on scans
    /// Most pose updates, >= 1. 30 as Open3D's ICPConvergenceCriteria.
    int max_iterations = 30;
    /// Pairs farther apart than this are not correspondences, metres, > 0. Must exceed the
    /// initial misalignment of matching surfaces; too large lets wrong pairs in. No default fits
    /// every scale: 1 m suits room- and street-scale scans starting within ~0.5 m.
    double max_correspondence_distance_m = 1.0;
    RobustKernel kernel = RobustKernel::kNone;  ///< IRLS kernel on the residual (see below)
    /// Kernel scale, metres, > 0: residuals well below it count fully. The kernel acts on the
    /// point-to-plane distance for point-to-plane and on |q − t| otherwise (so for GICP the
    /// scale must exceed the point spacing).
    double kernel_scale_m = 0.1;
    /// Converged when an update moves less than both tolerances (small_gicp's defaults:
    /// 1 mm and 0.1°), metres and radians, > 0.
    double translation_tolerance_m = 1e-3;
    double rotation_tolerance_rad = 1.7453292519943295e-3;
    /// Fewest correspondences to take a step, >= 6 (the unknowns); 10 keeps N − 6 in s² > 0.
    int min_correspondences = 10;
    /// Neighbours for target normals / covariances (and GICP source covariances) when the
    /// clouds lack them, >= 3. 10 as small_gicp's default: on the real LiDAR pair (voxels of
    /// 0.1–0.25 m) k = 10 gave 0.1–0.3° rotation error where k = 20 gave 0.2–0.7°, because a
    /// larger patch of a sparse scan bends over edges and curbs.
    int num_neighbors = 10;
    /// Normalised Hessian eigenvalue below which a direction counts as unconstrained, in
    /// (0, 1). 1e-2: a direction held by ~1 % of the points is reported (and GICP's
    /// regularised planes, with in-plane weight epsilon = 1e-3, are caught).
    double degeneracy_threshold = 1e-2;
    ParallelConfig parallel;  ///< threads for the correspondence and accumulation pass

    /// Throws ConfigError("<prefix>.max_iterations = 0, expected >= 1").
    void validate(std::string_view prefix = "icp") const;
};

/// Aligns `source` to `target` starting from `T_target_source_init`.
///
/// Missing target normals (point-to-plane) and missing covariances (GICP, both clouds) are
/// estimated with `num_neighbors` neighbours on internal copies; precompute them (core/normals.hpp)
/// when the same cloud is registered repeatedly.
/// Throws InputError for an empty, inconsistent or non-finite cloud, a non-finite initial pose,
/// or a target with fewer than 3 points when normals/covariances must be estimated;
/// ConfigError for a bad config. Too few correspondences is a result (converged = false).
RegistrationResult align(const PointCloud& source, const PointCloud& target,
                         const Eigen::Isometry3d& T_target_source_init, const IcpConfig& config);

/// Same, reusing `target_tree`, built over exactly `target.points` (InputError if the sizes
/// differ), so one tree serves many registrations against the same map.
RegistrationResult align(const PointCloud& source, const PointCloud& target,
                         const KdTree& target_tree, const Eigen::Isometry3d& T_target_source_init,
                         const IcpConfig& config);

/// Eigen-analysis of a Gauss-Newton Hessian `H` (left twists at the target origin, (rho,
/// omega) order) about `centroid_target` (metres) with rotations scaled by `radius_m` (> 0,
/// typically the RMS distance of the correspondences from their centroid). See
/// DegeneracyReport. A zero Hessian reports all six directions. Pure, O(1).
DegeneracyReport analyze_degeneracy(const Matrix6d& H, const Eigen::Vector3d& centroid_target,
                                    double radius_m, double threshold);

}  // namespace scantling::registration
