#include <scantling/core/error.hpp>
#include <scantling/core/normals.hpp>

#include <cmath>
#include <span>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

namespace scantling {
namespace {

constexpr std::size_t kGrain = 512;  // points per task: amortises scheduling
// computeDirect (closed form) can lose accuracy on badly conditioned matrices; a smallest
// eigenvector whose residual |C v - lambda v| exceeds this fraction of the matrix scale (or whose
// norm is off by as much) is recomputed with the iterative solver.
constexpr double kDirectRelTol = 1e-10;
// A neighbourhood spread below 1 nm (trace of the covariance, m²) is a single repeated point.
constexpr double kDegenerateTraceM2 = 1e-18;

Eigen::Matrix3d neighbourhood_covariance(const std::vector<Eigen::Vector3d>& points,
                                         std::span<const std::size_t> neighbors) {
    // Two passes (mean first) so clouds far from the origin keep their precision.
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t j : neighbors) mean += points[j];
    mean /= static_cast<double>(neighbors.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (std::size_t j : neighbors) {
        const Eigen::Vector3d d = points[j] - mean;
        cov.noalias() += d * d.transpose();
    }
    return cov / static_cast<double>(neighbors.size());
}

bool is_accurate(const Eigen::Matrix3d& cov, double value, const Eigen::Vector3d& vector) {
    if (!vector.allFinite() || !std::isfinite(value)) return false;
    const double residual = (cov * vector - value * vector).cwiseAbs().maxCoeff();
    return residual <= kDirectRelTol * cov.cwiseAbs().maxCoeff() &&
           std::abs(vector.norm() - 1.0) <= kDirectRelTol;
}

/// Unit normal of the neighbourhood: the eigenvector of the covariance's smallest eigenvalue
/// (+z for a degenerate neighbourhood of one repeated point), not yet oriented.
Eigen::Vector3d plane_normal(const Eigen::Matrix3d& cov) {
    if (cov.trace() <= kDegenerateTraceM2) return Eigen::Vector3d::UnitZ();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(cov);
    if (is_accurate(cov, solver.eigenvalues()(0), solver.eigenvectors().col(0))) {
        return solver.eigenvectors().col(0);
    }
    solver.compute(cov);
    return solver.eigenvectors().col(0).normalized();
}

Eigen::Vector3d oriented(Eigen::Vector3d n, const Eigen::Vector3d& p,
                         const Eigen::Vector3d& viewpoint) {
    if (n.dot(viewpoint - p) < 0.0) n = -n;
    return n;
}

/// GICP regularisation: eigenvalues (epsilon, 1, 1) with the covariance's eigenvectors. As the
/// two unit eigenvalues span the plane, this equals I - (1 - epsilon) n n^T: only the normal is
/// needed, so near-repeated in-plane eigenvalues (ill-defined in-plane axes) do not matter.
Eigen::Matrix3d shaped_covariance(const Eigen::Matrix3d& cov, const Eigen::Vector3d& normal,
                                  const CovarianceConfig& config) {
    if (!config.regularize) return cov;
    return Eigen::Matrix3d::Identity() - (1.0 - config.epsilon) * normal * normal.transpose();
}

void check_input(const PointCloud& cloud, const KdTree& tree, std::string_view what) {
    check_usable(cloud, what);
    if (cloud.size() < 3) {
        throw InputError(
            fmt::format("{}: the cloud has {} points, expected >= 3", what, cloud.size()));
    }
    if (tree.size() != cloud.size()) {
        throw InputError(fmt::format("{}: the k-d tree holds {} points, the cloud {}", what,
                                     tree.size(), cloud.size()));
    }
}

/// Calls fn(i, covariance of point i's k nearest neighbours) for every point, in parallel.
/// Points are visited in the tree's leaf order (cache locality); each result still goes to its
/// own index, so the output does not depend on the split into tasks.
template <typename Fn>
void for_each_neighbourhood(const PointCloud& cloud, const KdTree& tree, int k,
                            const ParallelConfig& parallel, Fn&& fn) {
    const std::span<const std::size_t> order = tree.leaf_order();
    parallel_for(parallel, cloud.size(), kGrain, [&](std::size_t begin, std::size_t end) {
        std::vector<std::size_t> neighbors;
        std::vector<double> distances_sq_m2;
        for (std::size_t t = begin; t < end; ++t) {
            const std::size_t i = order[t];
            tree.knn(cloud.points[i], static_cast<std::size_t>(k), neighbors, distances_sq_m2);
            fn(i, neighbourhood_covariance(cloud.points, neighbors));
        }
    });
}

void check_num_neighbors(int num_neighbors, std::string_view prefix) {
    if (num_neighbors < 3) {
        throw ConfigError(
            fmt::format("{}.num_neighbors = {}, expected >= 3", prefix, num_neighbors));
    }
}

}  // namespace

void NormalEstimationConfig::validate(std::string_view prefix) const {
    check_num_neighbors(num_neighbors, prefix);
    if (!viewpoint.allFinite()) {
        throw ConfigError(fmt::format("{}.viewpoint = ({}, {}, {}), expected finite", prefix,
                                      viewpoint.x(), viewpoint.y(), viewpoint.z()));
    }
    parallel.validate(fmt::format("{}.parallel", prefix));
}

void CovarianceConfig::validate(std::string_view prefix) const {
    check_num_neighbors(num_neighbors, prefix);
    if (!(epsilon > 0.0 && epsilon <= 1.0)) {
        throw ConfigError(fmt::format("{}.epsilon = {}, expected in (0, 1]", prefix, epsilon));
    }
    parallel.validate(fmt::format("{}.parallel", prefix));
}

void estimate_normals(PointCloud& cloud, const NormalEstimationConfig& config) {
    config.validate();
    check_usable(cloud, "estimate_normals");
    estimate_normals(cloud, KdTree(cloud.points), config);
}

void estimate_normals(PointCloud& cloud, const KdTree& tree, const NormalEstimationConfig& config) {
    config.validate();
    check_input(cloud, tree, "estimate_normals");
    cloud.normals.resize(cloud.size());
    for_each_neighbourhood(cloud, tree, config.num_neighbors, config.parallel,
                           [&](std::size_t i, const Eigen::Matrix3d& cov) {
                               cloud.normals[i] =
                                   oriented(plane_normal(cov), cloud.points[i], config.viewpoint);
                           });
}

void estimate_covariances(PointCloud& cloud, const CovarianceConfig& config) {
    config.validate();
    check_usable(cloud, "estimate_covariances");
    estimate_covariances(cloud, KdTree(cloud.points), config);
}

void estimate_covariances(PointCloud& cloud, const KdTree& tree, const CovarianceConfig& config) {
    config.validate();
    check_input(cloud, tree, "estimate_covariances");
    cloud.covariances.resize(cloud.size());
    for_each_neighbourhood(
        cloud, tree, config.num_neighbors, config.parallel,
        [&](std::size_t i, const Eigen::Matrix3d& cov) {
            cloud.covariances[i] =
                config.regularize ? shaped_covariance(cov, plane_normal(cov), config) : cov;
        });
}

void estimate_normals_and_covariances(PointCloud& cloud, const NormalEstimationConfig& normals,
                                      const CovarianceConfig& covariances) {
    normals.validate();
    covariances.validate();
    if (covariances.num_neighbors != normals.num_neighbors) {
        throw ConfigError(fmt::format(
            "covariances.num_neighbors = {}, expected equal to normals.num_neighbors = {}",
            covariances.num_neighbors, normals.num_neighbors));
    }
    check_usable(cloud, "estimate_normals_and_covariances");
    const KdTree tree(cloud.points);
    check_input(cloud, tree, "estimate_normals_and_covariances");
    cloud.normals.resize(cloud.size());
    cloud.covariances.resize(cloud.size());
    for_each_neighbourhood(cloud, tree, normals.num_neighbors, normals.parallel,
                           [&](std::size_t i, const Eigen::Matrix3d& cov) {
                               const Eigen::Vector3d n = plane_normal(cov);
                               cloud.normals[i] = oriented(n, cloud.points[i], normals.viewpoint);
                               cloud.covariances[i] = shaped_covariance(cov, n, covariances);
                           });
}

}  // namespace scantling
