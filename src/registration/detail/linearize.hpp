#pragma once
/// @file
/// The ICP family's one pass over the source: correspondences, residuals, robust weights and
/// the normal equations, summed deterministically (private to the registration module).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/parallel.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/icp.hpp>

namespace scantling::registration::detail {

/// Columns span the free directions of the twist (rho, omega): identity for full 6-DoF ICP.
using DofBasis = Eigen::Matrix<double, 6, Eigen::Dynamic>;

/// One source point's score g = w Jᵀ Ω r (its term of b), its sensitivity A = w Jᵀ Ω (how g
/// moves when the target point moves: g changes by −A δ for a shift δ; point-to-plane: the
/// first column only, δ along the normal) and the cell of its point q.
struct CellScore {
    std::array<std::int64_t, 3> cell{};
    Vector6d score = Vector6d::Zero();
    Eigen::Matrix<double, 6, 3> sensitivity = Eigen::Matrix<double, 6, 3>::Zero();
    bool valid = false;  ///< false: the point had no correspondence
};

/// Scores requested from linearize, for IcpCovariance::kClusteredSandwich.
struct ScoreRecord {
    double cell_size_m = 1.0;       ///< cell edge, metres
    std::vector<CellScore> scores;  ///< one per source point, in source order (filled)
};

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
    /// Outward target normals for IcpConfig::back_faces; nullptr = plain nearest neighbours.
    const std::vector<Eigen::Vector3d>* front_normals = nullptr;
    BackFaces back_faces = BackFaces::kPreferFront;  ///< with front_normals (back_faces.hpp)
};

/// Linearises the cost at `T_target_source`; with `record` also writes every source point's
/// score and cell into it (resized to the source). Bit-identical for any thread count.
LinearSystem linearize(const Problem& problem, const Eigen::Isometry3d& T_target_source,
                       ScoreRecord* record = nullptr);

}  // namespace scantling::registration::detail
