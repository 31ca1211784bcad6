#pragma once
/// @file
/// A defect seen by the camera lifted into the map (SPEC §7, issue 12 item 4): the sighting's
/// pixel (a fiducial tag's centre in the sources; io::DefectSighting) meets the depth frame's
/// returns around it, through the fused poses at the image's and the depth frame's stamps.
///
/// Steps: the depth frame's returns (already in the world frame through the fused pose at its
/// stamp) are brought into the camera at the image stamp and projected; those within the
/// sighting's radius (at least min_support_radius_px) of its centre are the support. The
/// support is split into planes by RANSAC (plane_inlier_m bands: a stiffener beside the patch
/// or the plate meeting it is not the patch), the plane nearest to the return seen closest to
/// the centre is the patch's, and the centre's viewing ray is intersected with it. Intersecting the
/// ray, rather than averaging the returns, keeps the centre where the tag detector put it when the
/// returns are unevenly spread over the patch.
///
/// Covariance (world frame), in two parts kept apart because they merge differently over views
/// (defect_map.hpp): the measurement — range noise over the support along the ray, the pixel
/// noise across it, both stretched by 1 / cos(incidence) — and the fused pose's: the body pose
/// covariance (δp, δθ) carried to the point by J = [I, −[q − p_body]×].
///
/// Frames: T_world_camera is the optical frame (x right, y down, z forward) of the RGB camera.
/// Reentrant; cost O(returns of the frame) per sighting.

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include <scantling/core/pinhole_intrinsics.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/io/recording.hpp>

namespace scantling::localization {

struct DefectLiftingConfig {
    /// Largest time between the image and the depth frame used with it, seconds, > 0. The
    /// fused poses at both stamps carry the motion in between; a tank's structure does not
    /// move, so the limit is how far the VIO's relative error grows (mm in 0.1 s).
    double max_frame_offset_s = 0.1;
    /// Returns projecting within the sighting's radius of its centre are the support, but at
    /// least within this many pixels (a far defect covers few), > 0.
    double min_support_radius_px = 4.0;
    /// Fewer supporting returns: not lifted, >= 3 (a plane).
    std::size_t min_support_points = 10;
    /// Band of the support's planes (RANSAC inlier distance), metres, > 0: 4 σ of the range noise.
    double plane_inlier_m = 0.02;
    /// 1σ range noise of one return, metres, > 0 (the L515's ~5 mm at 2 m).
    double range_sigma_m = 0.005;
    /// 1σ of the detected centre in the image, pixels, > 0 (a tag detector's corners: ~0.5 px).
    double pixel_sigma_px = 0.5;
    /// A plate seen more obliquely than this is not used (the ray–plane intersection becomes
    /// ill-conditioned), degrees, in (0, 90).
    double max_incidence_deg = 80.0;
    /// The returns within this distance of the lifted centre are kept as the defect's local
    /// point cloud, metres, > 0.
    double local_cloud_radius_m = 0.3;

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "defects") const;
};

/// One view of one defect in the map frame.
struct DefectObservation {
    int defect_id = 0;
    std::size_t image = 0;
    double stamp_s = 0.0;
    Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
    double radius_px = 0.0;
    Eigen::Vector3d position_world = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal_world = Eigen::Vector3d::UnitZ();           ///< unit, towards the camera
    Eigen::Matrix3d measurement_covariance = Eigen::Matrix3d::Zero();  ///< depth and pixel
    Eigen::Matrix3d pose_covariance = Eigen::Matrix3d::Zero();         ///< the fused pose's share
    double range_m = 0.0;                                              ///< camera to centre
    std::size_t support_points = 0;
    PointCloud local_cloud_world;  ///< returns within local_cloud_radius_m

    Eigen::Matrix3d covariance() const { return measurement_covariance + pose_covariance; }
};

/// What a sighting is lifted with.
struct LiftingView {
    PinholeIntrinsics intrinsics;
    Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();  ///< at the image stamp
    Eigen::Vector3d p_world_body = Eigen::Vector3d::Zero();            ///< at the image stamp
    Matrix6d body_covariance = Matrix6d::Zero();  ///< FusedState::covariance at the image stamp
};

struct LiftResult {
    std::optional<DefectObservation> observation;
    std::string reason;  ///< why not, with the numbers ("" when lifted)
};

/// Lifts `sighting` with the depth returns `depth_world` (world frame, finite points).
LiftResult lift_defect(const io::DefectSighting& sighting, const LiftingView& view,
                       const PointCloud& depth_world, const DefectLiftingConfig& config = {});

}  // namespace scantling::localization
