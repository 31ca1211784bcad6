#pragma once
/// @file
/// Trajectory evaluation against ground truth: the KITTI odometry metric (relative
/// translational and rotational error over 100–800 m segments), the absolute trajectory error
/// (ATE) after an SE(3) Umeyama alignment, the relative pose error (RPE) over a fixed distance,
/// and the association of time-stamped trajectories.
///
/// Poses are `T_world_body` (`p_world = T * p_body`); `gt` and `est` are matched index by index
/// (call `associate_by_time` first for time-stamped trajectories). Path distances are always
/// measured along the ground truth, as the KITTI devkit does. Errors between matched relative
/// motions are `E = (T_est_i⁻¹ T_est_j)⁻¹ (T_gt_i⁻¹ T_gt_j)` (the devkit's pose_error).
///
/// Pose files print rotations to 6–9 digits, so they are orthonormal only to ~1e-6. The
/// relative metrics (KITTI, RPE) therefore project every rotation onto SO(3) first (so that
/// the inverse is exact) and measure E from the difference of the two relative motions: a
/// trajectory evaluated against itself gives exactly 0 in every metric. A rotation further
/// than 1e-3 from orthonormal (max |RᵀR − I|, as the readers accept) or with det <= 0 is an
/// InputError naming the pose.
///
/// All functions are pure, single-threaded and deterministic; costs are O(n log n) in the number
/// of poses (the KITTI metric: O(n/step · lengths · log n)).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

namespace scantling {

/// SE(3) (rotation and translation, no scale) that best maps `est_positions` onto
/// `gt_positions` in the least-squares sense (Umeyama 1991): minimises
/// Σ |T p_est,i − p_gt,i|². Returns `T_gt_est`. Throws InputError when the sizes differ, there
/// are fewer than 3 pairs, a point is not finite, or the points are collinear or coincident
/// (the rotation about the line is then not determined). O(n).
Eigen::Isometry3d align_umeyama(const std::vector<Eigen::Vector3d>& est_positions,
                                const std::vector<Eigen::Vector3d>& gt_positions);

/// Distance travelled along `poses` up to each pose (first entry 0), metres.
std::vector<double> cumulative_distances_m(std::span<const Eigen::Isometry3d> poses);

/// Parameters of the KITTI odometry metric (devkit `evaluate_odometry.cpp`).
struct KittiMetricConfig {
    /// Segment lengths along the ground-truth path, metres, each > 0.
    std::vector<double> segment_lengths_m = {100, 200, 300, 400, 500, 600, 700, 800};
    int frame_step = 10;  ///< a segment starts at every frame_step-th frame (1 s at 10 Hz), >= 1

    /// Throws ConfigError("<prefix>.frame_step = 0, expected >= 1").
    void validate(std::string_view prefix = "kitti") const;
};

/// Errors of the segments of one length.
struct KittiLengthErrors {
    double length_m = 0.0;
    std::size_t num_segments = 0;
    double rte_percent = 0.0;       ///< 100 × mean |translation of E| / length
    double rre_deg_per_100m = 0.0;  ///< mean (angle of E / length) in deg per 100 m
};

/// The KITTI metric: mean over all segments (of every length) of the sequence, as the
/// devkit's per-sequence figure (this is what SiMpLE and most papers quote per sequence).
struct KittiMetrics {
    /// Number of segments over all lengths; 0 when the path is shorter than the shortest
    /// length, and then the two means are NaN.
    std::size_t num_segments = 0;
    double rte_percent = 0.0;                   ///< 100 × mean t_err/len (t_err in m, len in m)
    double rre_deg_per_100m = 0.0;              ///< mean r_err/len in rad/m × 180/π × 100
    std::vector<KittiLengthErrors> per_length;  ///< lengths with at least one segment
};

/// The KITTI metric of `est` against `gt` (same size, matched by index). For each start frame
/// (every frame_step-th) and each length, the segment ends at the first frame whose ground-truth
/// distance from the start exceeds the length (strictly, as the devkit); t_err = |trans E|,
/// r_err = the angle of R_E (the devkit's acos(½(trace R_E − 1)), computed in the
/// well-conditioned form 2 asin(|R_gt − R_est|_F / √8) of the two relative rotations), both
/// divided by the length.
/// @note Computed in double where the devkit uses float. On SiMpLE's published KITTI 00–10
/// estimates the RTE agrees with its README to the 4 printed decimals; the RRE differs from
/// the float devkit by up to 0.002 deg/100 m (float acos near 1 is coarse; double is closer
/// to the true angle).
/// Throws InputError (see evaluate_trajectory) or ConfigError.
KittiMetrics kitti_metrics(std::span<const Eigen::Isometry3d> gt,
                           std::span<const Eigen::Isometry3d> est,
                           const KittiMetricConfig& config = {});

/// Absolute trajectory error: position errors after the SE(3) alignment of `est` onto `gt`.
struct AteResult {
    Eigen::Isometry3d T_gt_est = Eigen::Isometry3d::Identity();  ///< the alignment applied
    std::vector<double> errors_m;  ///< |T_gt_est p_est,i − p_gt,i| per pose
    double rmse_m = 0.0;
    double mean_m = 0.0;
    double median_m = 0.0;
    double max_m = 0.0;
    double percent_of_path = 0.0;  ///< 100 × rmse / ground-truth path length (NaN if 0 length)
};

/// ATE of `est` against `gt` (same size, >= 2 poses). On a straight path the rotation about
/// the line is not determined, but every minimiser gives the same errors, so no error is
/// thrown there (unlike align_umeyama). Positions equal to the ground truth give exactly 0.
AteResult absolute_trajectory_error(std::span<const Eigen::Isometry3d> gt,
                                    std::span<const Eigen::Isometry3d> est);

/// Relative pose error over a fixed travelled distance.
struct RpeConfig {
    double delta_m = 10.0;  ///< ground-truth distance between the two poses of a pair, > 0

    /// Throws ConfigError("<prefix>.delta_m = 0, expected > 0").
    void validate(std::string_view prefix = "rpe") const;
};

struct RpeResult {
    double delta_m = 0.0;
    /// Pairs (i, j) evaluated: for every i, the first j with distance ≥ delta_m. 0 when the
    /// path is shorter than delta_m, and then the statistics are NaN.
    std::size_t num_pairs = 0;
    double trans_rmse_m = 0.0;  ///< RMS of |translation of E|
    double trans_mean_m = 0.0;
    double rot_mean_deg = 0.0;  ///< mean rotation angle of E
};

/// RPE of `est` against `gt` (same size, matched by index).
RpeResult relative_pose_error(std::span<const Eigen::Isometry3d> gt,
                              std::span<const Eigen::Isometry3d> est, const RpeConfig& config = {});

struct TrajectoryMetricsConfig {
    KittiMetricConfig kitti;
    RpeConfig rpe;

    void validate(std::string_view prefix = "eval") const;
};

/// Every metric of one estimated trajectory.
struct TrajectoryMetrics {
    std::size_t num_poses = 0;
    double path_length_m = 0.0;  ///< ground-truth path length
    KittiMetrics kitti;
    AteResult ate;
    RpeResult rpe;
};

/// All metrics of `est` against `gt`. Throws InputError when either is empty, the sizes differ,
/// there are fewer than 2 poses, or a pose is not finite; ConfigError for a bad config.
TrajectoryMetrics evaluate_trajectory(std::span<const Eigen::Isometry3d> gt,
                                      std::span<const Eigen::Isometry3d> est,
                                      const TrajectoryMetricsConfig& config = {});

/// Time-stamped poses matched by time.
struct AssociationConfig {
    /// An estimate is kept when the nearest ground-truth stamp is at most this far, seconds,
    /// >= 0. 0.02 s as the TUM benchmark tools.
    double max_time_difference_s = 0.02;
    /// Interpolate the ground truth at the estimate's stamp (slerp and linear translation
    /// between the two neighbouring ground-truth poses) instead of taking the nearest one.
    bool interpolate_gt = true;

    void validate(std::string_view prefix = "association") const;
};

struct AssociatedTrajectories {
    std::vector<double> stamps_s;  ///< the estimate's stamps that were matched
    std::vector<Eigen::Isometry3d> gt;
    std::vector<Eigen::Isometry3d> est;
    std::size_t num_unmatched = 0;  ///< estimates with no ground truth within the limit
};

/// Matches each estimated pose to the ground truth at its time stamp. Stamps must be finite
/// and strictly increasing in both inputs. Throws InputError for empty or mismatched inputs,
/// bad stamps, non-finite poses, or fewer than 2 matched poses (naming the time ranges).
AssociatedTrajectories associate_by_time(std::span<const double> gt_stamps_s,
                                         std::span<const Eigen::Isometry3d> gt,
                                         std::span<const double> est_stamps_s,
                                         std::span<const Eigen::Isometry3d> est,
                                         const AssociationConfig& config = {});

}  // namespace scantling
