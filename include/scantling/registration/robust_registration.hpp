#pragma once
/// @file
/// Certifiably robust global registration after TEASER++ (Yang, Shi & Carlone, "TEASER: Fast
/// and Certifiable Point Cloud Registration", T-RO 2020), scale fixed to 1 (SPEC §7).
///
/// Given putative correspondences (s_k, t_k), with inliers t_k = R s_k + t + e_k, |e_k| <= β:
/// 1. pairwise translation-invariant measurements (TIMs) s_j − s_i, t_j − t_i; a pair is
///    consistent when | |t_j − t_i| − |s_j − s_i| | <= 2β√c̄² (rigid motions keep lengths);
/// 2. consistency graph (vertices: correspondences, edges: consistent pairs) and its maximum
///    clique (max_clique.hpp): the largest mutually consistent set;
/// 3. rotation by GNC-TLS (graduated non-convexity with truncated least squares, Yang et al.
///    RA-L 2020) on the chain of the clique's TIMs (noise bound 2β), each step a weighted
///    Horn/SVD fit;
/// 4. translation by adaptive voting: exact 1-D TLS per axis over t_k − R s_k of the rotation
///    inliers (bound β√c̄²);
/// 5. inliers = correspondences with |R s_k + t − t_k| <= β√c̄²; (R, t) is finally refitted on
///    them by least squares (Horn), which only reduces the noise.
/// Hypothesis verification (cloud overload, HypothesisConfig::num_hypotheses > 1): with few
/// true matches among many wrong ones (FPFH in self-similar or near-symmetric scenes), wrong
/// matches can form the largest consistent set. Steps 3–5 then run on several vertex-disjoint
/// large cliques (the maximum clique, then greedy cliques grown from the unused vertices of
/// highest core number), and the pose under which the most source points lie near the target
/// cloud wins, as in RANSAC's fitness (ties: more correspondence inliers, then the earlier
/// clique; a pose within 1° and β√c̄² of the current best does not replace it).
/// The gravity-aligned 4-DoF variant (RobustRotation::kYawOnly) restricts R to a rotation about
/// z, for robots whose roll and pitch are known: express both clouds in gravity-aligned frames
/// (z up) first. Its pruning also uses the invariance of height differences, and its rotation is
/// an exact 1-D TLS over the yaw angle (sweep over the arcs where each TIM fits).
///
/// Cost: O(N²) pair checks (parallel), the clique search, O(M) per GNC iteration, O(M log M)
/// voting (M = clique size); verification adds O(V + E) for the further cliques, a k-d tree
/// over the target and, per candidate (parallel), a solve and max_scored_points queries.
/// Thread-safety: pure functions.
/// @note Deterministic: the same inputs give the same result for any thread count.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <scantling/core/normals.hpp>
#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/registration/feature_matching.hpp>
#include <scantling/registration/fpfh.hpp>
#include <scantling/registration/icp.hpp>
#include <scantling/registration/max_clique.hpp>
#include <scantling/registration/result.hpp>

namespace scantling::registration {

/// Which rotations the solver may return.
enum class RobustRotation {
    kFull,     ///< any rotation (6-DoF registration)
    kYawOnly,  ///< rotation about the z axis only (4-DoF: x, y, z, yaw; gravity-aligned frames)
};

/// Hypothesis verification: which candidate poses are compared, and how (cloud overload only).
struct HypothesisConfig {
    /// Candidate poses (cliques) scored, >= 1. 1 = plain TEASER++ (the maximum clique's pose,
    /// no overlap scoring). 32: on the simulated tank scans (docs/benchmarks.md) scan-to-scan
    /// success rose from 94–98 % to 100 % already with 8–16; scan-to-map in the column needed
    /// 32 (10 % with 16, 18 % with 32, no better with 64 or 128), at ~1 ms per candidate.
    int num_hypotheses = 32;
    /// A source point overlaps when a target point lies closer than this to it, metres, > 0.
    /// About 1.5 voxels, like RANSAC's max_correspondence_distance (0.075 m at 0.05 m voxels).
    double overlap_distance_m = 0.075;
    /// Most source points scored per hypothesis, >= 1 (an even subsample in index order).
    /// 2000 resolve overlap shares to about ±1 % at a fraction of a millisecond per pose.
    std::size_t max_scored_points = 2000;

    /// Throws ConfigError naming the field ("hypotheses.num_hypotheses = 0, expected >= 1").
    void validate(std::string_view prefix = "hypotheses") const;
};

struct RobustRegistrationConfig {
    /// β: largest norm of the error of an inlier correspondence, |t_k − (R s_k + t)|, metres,
    /// > 0. SPEC §7: β = 3σ with σ the point noise; for descriptor matches on voxelised clouds
    /// the matched points are only as close as the sampling, so use about one voxel (0.05 m).
    /// Too small rejects true inliers; too large lets more outliers look consistent.
    double noise_bound_m = 0.05;
    /// c̄²: square of the TLS threshold in units of β (TEASER++'s cbar2), > 0. 1 = a residual
    /// counts as inlier up to exactly β (SPEC §7).
    double cbar2 = 1.0;
    /// Estimate a scale factor too. Not supported (SPEC §7 fixes the scale to 1): true throws
    /// ConfigError. Kept so configs can state it explicitly, as in TEASER++.
    bool estimate_scaling = false;
    RobustRotation rotation = RobustRotation::kFull;  ///< 6-DoF or gravity-aligned 4-DoF
    /// Exact-search limits (see max_clique.hpp). 2·10⁴ search nodes instead of MaxCliqueConfig's
    /// 10⁵: with the hypotheses verified, the maximum clique need not be exact. On the simulated
    /// tank scan pairs (50 per case) success and median errors were the same at 2·10⁴ and 10⁵,
    /// and the scan pairs took 20–35 % less time (docs/benchmarks.md).
    MaxCliqueConfig max_clique{
        .solve_exactly = true, .max_vertices_exact = 20000, .max_search_nodes = 20'000};
    /// Most GNC iterations of the rotation solver, >= 1 (TEASER++: rotation_max_iterations 100).
    int gnc_max_iterations = 100;
    /// Factor by which GNC's μ grows each iteration (the surrogate cost approaches TLS), > 1.
    /// 1.4 as in TEASER++ (rotation_gnc_factor): larger is faster but less robust.
    double gnc_factor = 1.4;
    /// GNC stops when the weighted cost changes by less than this between iterations, in the
    /// cost's unit (m², sum of squared TIM residuals), > 0. TEASER++'s rotation_cost_threshold.
    double rotation_cost_threshold = 1e-6;
    /// Fewest final inliers for `converged`, >= 3 (3 points fix a rigid motion). With random
    /// outliers alone, chance cliques of 4–8 mutually consistent matches appear, so a lower
    /// value risks accepting a wrong pose; 10 keeps that risk negligible in our tests.
    int min_inliers = 10;
    /// Fewer inliers than this many times `noise_bound_m` of spread (standard deviation along
    /// the second principal axis, or horizontally for kYawOnly) cannot fix the rotation: the
    /// inliers are (nearly) collinear or coincident, and the result is not converged. >= 0.
    double min_spread_in_noise_bounds = 1.0;
    /// Verification of several candidate poses by overlap (used by the cloud overload only).
    HypothesisConfig hypotheses;
    ParallelConfig parallel;  ///< threads for the pair checks and the hypothesis scoring

    /// Throws ConfigError naming the field ("robust.noise_bound_m = 0, expected finite > 0").
    void validate(std::string_view prefix = "robust") const;
};

struct RobustRegistrationResult {
    /// Pose, converged flag (enough non-degenerate inliers), iterations (GNC steps),
    /// num_inliers, fitness (inliers / correspondences), rmse_m (inlier residual RMS), status.
    /// No information matrix: the TLS estimate has none (refine with ICP for one).
    RegistrationResult registration;
    std::vector<std::size_t> inliers;  ///< indices into the correspondences, ascending
    std::size_t max_clique_size = 0;   ///< vertices of the consistency graph's clique
    MaxCliqueMethod max_clique_method = MaxCliqueMethod::kExact;
    std::size_t num_consistent_pairs = 0;  ///< edges of the consistency graph
    /// Candidate poses scored by overlap (0 when no verification ran: the span overload, one
    /// hypothesis requested, or no clique of >= 3).
    std::size_t num_hypotheses_scored = 0;
    /// Which candidate won: 0 = the maximum clique, i = the i-th further clique.
    std::size_t winning_hypothesis = 0;
    /// Overlap share of the returned pose (see HypothesisConfig), in [0, 1]; 0 when not scored.
    double overlap = 0.0;
};

/// Robust registration of paired points: `source_points[k]` (source frame) corresponds to
/// `target_points[k]` (target frame). Returns T_target_source. Without clouds there is nothing
/// to verify a pose against: the maximum clique's pose is returned (config.hypotheses unused).
/// Throws InputError when the spans differ in length or hold a non-finite point; ConfigError on
/// a bad config. Fewer than 3 correspondences, a clique too small, too few inliers or
/// degenerate (collinear) inliers give converged = false with the reason in status.
RobustRegistrationResult robust_register(std::span<const Eigen::Vector3d> source_points,
                                         std::span<const Eigen::Vector3d> target_points,
                                         const RobustRegistrationConfig& config);

/// Same for correspondences between two clouds (indices into `source.points`, `target.points`;
/// InputError when out of range). `inliers` index `correspondences`. With
/// config.hypotheses.num_hypotheses > 1, several cliques' poses are verified by their overlap
/// of `source` with `target` (see the file comment); with 1, the same as the span overload.
RobustRegistrationResult robust_register(const PointCloud& source, const PointCloud& target,
                                         std::span<const Correspondence> correspondences,
                                         const RobustRegistrationConfig& config);

/// Everything `register_fpfh_teaser` does, in order.
struct FpfhPipelineConfig {
    /// Voxel size both clouds are downsampled to, metres, > 0. SPEC §7: 0.04–0.05 m.
    double voxel_size_m = 0.05;
    /// Normals: k nearest neighbours of the downsampled cloud, >= 3. 30 points span ~2 voxels
    /// each way, enough for a stable plane yet local; normals face `viewpoint` (see normals.hpp).
    NormalEstimationConfig normals{
        .num_neighbors = 30, .viewpoint = Eigen::Vector3d::Zero(), .parallel = {}};
    FpfhConfig fpfh;    ///< radius_m ≈ 5 × voxel_size_m (0.25 m for 0.05 m)
    MatchConfig match;  ///< mutual nearest neighbours by default
    /// Tuple test on the matches before the robust solver (off by default: the maximum clique
    /// already rejects inconsistent matches, and the test is random).
    std::optional<TupleFilterConfig> tuple_filter;
    std::uint64_t seed = 0;  ///< seed of the tuple test's Rng
    /// Robust solver; noise_bound_m should be about voxel_size_m (matched voxel centres differ
    /// by up to about one voxel even for correct matches). Its hypothesis verification scores
    /// the candidates on the downsampled clouds.
    RobustRegistrationConfig robust;
    /// Optional ICP refinement of the robust estimate on the downsampled clouds (when converged).
    /// Its max_correspondence_distance_m must cover the robust estimate's error (~2 voxels).
    std::optional<IcpConfig> refine;

    void validate(std::string_view prefix = "fpfh_pipeline") const;
};

struct FpfhPipelineResult {
    RobustRegistrationResult robust;  ///< the global estimate (before refinement)
    /// The final pose: the ICP result when refinement ran and converged, otherwise the robust
    /// estimate's registration result.
    RegistrationResult registration;
    bool refined = false;                 ///< ICP refinement ran and converged
    std::size_t num_source_points = 0;    ///< after downsampling
    std::size_t num_target_points = 0;    ///< after downsampling
    std::size_t num_correspondences = 0;  ///< passed to the robust solver
};

/// Global registration without an initial guess: voxel downsampling, normals, FPFH, mutual
/// matching, robust registration, optional ICP refinement. Returns T_target_source.
/// Throws InputError for empty or non-finite clouds; ConfigError on a bad config.
FpfhPipelineResult register_fpfh_teaser(const PointCloud& source, const PointCloud& target,
                                        const FpfhPipelineConfig& config = {});

}  // namespace scantling::registration
