#pragma once
/// @file
/// RANSAC global registration from putative correspondences, the baseline of Open3D's
/// RegistrationRANSACBasedOnFeatureMatching / ...BasedOnCorrespondence (0.16).
///
/// Each iteration draws 3 distinct correspondences, rejects the sample when an edge of the
/// source triangle and the matching target edge differ by more than the edge-length ratio
/// (CorrespondenceCheckerBasedOnEdgeLength), fits the rigid motion (Horn/SVD), rejects it when a
/// sampled pair lands farther apart than the inlier distance
/// (CorrespondenceCheckerBasedOnDistance), and scores it by the share of all correspondences within
/// that distance (fitness; ties: lower inlier RMSE). Stops after max_iterations or after log(1 −
/// confidence) / log(1 − fitness³) iterations. Finally the best hypothesis is refitted on its
/// inliers (least squares).
///
/// Parallelism without losing determinism: iterations run in fixed batches, batch b drawing
/// from `Rng(seed).split(b)`; batches are evaluated in parallel in fixed groups, their bests
/// combined in batch order, and the stopping test applied between groups. The result depends on
/// the seed only, never on the thread count.
/// Cost: O(N) per hypothesis that passes the checkers (N = correspondences).

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/registration/feature_matching.hpp>
#include <scantling/registration/result.hpp>

namespace scantling::registration {

struct RansacConfig {
    /// A correspondence is an inlier of a hypothesis when the transformed source point lies
    /// within this distance of its target point, metres, > 0. Open3D's examples: 1.5 × voxel
    /// (0.075 m for 0.05 m voxels).
    double max_correspondence_distance_m = 0.075;
    /// Edge-length checker: every edge ratio of the sampled triangles must exceed this, in
    /// (0, 1); 0.9 as in Open3D's examples.
    double edge_length_ratio = 0.9;
    /// Distance checker: reject a hypothesis whose own sample pairs are farther apart than
    /// max_correspondence_distance_m (Open3D's examples use it).
    bool check_distance = true;
    /// Most hypotheses drawn, >= 1 (Open3D: 100000).
    int max_iterations = 100000;
    /// Early stop once the probability of having drawn an all-inlier sample reaches this, in
    /// (0, 1); 0.999 as Open3D's RANSACConvergenceCriteria.
    double confidence = 0.999;
    /// Fewest inliers of the best hypothesis for `converged`, >= 3.
    int min_inliers = 3;
    std::uint64_t seed = 0;   ///< seed of the sampling (see the determinism note)
    ParallelConfig parallel;  ///< threads over batches of hypotheses

    /// Throws ConfigError naming the field ("ransac.confidence = 1, expected in (0, 1)").
    void validate(std::string_view prefix = "ransac") const;
};

struct RansacResult {
    /// Pose (T_target_source), converged (a hypothesis with >= min_inliers), iterations
    /// (hypotheses drawn), num_inliers, fitness (inliers / correspondences), rmse_m, status.
    RegistrationResult registration;
    std::vector<std::size_t> inliers;  ///< indices into the correspondences, ascending
};

/// RANSAC over `correspondences` between `source_points` and `target_points` (indices must be
/// in range: InputError otherwise; non-finite points: InputError). Fewer than 3 correspondences
/// or no hypothesis passing the checkers give converged = false.
RansacResult ransac_register(std::span<const Eigen::Vector3d> source_points,
                             std::span<const Eigen::Vector3d> target_points,
                             std::span<const Correspondence> correspondences,
                             const RansacConfig& config = {});

}  // namespace scantling::registration
