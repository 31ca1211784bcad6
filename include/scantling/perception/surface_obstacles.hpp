#pragma once
/// @file
/// Stop-and-map obstacle perception for the magnetic crawler (SPEC §6): the LiDAR points
/// accumulated while the robot stands still are voxelised, a second-degree surface is fitted
/// by RANSAC, and every point is judged by its signed distance to it: on the surface = free,
/// above = positive obstacle (weld bead, bolt, bracket), below = negative obstacle (a hole seen
/// through, a plate edge beyond which the surface falls away). The labels are then rasterised
/// on a grid in the body x-y plane and the obstacle cells grouped into clusters.
///
/// Frame: the crawler's body frame at the stop, origin at the robot on the surface, z the
/// surface normal into free space, x forward. Near the robot the surface is then a height field.
///
/// The model is the quadric  z = a x² + b xy + c y² + d x + e y + f + g z²,  i.e. the
/// height-field quadric of the SPEC plus one term, g z². Why the extra term: a height-field
/// quadric is only the second-order expansion of a curved wall, and on a Ø 5 m tank it is off by
/// x⁴/(8R³) = 20 cm at 2 m, so most of the view would read as obstacles. With g z² every
/// cylinder or sphere tangent to the x-y plane is exact (x² + (z − R)² = R² is
/// z = x²/(2R) + z²/(2R)), and a plate gives g ≈ 0. Hypotheses are still drawn as the SPEC's
/// 6-point height field (g = 0, exact 6×6 solve): a minimal 7-point sample cannot fix g on a
/// flat plate, where z² is noise. The winner is refitted on its inliers by least squares with
/// g free under a ridge that holds g at 0 unless the inliers span several centimetres of height
/// (so that on a plate the quadric's second sheet, z ≈ 1/g, stays far out of view instead of
/// passing through a pipe above it), and collect → refit repeats until the inliers stop
/// changing: the inner, nearly quadric, part of the wall fixes g, and the refit reaches the rest.
/// Not modelled: xz and yz terms, so a wall that is both curved and tilted against z is only
/// approximated (to second order at the robot, as the SPEC's height field would be).
///
/// Distances are the first-order (Sampson) distance F/|∇F| to F(p) = 0, which for a surface
/// tilted by θ is the distance along its normal, not the vertical one (1/cos θ larger).
///
/// An obstacle point needs min_obstacle_support points of its sign in the 3×3 cells around it,
/// else it is uncertain: 3 mm noise puts ~1e-4 of a plate's points past a 12 mm threshold, alone.
///
/// Negative obstacles are (1) points more than obstacle_threshold_m below the surface, and
/// (2) when `enclosed_unknown_is_negative`, regions of at least min_enclosed_unknown_cells grid
/// cells without any point that are enclosed by observed cells (not 4-connected to the grid's
/// border): a hole whose far side returns nothing in range. Occlusion shadows that end inside
/// the observed area are marked too; for a crawler that is the safe side of the error.
///
/// Cost: O(n log n) for the voxel grid, O(iterations · 2000) for the hypotheses (they are
/// ranked on a fixed subsample), O(n) per refit round, O(cells) for the grid.
/// Thread-safety: a pure function of its arguments.
/// @note Deterministic: the same cloud, config and seed give the same result for any
/// `parallel.num_threads` (only the voxel grid runs in parallel, and it is order-independent).

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>

namespace scantling::perception {

struct SurfaceObstaclesConfig {
    double voxel_size_m = 0.01;  ///< voxel grid filter on the accumulated cloud (SPEC §6), > 0
    /// Instead of the 3D voxel grid, one point per x-y column of voxel_size_m at the median
    /// height of its points. Why: a 3D grid cuts a column of noisy returns into voxels stacked
    /// above and below the surface, each with its own centroid, so a range noise comparable
    /// to the voxel (the Mid-70's 2 cm at steep incidence) makes obstacles of a third of the
    /// voxels under 0.75 m (measured on the simulated crawler, docs/results.md); the median
    /// of the column is the surface (or the obstacle's top) to σ/√n. Vertical faces collapse to
    /// their column's median: the grid labels heights, which is what a crawler drives on.
    bool column_median = false;
    double max_range_m = 3.0;             ///< points farther in x-y from the robot are dropped, > 0
    double inlier_threshold_m = 0.01;     ///< |distance| to the surface of a free point, > 0
    double obstacle_threshold_m = 0.012;  ///< |distance| of an obstacle, >= inlier threshold;
                                          ///< points in between are "uncertain"
    int iterations = 500;                 ///< RANSAC hypotheses, >= 1
    std::uint64_t seed = 1;
    std::size_t min_points =
        100;  ///< fewer voxelised points (or surface inliers): no surface, >= 6
    /// Tightest radius of curvature the surface may have: hypotheses curving more are dropped
    /// (they pass through obstacles), > 0.
    double min_radius_m = 1.0;
    double max_tilt_deg = 30.0;  ///< hypotheses steeper than this at the robot are dropped, (0, 90)
    double cell_size_m = 0.02;   ///< result grid cell edge, > 0
    /// Obstacle points of the same sign needed in the 3×3 cells around an obstacle point (itself
    /// included); fewer: it is relabelled uncertain, as a lone noise spike would be. 1 = off.
    std::size_t min_obstacle_support = 2;
    /// Smallest obstacle cluster, cells, >= 1 (1 = off): a smaller one is relabelled uncertain
    /// in the grid. A range noise of centimetres (the Mid-70's 2 cm) leaves single cells past
    /// the threshold where the support rule lets pairs through; a 3 cm bolt covers 2–4 cells.
    std::size_t min_cluster_cells = 1;
    /// Obstacle cells this close (cells, Chebyshev) to a cell without points are uncertain,
    /// >= 0 (0 = off). Why: range noise moves a return along its ray, so where the observed
    /// area ends (the field of view's rim, the range cut, a shadow) the columns get the returns
    /// shifted one way only: above the surface at the near rim (shorter ranges come back
    /// towards the sensor), below it at the far rim. With the Mid-70's 2 cm that was a 20-cell
    /// "obstacle" 0.23 m ahead of the crawler at every stop (docs/results.md).
    int rim_cells = 0;
    bool enclosed_unknown_is_negative = true;  ///< see the file comment
    std::size_t min_enclosed_unknown_cells =
        25;                   ///< smallest such region (25 = 1 dm² at 2 cm), >= 1
    ParallelConfig parallel;  ///< threads of the voxel grid filter

    /// Throws ConfigError naming "<prefix>.<field>" and what was expected.
    void validate(std::string_view prefix = "surface_obstacles") const;
};

/// F(p) = xx x² + xy x y + yy y² + x_slope x + y_slope y + offset_m + zz z² − z = 0, body frame.
struct QuadricSurface {
    double xx = 0.0;        ///< a, 1/m; a cylinder of radius R across x has ±1/(2R)
    double xy = 0.0;        ///< b, 1/m
    double yy = 0.0;        ///< c, 1/m
    double x_slope = 0.0;   ///< d, dimensionless (tan of the tilt about y)
    double y_slope = 0.0;   ///< e, dimensionless
    double offset_m = 0.0;  ///< f, the surface's height under the robot
    double zz = 0.0;        ///< g, 1/m

    /// F(p), m: negative above the surface (free side), positive below.
    double residual(const Eigen::Vector3d& p) const;
    /// ∇F(p), dimensionless.
    Eigen::Vector3d gradient(const Eigen::Vector3d& p) const;
    /// −F/|∇F|: signed distance to the surface to first order, > 0 on the free side, m.
    double signed_distance_m(const Eigen::Vector3d& p) const;
    /// The surface's z under (x, y): z = poly(x, y) + g z², by fixed point (|g z| ≪ 1 near the
    /// robot: three rounds are exact to micrometres), m.
    double height_m(const Eigen::Vector2d& xy) const;
};

/// What a point or a grid cell is.
enum class SurfaceLabel : std::uint8_t {
    kFree,       ///< on the surface: the crawler may drive there
    kPositive,   ///< above the surface by more than obstacle_threshold_m
    kNegative,   ///< below the surface by more than obstacle_threshold_m (or enclosed unknown)
    kUncertain,  ///< between the inlier and the obstacle thresholds (or no surface was found)
    kUnknown,    ///< grid cells only: no point
};

enum class SurfaceStatus {
    kOk,
    kTooFewPoints,  ///< fewer than min_points voxelised points in range (an empty cloud too)
    kNoSurface,     ///< no hypothesis, or the best surface has fewer than min_points inliers
};

/// Square grid centred on the robot, covering [−max_range_m, max_range_m]² (rounded up to whole
/// cells); cell (ix, iy) spans origin_xy_m + cell_size_m · [ix, ix + 1] × [iy, iy + 1].
struct SurfaceGrid {
    double cell_size_m = 0.0;
    int cells_per_side = 0;
    Eigen::Vector2d origin_xy_m = Eigen::Vector2d::Zero();  ///< the grid's lower corner
    std::vector<SurfaceLabel> cells;                        ///< index iy · cells_per_side + ix

    /// Label of the cell holding (x, y), kUnknown outside the grid.
    SurfaceLabel label_at(const Eigen::Vector2d& p_body_xy_m) const;
    Eigen::Vector2d cell_centre(int ix, int iy) const;
};

/// An 8-connected component of positive (or of negative) grid cells.
struct ObstacleCluster {
    SurfaceLabel label = SurfaceLabel::kPositive;             ///< kPositive or kNegative
    Eigen::Vector2d centroid_xy_m = Eigen::Vector2d::Zero();  ///< mean of the cell centres
    Eigen::Vector2d min_xy_m = Eigen::Vector2d::Zero();       ///< extent: outer cell corners
    Eigen::Vector2d max_xy_m = Eigen::Vector2d::Zero();
    std::size_t num_cells = 0;
};

struct SurfaceObstacles {
    SurfaceStatus status = SurfaceStatus::kTooFewPoints;
    QuadricSurface surface;            ///< valid when status == kOk
    PointCloud points;                 ///< the voxelised points in range (positions only)
    std::vector<SurfaceLabel> labels;  ///< per point of `points` (kUncertain without a surface)
    std::vector<double> distances_m;   ///< per point: signed distance (0 without a surface)
    std::size_t num_inliers = 0;       ///< points within inlier_threshold_m of the surface
    double inlier_rms_m = 0.0;         ///< RMS distance of those inliers
    std::size_t num_non_finite = 0;    ///< input points skipped as NaN / infinite
    std::size_t num_out_of_range = 0;  ///< input points beyond max_range_m
    SurfaceGrid grid;
    std::vector<ObstacleCluster> clusters;  ///< positive ones first, each in grid scan order
};

/// Where the LiDAR should have seen the surface (optional input of detect_surface_obstacles):
/// the cells of the fitted surface (z = 0 without one) inside its cone, less a margin, and
/// within max_range_m of it. Such a cell without a return, and not in the shadow of a positive
/// cell (seen from the sensor's foot), is negative: the surface is not there (a hole, a plate's
/// edge). Why: a hole in a plate with nothing beneath it, or the plate's end, returns nothing,
/// and the enclosed-unknown rule only sees the holes that observed cells surround on all sides;
/// measured on the crawler's plate, it found 0 of 21 edges and 0 of 1 holes (docs/results.md).
struct ExpectedView {
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();  ///< x the boresight
    double half_fov_rad = 0.0;  ///< cone half angle about x, (0, π/2]
    /// Off the cone's rim, where the noise moves returns out of their cells (rim_cells), rad.
    double margin_rad = 0.05;
    /// Farther cells are not expected: a rosette's returns thin out with range, > 0.
    double max_range_m = 1.5;
};

/// Labels the accumulated stop cloud (body frame; see the file comment). An empty cloud, or one
/// with only non-finite points, gives status kTooFewPoints (a sensor that returned nothing is
/// an outcome, not a contract violation); non-finite points are skipped and counted (LiDAR
/// drivers mark dropouts with NaN). Throws ConfigError for a bad config and InputError for a
/// cloud whose optional fields do not match its points.
SurfaceObstacles detect_surface_obstacles(const PointCloud& cloud_body,
                                          const SurfaceObstaclesConfig& config = {},
                                          const std::optional<ExpectedView>& view = std::nullopt);

}  // namespace scantling::perception
