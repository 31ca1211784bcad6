#include "hypothesis_scoring.hpp"

namespace scantling::registration::detail {
namespace {

/// Every (n / m)-th point, so the subsample covers the whole scan (index order follows the
/// sensor's sweep or the voxel grid, both spatially spread).
std::vector<Eigen::Vector3d> subsample(const std::vector<Eigen::Vector3d>& points,
                                       std::size_t max_points) {
    const std::size_t n = points.size();
    if (n <= max_points) return points;
    std::vector<Eigen::Vector3d> out(max_points);
    for (std::size_t i = 0; i < max_points; ++i) out[i] = points[i * n / max_points];
    return out;
}

}  // namespace

OverlapScorer::OverlapScorer(const PointCloud& source, const PointCloud& target, double distance_m,
                             std::size_t max_points)
    : tree_(target.points),
      points_(subsample(source.points, max_points)),
      distance_sq_m2_(distance_m * distance_m) {}

double OverlapScorer::score(const Eigen::Isometry3d& T_target_source) const {
    if (points_.empty() || tree_.empty()) return 0.0;
    std::size_t close = 0;
    for (const Eigen::Vector3d& p : points_) {
        const auto nn = tree_.nearest(T_target_source * p);
        if (nn->distance_sq_m2 < distance_sq_m2_) ++close;
    }
    return static_cast<double>(close) / static_cast<double>(points_.size());
}

}  // namespace scantling::registration::detail
