#pragma once
/// @file
/// The corridor a magnetic crawler can drive along on a stiffened steel face, from the LiDAR
/// cloud it accumulated at a stop. The crawler stands on one face: the plate between two
/// stiffeners (a frame), a stiffener's top face (a flange about as wide as the robot) or a
/// stiffener's vertical side (its web). The corridor is the face's straight strip ahead,
/// bounded left and right by a WALL (a surface rising out of the face: a web seen from the
/// plate, the plate seen from a web) or an EDGE (the face ends: no returns, or returns far below
/// it, like the plate under a flange). The mission drives along its centre line.
///
/// Frame: the crawler's body frame at the stop (the cloud's frame): the face is z = 0, z its
/// outward normal, x forward, y left.
///
/// Method: the points with min_x_m <= x <= max_x_m and |y| <= max_half_width_m are binned on
/// an x-y grid (rows along x, columns along y; y = 0 is a column border) and each cell takes
/// the median height of its points: face (|median| < face_tolerance_m), wall (above), drop
/// (below) or empty. In each row, from the face cell nearest y = 0, the face is walked outwards
/// on both sides, bridging up to max_gap_cells empty cells; it ends at a wall cell (kWall), at
/// a drop cell or a longer gap (kEdge), or at max_half_width_m (no boundary on that side). The
/// boundary is then placed inside the cells from the points (a wall: the median y of the
/// points rising out of the face; an edge: the outermost face point), not on a cell side, which
/// would put it half a cell inside on average and make the corridor a cell narrower.
/// Two parallel lines y = a_left + b x and y = a_right + b x are fitted by least squares to
/// the rows with both boundaries; the row farthest from them is dropped while it is beyond
/// max_boundary_residual_m, and the fit repeated. Parallel, because stiffeners and flange
/// edges are: the slope gets both sides' data and the width is one number. The centre line is
/// midway.
///
/// Cost: O(n) for the binning, O(cells + points) for the medians, O(rows²) for the fit.
/// Thread-safety: a pure function of its arguments.
/// @note Deterministic, and independent of the order of the points: every per-cell quantity
/// is an order statistic, and the fit sums over rows in a fixed order.

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <string_view>

#include <scantling/core/point_cloud.hpp>

namespace scantling::perception {

/// The boundaries a row must have to be used (FaceCorridorConfig::bounds).
enum class CorridorBounds {
    kAny,          ///< a wall or an edge either side
    kWalls,        ///< a wall both sides: the plate between two stiffeners' webs
    kEdges,        ///< an edge both sides: a stiffener's top face
    kWallAndEdge,  ///< one of each, the same way round in every row used: a web's side
};

struct FaceCorridorConfig {
    double cell_size_m = 0.02;       ///< edge of the x-y grid's square cells, > 0
    double face_tolerance_m = 0.03;  ///< a cell whose median |z| is below this is the face, > 0
    double min_x_m = 0.15;           ///< nearest row used, cloud frame, finite, < max_x_m
    double max_x_m = 1.0;            ///< farthest row used, cloud frame, finite
    /// How far left and right of y = 0 a boundary is looked for, > cell_size_m.
    double max_half_width_m = 1.0;
    /// Empty cells bridged inside the face (a rosette's returns are sparse far out), >= 0.
    std::size_t max_gap_cells = 2;
    std::size_t min_rows = 10;  ///< rows with both boundaries (inliers) needed, > 0
    /// A row whose left or right boundary is farther than this from its fitted line is an
    /// outlier (a bolt, a bracket, a bead beside the wall), > 0.
    double max_boundary_residual_m = 0.03;
    /// The boundaries a row must have; other rows are skipped. Why: a task knows what bounds
    /// its face, and an "edge" where the sensor's view ends (no returns because it did not
    /// look) is no edge: measured between two stiffeners 0.65 m apart with the crawler 6 cm
    /// off the centre, the Mid-70's footprint rim ended 10 of 19 rows on one side, which bent
    /// the fitted lines by several degrees (the crawler 0.11 m off the centre line on average).
    /// A task sets it (mission/crawler_stack.hpp); not read from YAML.
    CorridorBounds bounds = CorridorBounds::kAny;

    /// Throws ConfigError naming "<prefix>.<field>", its value and what was expected.
    void validate(std::string_view prefix = "face_corridor") const;
};

/// What ends the face on one side.
enum class CorridorBound {
    kNone,  ///< not seen: the face runs on to max_half_width_m (or no corridor)
    kWall,  ///< a surface rising out of the face
    kEdge,  ///< the face ends: no returns, or returns below the face
};

/// The corridor, cloud frame. Valid when `found`.
struct FaceCorridor {
    bool found = false;
    /// "ok", or why not (e.g. "only 3 rows have both boundaries, expected >= 10").
    std::string status;
    /// On the centre line, z = 0, at the first (nearest) row used, m.
    Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();
    /// The centre line's direction: unit, z = 0, x > 0 (forward).
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
    double width_m = 0.0;  ///< distance between the two (parallel) boundary lines
    /// Signed distance of the left boundary line from the centre line, > 0 (left), m.
    double left_offset_m = 0.0;
    /// Signed distance of the right boundary line from the centre line, < 0 (right), m.
    double right_offset_m = 0.0;
    CorridorBound left_bound = CorridorBound::kNone;   ///< majority over the rows used
    CorridorBound right_bound = CorridorBound::kNone;  ///< majority over the rows used
    std::size_t rows_used = 0;                         ///< inlier rows of the fit
    double boundary_rms_m = 0.0;     ///< RMS of both lines' residuals over the rows used, m
    std::size_t points_dropped = 0;  ///< non-finite points skipped
};

/// The corridor of the face the crawler stands on (see the file comment). An empty cloud, or
/// too few rows with both boundaries, is an outcome (found = false, `status` says why), not a
/// contract violation; non-finite points are skipped and counted. Throws ConfigError for a bad
/// config. Only `cloud.points` is read.
FaceCorridor extract_face_corridor(const PointCloud& cloud, const FaceCorridorConfig& config = {});

/// "none", "wall" or "edge".
const char* to_string(CorridorBound b);
/// "any", "walls", "edges" or "wall and edge".
const char* to_string(CorridorBounds b);

}  // namespace scantling::perception
