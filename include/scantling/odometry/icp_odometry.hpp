#pragma once
/// @file
/// The baseline LiODOM is measured against (issue 4, item 4): scan-to-scan point-to-plane ICP.
/// Each sweep, range-gated and voxel-downsampled, is aligned to the previous one from the
/// constant-velocity prediction, and the relative poses are chained. No map: drift accumulates
/// with every pair, which is what a map-based odometry is supposed to beat.
#include <Eigen/Geometry>
#include <string_view>
#include <vector>

#include <scantling/odometry/liodom.hpp>
#include <scantling/registration/icp.hpp>

namespace scantling::odometry {

struct IcpOdometryConfig {
    double min_range_m = 0.5;   ///< closer points dropped, m
    double max_range_m = 80.0;  ///< farther points dropped, m
    double voxel_size_m = 0.2;  ///< downsampling of each sweep, m (> 0)
    /// Point-to-plane, 1 m correspondences, Huber kernel: the usual scan-to-scan setting.
    registration::IcpConfig icp = [] {
        registration::IcpConfig c;
        c.method = registration::IcpMethod::kPointToPlane;
        c.kernel = registration::RobustKernel::kHuber;
        c.max_correspondence_distance_m = 1.0;
        c.translation_tolerance_m = 1e-4;
        c.rotation_tolerance_rad = 1e-5;
        // The chained poses carry no covariance: skip the clustered model's extra pass.
        c.covariance = registration::IcpCovariance::kHessian;
        return c;
    }();
    double max_time_gap_s = 0.5;
    /// A registration implying a faster motion is rejected (the pose is predicted and the
    /// velocity reset): ICP sliding along a featureless direction otherwise runs away, m/s.
    double max_speed_mps = 40.0;
    ParallelConfig parallel{};
    void validate(std::string_view prefix = "icp_odometry") const;
};

/// The baseline with the range gate and voxel size of a LiODOM config (same sensor, same data).
IcpOdometryConfig icp_odometry_config_like(const LiodomConfig& liodom);

/// Runs the baseline over `num_sweeps` sweeps; reports as run_odometry (register_ms holds the
/// ICP time, extract_ms the downsampling and normals, map_ms 0). A sweep that cannot be read,
/// is empty or does not converge is carried by the motion model.
std::vector<FrameReport> run_icp_odometry(
    std::size_t num_sweeps, const SweepReader& read_sweep, const IcpOdometryConfig& config,
    const FrameCallback& on_frame = {},
    const Eigen::Isometry3d& T_odom_initial = Eigen::Isometry3d::Identity(),
    const MotionPrior& prior = {});

}  // namespace scantling::odometry
