#pragma once
/// @file
/// LiODOM pose estimation (SPEC §2): edge points against lines of the local map.
///
/// For each edge p (sensor frame) moved into the world with the current pose, its k nearest
/// local-map points are accepted as a line when their covariance has one dominant eigenvalue;
/// the residual is the point-to-line distance d_e = |(p − N1) × (N1 − N2)| / |N1 − N2|, written
/// as the 3-vector (I − uuᵀ)(p − c) whose norm is d_e (c the neighbours' centroid, u the line
/// direction), weighted by ω = 1 − (r − r_min)/(r_max − r_min), r the sensor-frame range.
/// J = ½ Σ ρ(ω² d_e²) with ρ Huber is minimised over the 6-DoF pose by Gauss-Newton on
/// iteratively reweighted least squares, correspondences re-found at each outer iteration.
///
/// Own Gauss-Newton rather than Ceres: the problem is a dense 6×6 normal system per
/// iteration; Ceres' per-residual cost-function overhead dominates at this size
/// (docs/benchmarks.md, "LiODOM solver").
///
/// Degeneracy (SPEC §11): the 6×6 information JᵀWJ is eigen-decomposed; directions whose
/// eigenvalue falls below `degeneracy_ratio` × the largest are reported. With
/// `remap_degenerate` the update along them is removed (solution remapping), so that the pose
/// keeps its initial value there: right when the initial pose comes from another sensor (a
/// VIO prior on a smooth hull), wrong when it is only the constant-velocity model (a weakly
/// observed direction then follows the last velocity for ever: measured in docs/results.md).
#include <Eigen/Geometry>
#include <cstddef>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/odometry/edge_features.hpp>
#include <scantling/odometry/local_map.hpp>

namespace scantling::odometry {

struct EdgeRegistrationConfig {
    int num_neighbors = 5;                 ///< k of the line fit (LOAM: 5)
    double max_neighbor_distance_m = 1.0;  ///< farthest of the k neighbours, metres
    double line_eigen_ratio = 3.0;         ///< λ1 ≥ ratio · λ2 makes a line (A-LOAM: 3)
    /// Planar points: the k neighbours make a plane when the middle eigenvalue of their
    /// covariance is at least this times the smallest (> 1).
    double plane_eigen_ratio = 10.0;
    double huber_delta_m = 0.1;  ///< Huber threshold on ω·d_e, metres
    int max_iterations = 12;     ///< outer iterations (correspondences re-found)
    int inner_iterations = 2;    ///< Gauss-Newton steps per set of correspondences
    /// After the first outer iteration an edge's line (a planar point's plane) is fitted again
    /// only when the point has moved more than this since its last fit, metres (0 = refit
    /// every point every outer iteration, LOAM's way). Past the first iteration points move
    /// millimetres, their five neighbours rarely change, and the k-NN search is most of a
    /// sweep's time.
    double refit_distance_m = 0.0;
    int min_correspondences = 30;  ///< fewer: the sweep is not registered
    double convergence_translation_m = 1e-4;
    double convergence_rotation_rad = 1e-5;
    /// Directions of the information matrix with eigenvalue < ratio × the largest are
    /// degenerate (0 = never). Translation and rotation are compared after scaling rotation by
    /// the mean edge range, so that the ratio is unit-free.
    double degeneracy_ratio = 1e-3;
    /// Keep the initial pose along degenerate directions (set by LiODOM when a motion prior
    /// from another sensor gives the initial pose).
    bool remap_degenerate = false;
    /// Converged when the update along the well-observed directions is below the thresholds,
    /// whatever the degenerate ones do: along those the data hold the pose only weakly, so the
    /// update keeps wandering there and the test would otherwise run every sweep along a
    /// featureless hull to max_iterations. False: the whole update must fall below them.
    bool converge_on_observed = false;
    bool range_weighting = true;  ///< ω as in SPEC §2 (false: ω = 1)
    ParallelConfig parallel{};
    void validate(std::string_view prefix = "registration") const;
};

struct EdgeRegistrationResult {
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
    bool converged = false;   ///< the update fell below the thresholds
    bool registered = false;  ///< enough correspondences: the pose comes from the data
    int iterations = 0;
    std::size_t num_correspondences = 0;
    double rmse_m = 0.0;  ///< of the unweighted point-to-line distances of the inliers
    /// JᵀWJ at the solution, (ρ, ω) order as se3_exp (rotation in rad, not scaled). With
    /// `remap_degenerate`, without its degenerate directions: the pose there is the initial
    /// one, not a measurement (a filter fusing it must not count the prior twice).
    Matrix6d information = Matrix6d::Zero();
    /// Eigenvalues of the scaled information, ascending, and how many are degenerate.
    Vector6d eigenvalues = Vector6d::Zero();
    int num_degenerate = 0;
    /// Smallest / largest eigenvalue of the scaled information (0 = a null direction).
    double min_eigen_ratio = 0.0;
    /// Unit directions (columns, (ρ, ω) order, scaled frame) that were degenerate.
    Eigen::Matrix<double, 6, Eigen::Dynamic> degenerate_directions;
};

/// A line of the local map: its neighbours' centroid and unit direction.
struct EdgeLine {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
    bool valid = false;  ///< false: too few or too far neighbours, or not line-like
};

/// The `num_neighbors` nearest map points of `query` (world frame) as a line: all within
/// `max_neighbor_distance_m` and with λ1 ≥ `line_eigen_ratio` · λ2. `points` and `distances` are
/// the caller's scratch buffers (the hot path reuses them).
EdgeLine fit_edge_line(const LocalMap& map, const Eigen::Vector3d& query,
                       const EdgeRegistrationConfig& config, std::vector<Eigen::Vector3d>& points,
                       std::vector<double>& distances);

/// A plane of the local map: its neighbours' centroid and unit normal.
struct SurfacePatch {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    bool valid = false;  ///< false: too few or too far neighbours, or not plane-like
};

/// The `num_neighbors` nearest points of `query` in `map` as a plane: all within
/// `max_neighbor_distance_m` and with λ2 ≥ `plane_eigen_ratio` · λ3 (middle against smallest).
SurfacePatch fit_surface_patch(const LocalMap& map, const Eigen::Vector3d& query,
                               const EdgeRegistrationConfig& config,
                               std::vector<Eigen::Vector3d>& points,
                               std::vector<double>& distances);

/// ω = 1 − (r − r_min)/(r_max − r_min), clamped to [0, 1] (1 when `enabled` is false).
double edge_range_weight(double range_m, double min_range_m, double max_range_m, bool enabled);

/// Registers `edges` (sensor frame, with ranges) to `map` from `T_init` (world ← sensor).
/// Never throws on data: too few correspondences give registered = false and T_init back.
/// `min_range_m`/`max_range_m` are the range gate the edges were extracted with (for ω).
/// With `plane_map`, the planar points of `edges` add point-to-plane residuals against it.
EdgeRegistrationResult register_edges(const EdgeFeatures& edges, const LocalMap& map,
                                      const Eigen::Isometry3d& T_init, double min_range_m,
                                      double max_range_m, const EdgeRegistrationConfig& config = {},
                                      const LocalMap* plane_map = nullptr);

}  // namespace scantling::odometry
