#pragma once
/// @file
/// Planes in a depth frame by sequential RANSAC: the largest plane is found, its inliers are
/// removed, and the search repeats on the rest. The building block of the structure detectors
/// (web frames and walls in a ballast tank, floor and ceiling in a column).
///
/// A hypothesis is drawn from three points (or from one point and its normal when the cloud
/// has normals), scored by the points within distance_threshold_m whose normals (when present)
/// agree within normal_threshold_deg, and the best is refitted by least squares (PCA) on its
/// inliers. Deterministic: the same cloud, config and seed give the same planes.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include <scantling/core/point_cloud.hpp>

namespace scantling::perception {

struct PlaneRansacConfig {
    double distance_threshold_m = 0.02;  ///< inlier distance to the plane, > 0
    double normal_threshold_deg = 20.0;  ///< inlier normal agreement when normals exist, (0, 90]
    std::size_t min_inliers = 100;       ///< a plane with fewer inliers ends the search, >= 3
    std::size_t max_planes = 8;          ///< at most this many planes, >= 1
    int iterations = 200;                ///< hypotheses per plane, >= 1
    std::uint64_t seed = 1;

    /// Throws ConfigError naming "<prefix>.<field>" and what was expected.
    void validate(std::string_view prefix = "plane_ransac") const;
};

struct Plane {
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit; n·p + offset_m = 0 on the plane
    double offset_m = 0.0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< of the inliers
    std::vector<std::size_t> inliers;                    ///< indices into the input cloud, sorted
    double rms_m = 0.0;  ///< RMS point-to-plane distance of the inliers after the refit

    double signed_distance(const Eigen::Vector3d& p) const { return normal.dot(p) + offset_m; }
};

/// The planes found, largest first. An empty cloud gives none; throws InputError for a
/// non-finite or inconsistent cloud and ConfigError for a bad config.
std::vector<Plane> segment_planes(const PointCloud& cloud, const PlaneRansacConfig& config = {});

/// The plane with its normal (and offset) flipped, if needed, so that `viewpoint` is on its
/// positive side: the face a camera at `viewpoint` saw.
Plane facing(Plane plane, const Eigen::Vector3d& viewpoint);

/// The least-squares plane through points (PCA; the normal is the smallest-eigenvalue
/// eigenvector, oriented towards `towards` when given). Needs >= 3 non-collinear points:
/// throws InputError otherwise.
Plane fit_plane(const std::vector<Eigen::Vector3d>& points,
                const Eigen::Vector3d& towards = Eigen::Vector3d::Zero());

}  // namespace scantling::perception
