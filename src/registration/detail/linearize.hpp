#pragma once
/// @file
/// The ICP family's one pass over the source: correspondences, residuals, robust weights and
/// the normal equations, summed deterministically (private to the registration module).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/parallel.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/icp.hpp>

namespace scantling::registration::detail {

/// Everything one linearisation gives: the normal equations and the figures the result needs.
struct LinearSystem {
    Matrix6d H = Matrix6d::Zero();                    ///< Σ w Jᵀ Ω J
    Vector6d b = Vector6d::Zero();                    ///< Σ w Jᵀ Ω r
    double cost = 0.0;                                ///< Σ w rᵀ Ω r
    double distance_sq_sum_m2 = 0.0;                  ///< Σ |q − t|² over the correspondences
    Eigen::Vector3d q_sum = Eigen::Vector3d::Zero();  ///< Σ q (for the centroid)
    double q_norm_sq_sum = 0.0;                       ///< Σ |q|² (for the RMS radius)
    std::size_t count = 0;                            ///< correspondences

    LinearSystem& operator+=(const LinearSystem& other);
};

/// The inputs of a registration, with normals/covariances already present where needed.
struct Problem {
    const std::vector<Eigen::Vector3d>* source_points = nullptr;
    const std::vector<Eigen::Matrix3d>* source_covariances = nullptr;  ///< GICP only
    const KdTree* target_tree = nullptr;
    const std::vector<Eigen::Vector3d>* target_normals = nullptr;      ///< point-to-plane only
    const std::vector<Eigen::Matrix3d>* target_covariances = nullptr;  ///< GICP only
    IcpMethod method = IcpMethod::kPointToPlane;
    double max_correspondence_distance_m = 1.0;
    RobustKernel kernel = RobustKernel::kNone;
    double kernel_scale_m = 1.0;
    ParallelConfig parallel;
};

/// Linearises the cost at `T_target_source`. Bit-identical for any thread count.
LinearSystem linearize(const Problem& problem, const Eigen::Isometry3d& T_target_source);

}  // namespace scantling::registration::detail
