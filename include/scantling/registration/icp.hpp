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
/// Uncertainty: at the final estimate, with H the weighted Gauss-Newton Hessian (free DoFs),
/// g_i = w_i Jᵢᵀ Ω rᵢ the score of correspondence i (its term of the gradient) and
/// A_i = w_i Jᵢᵀ Ω its sensitivity to a shift of its target point, two models
/// (IcpConfig::covariance):
/// - kHessian: covariance = s² H⁻¹ with s² = Σ w rᵀ Ω r / (N − 6) (Ω = 1 for point-to-point
///   and point-to-plane, the GICP weight otherwise). Right only for independent residuals and
///   exact correspondences. Against a CAD map, neighbouring residuals share their errors (voxel
///   centroids at edges, the map's sampling, its hidden faces): on simulated tank scans its
///   mean NEES was 340–810 for an expected 6, still 35–96 with back faces rejected
///   (docs/results.md).
/// - kClusteredSandwich (default): the cluster-robust sandwich plus a correlated map error,
///     covariance = H⁻¹ (G/(G−1) Σ_c g_c g_cᵀ + σ_m² Σ_c A_c A_cᵀ) H⁻¹,
///   g_c, A_c the sums over the correspondences in cell c: cubic cells of
///   `covariance_cell_size_m` (by the point in the target frame, G occupied cells). The first
///   term lets residuals within a cell be correlated in any way (cells independent) and agrees
///   with kHessian for independent residuals; the second, σ_m = `map_error_sigma_m`, shifts all
///   target surfaces of a cell together by N(0, σ_m²) along their normals (isotropically for
///   point-to-point and GICP): errors the pose absorbs, so the residuals cannot show them. It
///   needs G >= 3 × DoF cells (with 12–17 cells the mean NEES was twice too large): otherwise no
///   covariance. `information` is the covariance's inverse when there is one; otherwise H over s²
///   times the design effect tr(M) / (s² tr H), M the middle term (a scalar inflation that keeps
///   the weak directions visible).
/// Neither model sees a bias shared by all surfaces: see `back_faces` for the one CAD
/// maps cause. Point-to-point treats the matched points as fixed, so its Hessian cannot see
/// sliding along a surface: its covariance and degeneracy report are optimistic. Use
/// point-to-plane or GICP when the uncertainty matters. Exact data keep a finite covariance
/// through a floor of 1e-10 on s² (and 1e-10 H added to M).
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

/// How RegistrationResult::covariance is estimated (see the file comment).
enum class IcpCovariance {
    kHessian,            ///< s² H⁻¹: independent residuals assumed
    kClusteredSandwich,  ///< H⁻¹ (Σ_cells g_c g_cᵀ) H⁻¹: residuals correlated within a cell
};

/// What to do when a source point's nearest target point lies on a surface facing away from
/// the sensor (see IcpConfig::back_faces). Uses the target's own normals only.
enum class BackFaces {
    kKeep,  ///< the nearest target point, whatever its normal
    /// The nearest front-facing target point among the 8 nearest; the nearest when none faces
    /// the sensor (normals not oriented for this viewpoint: the plain nearest neighbour).
    kPreferFront,
    kReject,  ///< drop the pair when the nearest target point faces away
};

/// "keep", "prefer_front", "reject".
std::string_view to_string(BackFaces mode);

/// Inverse of to_string; throws ConfigError naming `field` and listing the accepted names.
BackFaces back_faces_from_string(std::string_view name, std::string_view field = "back_faces");

/// "hessian", "clustered_sandwich".
std::string_view to_string(IcpCovariance model);

/// Inverse of to_string; throws ConfigError naming `field` and listing the accepted names.
IcpCovariance icp_covariance_from_string(std::string_view name,
                                         std::string_view field = "covariance");

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
    IcpCovariance covariance = IcpCovariance::kClusteredSandwich;  ///< see the file comment
    /// Cell edge of kClusteredSandwich, metres, > 0: longer than the distance over which
    /// residual errors are correlated, short enough for >= 3 cells per DoF in a scan. 1 m: on
    /// simulated tank scans at 0.05 m voxels (back faces rejected, σ_m = 1 mm, 100 trials each)
    /// the mean NEES was 4.6 (depth camera, ballast-tank mock-up) and 7.1 (360° LiDAR,
    /// distillation column) for 6 expected, 4.7 and 4.7 with the default kPreferFront; 0.5 m
    /// cells gave 8.2 and 12.5, 1.5 m too few cells in a depth camera's view.
    double covariance_cell_size_m = 1.0;
    /// σ_m of kClusteredSandwich, metres, >= 0 (0: the residual sandwich alone): how far the
    /// target surfaces of one cell may sit, together, from where the map puts them (the map's
    /// accuracy and both clouds' discretisation: at 0.05 m voxels a bias of ~1 mm remains that
    /// no residual shows). 1 mm: with it the NEES above, without it 33 and 9.9 (back faces
    /// rejected); 2 mm gave 1.9 and 5.0. A real CAD map's as-built deviations are larger and belong
    /// here.
    double map_error_sigma_m = 0.001;
    /// Target points whose normal faces away from the source origin o (the sensor, for a scan
    /// given in its sensor or body frame): n_t · (o − t) <= 0, o in the target frame. A CAD
    /// map's triangle normals point to the free side, and a map sampled on both faces of 1 cm
    /// plates otherwise pairs much of the scan with hidden faces and pulls the pose towards
    /// them (mock-up: 3.7 mm along the view, median error 4.3 mm, 1.1 mm without; no
    /// covariance model is consistent with that bias, docs/results.md). kPreferFront (default)
    /// fixes that and is harmless elsewhere: normals estimated from a cloud face that cloud's
    /// sensor, and where none of the 8 nearest faces this sensor the nearest is kept. Only
    /// normals present in `target` are used (without them every mode is kKeep), except that
    /// kReject requires them. A kNN search runs only for points whose nearest faces away.
    BackFaces back_faces = BackFaces::kPreferFront;
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
/// a target with fewer than 3 points when normals/covariances must be estimated, or a target
/// without normals when `back_faces` is kReject; ConfigError for a bad config. Too few
/// correspondences is a result (converged = false).
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

/// Same, within the directions a constrained solve may move (`free_basis`: columns spanning
/// them, as twists at the target origin; constrained_icp.hpp's planar x, y, yaw): the fixed
/// directions are not asked of the geometry, so they are never weak, and "divided by the
/// largest" compares the free directions among themselves. Why: a plate's normal constrains z,
/// roll and pitch a hundred times more than the few points on a bead constrain x or y, and the
/// six-direction ratio would call every planar registration degenerate. eigenvalues holds the
/// free directions' values ascending, then 1 for each fixed one. Pure, O(1).
DegeneracyReport analyze_degeneracy(const Matrix6d& H, const Eigen::Vector3d& centroid_target,
                                    double radius_m, double threshold,
                                    const Eigen::Matrix<double, 6, Eigen::Dynamic>& free_basis);

}  // namespace scantling::registration
