#pragma once
/// @file
/// Overlap score of a candidate pose (private to robust_registration.cpp): the share of a fixed
/// subsample of the source cloud that lands within a distance of the target cloud, as RANSAC's
/// fitness counts every point rather than the correspondences.

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/point_cloud.hpp>

namespace scantling::registration::detail {

class OverlapScorer {
  public:
    /// Scores against `target` (a k-d tree over its points is built here) with at most
    /// `max_points` source points, evenly spread over the source's index order.
    OverlapScorer(const PointCloud& source, const PointCloud& target, double distance_m,
                  std::size_t max_points);

    /// Share in [0, 1] of the scored source points p with a target point closer than the
    /// distance to T_target_source p (0 when either cloud is empty). Thread-safe.
    double score(const Eigen::Isometry3d& T_target_source) const;

  private:
    KdTree tree_;
    std::vector<Eigen::Vector3d> points_;
    double distance_sq_m2_ = 0.0;
};

}  // namespace scantling::registration::detail
