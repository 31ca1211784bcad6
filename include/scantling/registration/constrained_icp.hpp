#pragma once
/// @file
/// The crawler's pose correction between consecutive stop clouds (SPEC §6): point-to-plane ICP
/// restricted to the surface plane (x, y, yaw), with caps on the correction that make it fall
/// back to its prior instead of jumping.
///
/// Frames: both clouds are given in the same local frame, in which z is the normal of the
/// surface the crawler drives on. Typically `source` is the new stop cloud in the new robot
/// frame and `target` the previous stop cloud mapped into the predicted new robot frame
/// (through the localisation poses captured at both stops); the result's T_target_source is then
/// the correction C of corrected_map_pose.
///
/// Determinism and threads as icp.hpp; the optional random thinning to `max_points` is seeded.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/registration/result.hpp>
#include <scantling/registration/robust_kernel.hpp>

namespace scantling::registration {

struct ConstrainedIcpConfig {
    int num_neighbors = 15;   ///< target normals from 15 neighbours (SPEC §6 k-d tree matcher)
    int max_iterations = 25;  ///< SPEC §6, >= 1
    /// Pairs farther apart are dropped, metres, > 0. Not in the SPEC: 0.5 m lets every pair of a
    /// correction within the 0.35 m cap in, and little else.
    double max_correspondence_distance_m = 0.5;
    RobustKernel kernel = RobustKernel::kNone;  ///< as IcpConfig::kernel
    double kernel_scale_m = 0.05;               ///< as IcpConfig::kernel_scale_m, > 0
    /// Solve for x, y, yaw only (roll = pitch = z = 0 in the local frame, SPEC §6); false
    /// solves all six degrees of freedom (the caps still apply).
    bool planar = true;
    double max_rotation_rad = 0.05;   ///< cap on the correction's rotation angle (SPEC §6), > 0
    double max_translation_m = 0.35;  ///< cap on the correction's translation norm (SPEC §6), > 0
    /// Stop when one update moves less than both (SPEC §6 "differential errors below 0.01").
    double rotation_tolerance_rad = 0.01;
    double translation_tolerance_m = 0.01;
    /// Voxel filter of both clouds before matching, metres (SPEC §6 grid filter 0.01 m);
    /// 0 = off, otherwise > 0.
    double voxel_size_m = 0.01;
    /// Most points kept per cloud after the voxel filter (SPEC §6 max density 400000), chosen
    /// uniformly at random with `seed`; 0 = no limit.
    std::size_t max_points = 400000;
    std::uint64_t seed = 1;
    int min_correspondences = 10;        ///< as IcpConfig::min_correspondences, >= 6
    double degeneracy_threshold = 1e-2;  ///< as IcpConfig::degeneracy_threshold, in (0, 1)
    ParallelConfig parallel;

    /// Throws ConfigError("<prefix>.max_rotation_rad = 0, expected finite > 0").
    void validate(std::string_view prefix = "constrained_icp") const;
};

/// Aligns `source` to `target` from `T_target_source_prior` (identity: the prior correction is
/// none). The correction Δ = T_target_source · prior⁻¹ is capped: when an iteration takes its
/// rotation angle above max_rotation_rad or its translation norm above max_translation_m, the
/// prior is returned with converged = false and status "cap_hit: <which cap and value>".
/// With `planar`, the update is a left twist (x, y, yaw) in the target frame, so z, roll and
/// pitch of the prior are kept bit-exactly. The covariance has zero rows and columns for the
/// fixed directions. Target normals present in `target` are used; otherwise estimated.
/// num_inliers and fitness refer to the filtered source (voxel grid, max_points).
/// Throws InputError for an empty, inconsistent or non-finite cloud or prior; ConfigError.
RegistrationResult align_constrained(
    const PointCloud& source, const PointCloud& target, const ConstrainedIcpConfig& config,
    const Eigen::Isometry3d& T_target_source_prior = Eigen::Isometry3d::Identity());

/// Corrected map pose after a stop (SPEC §6): P_new = P_prev · P_cprev⁻¹ · P_cnew · C.
/// `P_prev` = T_map_robot at the previous stop (already corrected); `P_cprev`, `P_cnew` =
/// T_loc_robot captured from the localisation (PF) at the previous and the new stop;
/// `C` = the ICP correction T_predicted_robot (the new robot frame in the frame predicted by the
/// localisation's relative motion). Pure, O(1).
Eigen::Isometry3d corrected_map_pose(const Eigen::Isometry3d& P_prev,
                                     const Eigen::Isometry3d& P_cprev,
                                     const Eigen::Isometry3d& P_cnew, const Eigen::Isometry3d& C);

}  // namespace scantling::registration
