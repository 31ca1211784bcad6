#pragma once
/// @file Surface normals and local covariances from the k nearest neighbours of each point.
///
/// Both come from the same fit: the neighbourhood's 3×3 covariance (the point itself is one of
/// its k neighbours) and its eigen-decomposition. The normal is the eigenvector of the smallest
/// eigenvalue (the direction the neighbourhood is thinnest in).
///
/// Cost: one k-d tree build, O(n log n), plus n kNN queries of O(log n + k) each; the per-point
/// work is parallel. Thread-safety: the functions touch only the cloud they are given.
/// @note Deterministic: each point's result depends only on its own neighbourhood, so 1 and N
/// threads give bit-identical normals and covariances.

#include <Eigen/Core>
#include <string_view>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>

namespace scantling {

struct NormalEstimationConfig {
    /// Neighbours per fit, the point included, >= 3. Three points define a plane exactly but
    /// follow the range noise; the normal's angular error shrinks roughly as 1/sqrt(k), while a
    /// larger patch rounds off edges and corners. 20 is the usual GICP compromise (PCL's and
    /// fast_gicp's k_correspondences default) and spans about 0.3–1 m on a 64-beam sweep at 10–30 m
    /// range.
    int num_neighbors = 20;
    /// Normals are flipped to point towards this position, in the cloud's frame, metres. For a
    /// raw sweep in the sensor frame the default (the sensor origin) faces them to the sensor.
    Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero();
    ParallelConfig parallel;  ///< threads for the per-point fits

    /// Throws ConfigError naming the field ("normals.num_neighbors = 2, expected >= 3").
    void validate(std::string_view prefix = "normals") const;
};

struct CovarianceConfig {
    /// Neighbours per fit, the point included, >= 3 (see NormalEstimationConfig::num_neighbors).
    int num_neighbors = 20;
    /// GICP plane regularisation (Segal et al., RSS 2009): keep the eigenvectors, replace the
    /// eigenvalues by (epsilon, 1, 1), smallest first. The result is then unitless: it encodes
    /// the local plane, not the spread of the points. Off: the raw covariance in m².
    bool regularize = true;
    /// Relative thickness of the regularised plane, in (0, 1]; 1e-3 as in the GICP paper.
    double epsilon = 1e-3;
    ParallelConfig parallel;  ///< threads for the per-point fits

    /// Throws ConfigError naming the field ("covariances.epsilon = 0, expected in (0, 1]").
    void validate(std::string_view prefix = "covariances") const;
};

/// Sets `cloud.normals`: unit normals, oriented towards `config.viewpoint`. A neighbourhood of
/// identical points has no plane; its normal is +z (then oriented). With fewer points than
/// `num_neighbors`, every point uses the whole cloud.
/// Throws InputError for fewer than 3 points or a non-finite / inconsistent cloud.
void estimate_normals(PointCloud& cloud, const NormalEstimationConfig& config = {});

/// Same, reusing a tree built over exactly `cloud.points` (InputError if the sizes differ).
void estimate_normals(PointCloud& cloud, const KdTree& tree,
                      const NormalEstimationConfig& config = {});

/// Sets `cloud.covariances` (see CovarianceConfig::regularize for their meaning and unit). A
/// neighbourhood of one repeated point is regularised as the plane z = const.
/// Throws InputError for fewer than 3 points or a non-finite / inconsistent cloud.
void estimate_covariances(PointCloud& cloud, const CovarianceConfig& config = {});

/// Same, reusing a tree built over exactly `cloud.points` (InputError if the sizes differ).
void estimate_covariances(PointCloud& cloud, const KdTree& tree,
                          const CovarianceConfig& config = {});

/// Sets both from one kNN pass (what GICP-style registration needs). Neighbourhood size and
/// threads come from `normals`; `covariances.num_neighbors` must be equal (ConfigError if not).
void estimate_normals_and_covariances(PointCloud& cloud, const NormalEstimationConfig& normals,
                                      const CovarianceConfig& covariances);

}  // namespace scantling
