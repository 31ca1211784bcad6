#pragma once
/// @file
/// How good is a registration: overlap and RMSE against the target, and the acceptance gates of
/// SPEC §7 (attitude against the IMU, speed between consecutive absolute poses, overlap).
///
/// Gates are pure functions returning GateResult; a failed gate is data, not an exception.
/// Thread-safety: all functions only read their inputs. Deterministic for any thread count
/// (fixed-chunk ordered reductions).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <string_view>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>

namespace scantling::registration {

/// Nearest-neighbour agreement of a registered cloud with its target.
struct CorrespondenceQuality {
    std::size_t num_inliers = 0;  ///< points with a target point within the distance
    double fitness = 0.0;         ///< num_inliers / source size (0 for an empty source)
    double rmse_m = 0.0;          ///< RMS nearest-neighbour distance of the inliers, metres
};

/// For each point of `source_in_target` (already mapped into the target frame), its nearest
/// point in `target_tree`; distances <= `max_distance_m` (finite, > 0) are inliers.
/// O(n log m). Throws InputError on a non-finite or inconsistent source, ConfigError on a bad
/// distance. An empty source or tree gives zeros.
CorrespondenceQuality evaluate_correspondences(const PointCloud& source_in_target,
                                               const KdTree& target_tree, double max_distance_m,
                                               const ParallelConfig& parallel = {});

/// Share of source points within one voxel (`voxel_m`) of the target, in [0, 1] (SPEC §7
/// quality measure).
double overlap_ratio(const PointCloud& source_in_target, const KdTree& target_tree, double voxel_m,
                     const ParallelConfig& parallel = {});

/// RMS nearest-neighbour distance of the points within `max_distance_m`, metres (0 if none).
double rmse(const PointCloud& source_in_target, const KdTree& target_tree, double max_distance_m,
            const ParallelConfig& parallel = {});

/// Outcome of a gate: `reason` says why it failed, with the numbers ("" when passed).
struct GateResult {
    bool passed = false;
    std::string reason;
};

struct AttitudeGateConfig {
    /// Largest accepted difference of roll and of pitch (each, wrapped to [−π, π]) between the
    /// registration and the IMU, radians, > 0. The SPEC gives no value: 5°, several times a
    /// MEMS IMU's attitude error, yet well below the tilt of a wrong match on a tilted structure.
    double max_difference_rad = 0.08726646259971647;

    void validate(std::string_view prefix = "attitude_gate") const;
};

/// SPEC §7: reject a registration whose roll or pitch disagrees with the IMU's. Both rotations
/// are R_world_body with world z up (gravity aligned); roll and pitch are the Z-Y-X Euler
/// angles of core/se3.hpp, which do not depend on yaw. Throws InputError on non-finite input.
GateResult check_attitude(const Eigen::Matrix3d& R_world_body_registration,
                          const Eigen::Matrix3d& R_world_body_imu,
                          const AttitudeGateConfig& config = {});

struct SpeedGateConfig {
    double max_speed_mps = 0.3;  ///< SPEC §7 motion filter, > 0

    void validate(std::string_view prefix = "speed_gate") const;
};

/// SPEC §7: reject a pose that implies moving faster than max_speed_mps since the previous
/// accepted absolute pose (straight-line distance over elapsed time). Throws InputError unless
/// `current_stamp_s > previous_stamp_s` and both poses and stamps are finite.
GateResult check_speed(const Eigen::Isometry3d& T_world_body_previous, double previous_stamp_s,
                       const Eigen::Isometry3d& T_world_body_current, double current_stamp_s,
                       const SpeedGateConfig& config = {});

struct OverlapGateConfig {
    double min_overlap = 0.75;  ///< SPEC §7: at least 75 % of scan points near the map, (0, 1]
    /// The "one voxel" of SPEC §7, metres, > 0; 0.05 m = the registration voxel size there.
    double voxel_size_m = 0.05;

    void validate(std::string_view prefix = "overlap_gate") const;
};

/// SPEC §7: reject a registration when fewer than min_overlap of the scan points lie within one
/// voxel of the map. `overlap` in [0, 1] (InputError otherwise), e.g. from overlap_ratio.
GateResult check_overlap(double overlap, const OverlapGateConfig& config = {});

/// Same, computing overlap_ratio(scan_in_map, map_tree, config.voxel_size_m) first.
GateResult check_overlap(const PointCloud& scan_in_map, const KdTree& map_tree,
                         const OverlapGateConfig& config = {}, const ParallelConfig& parallel = {});

}  // namespace scantling::registration
