#pragma once
/// @file
/// A cylinder with a known axis direction (a column's wall: the axis is vertical, so gravity
/// from the IMU gives it) by RANSAC on the circle its points make in the plane perpendicular
/// to the axis, refined by geometric least squares (Gauss–Newton on the radial residual).
/// Used by the column structure detector: the centre and radius found are checked against the
/// column's known diameter before a registration is trusted.
///
/// A hypothesis is a circle through three projected points (or two points and their normals
/// when the cloud has normals); inliers are within distance_threshold_m of the circle and,
/// with normals, have a normal within normal_threshold_deg of the radial direction.
/// Deterministic: the same cloud, config and seed give the same cylinder.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include <scantling/core/point_cloud.hpp>

namespace scantling::perception {

struct CylinderRansacConfig {
    double distance_threshold_m = 0.03;  ///< inlier radial distance, > 0
    double normal_threshold_deg = 25.0;  ///< inlier normal vs radial direction, (0, 90]
    double min_radius_m = 0.3;           ///< hypotheses outside [min, max] are dropped, > 0
    double max_radius_m = 5.0;           ///< > min_radius_m
    std::size_t min_inliers = 200;       ///< fewer: no cylinder, >= 3
    int iterations = 300;                ///< hypotheses, >= 1
    std::uint64_t seed = 1;

    void validate(std::string_view prefix = "cylinder_ransac") const;
};

struct Cylinder {
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< unit, as given
    /// The axis point closest to the cloud's frame origin (its component along the axis is 0).
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double radius_m = 0.0;
    std::vector<std::size_t> inliers;  ///< indices into the input cloud, sorted
    double rms_m = 0.0;                ///< RMS radial residual of the inliers after the refit
    /// 3×3 covariance of (centre · e1, centre · e2, radius) from the refit's Gauss–Newton normal
    /// matrix and the residual variance, m², with e1 = axis.unitOrthogonal() (Eigen; `axis` above)
    /// and e2 = axis × e1: to have it in the cloud's frame, J = [e1 e2] for the centre block.
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

/// The best cylinder about `axis` (need not be unit; must be finite and non-zero), or none when
/// fewer than min_inliers points support one. Throws InputError for a non-finite cloud or axis
/// and ConfigError for a bad config.
std::optional<Cylinder> fit_cylinder(const PointCloud& cloud, const Eigen::Vector3d& axis,
                                     const CylinderRansacConfig& config = {});

}  // namespace scantling::perception
