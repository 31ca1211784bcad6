#pragma once
/// @file
/// How much of a planar inspection rectangle (a patch of hull or tank wall) a camera has seen,
/// and where the holes are: `make run`'s coverage line (issue 13 item 6) and the ROV hull
/// survey's "share of the hull area seen at the wanted resolution", whose holes go back to the
/// planner.
///
/// The rectangle is split into a grid of cells; each view (a camera pose) adds one to the view
/// count of every cell whose centre it sees. A cell centre p is seen from a camera at c when
///   - p projects inside the image (core/pinhole_intrinsics.hpp: camera frame x right, y down,
///     z forward along the optical axis; no distortion),
///   - c is on the front face, n·(c − p) > 0 with n = u × v, and the range |c − p| is at most
///     max_range_m,
///   - the incidence i, the angle between the ray p → c and n, is at most max_incidence_deg,
///   - when max_mm_per_px > 0, the image resolution on the wall,
///     1000 · range_m / (f · cos i) mm per pixel with f = min(fx, fy) (the on-axis pixel angle
///     1/f, which bounds the angle of every pixel), is at most max_mm_per_px,
///   - the caller's `occluded(c, p)` line-of-sight test, if given, returns false.
/// A cell is covered once at least min_views views have seen it.
///
/// Cost: add_view tests only the cells in the bounding box (in the rectangle's (u, v)) of the
/// disc where the range, incidence and resolution limits all hold, intersected with the
/// footprint of the image on the plane when the whole frustum meets it: O(cells seen), not
/// O(cells). result() is O(cells) (hole labelling).
/// Thread-safety: const members may run concurrently; add_view must not run alongside anything.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

#include <scantling/core/pinhole_intrinsics.hpp>

namespace scantling::perception {

/// Upper bound on the number of grid cells (~40 MB of view counts): a mistyped size or cell
/// is refused instead of allocating gigabytes.
inline constexpr double kMaxCoverageCells = 1e7;

struct CameraCoverageConfig {
    double cell_size_m = 0.05;        ///< largest side of a grid cell, > 0
    double max_range_m = 6.0;         ///< camera-to-cell distance at most this, > 0
    double max_incidence_deg = 60.0;  ///< ray-to-normal angle at most this, (0, 90]
    /// Coarsest image resolution on the wall that counts, mm per pixel, >= 0 (0: no limit).
    double max_mm_per_px = 0.0;
    int min_views = 1;  ///< views a cell needs to count as covered, >= 1

    /// Throws ConfigError naming "<prefix>.<field>" and what was expected.
    void validate(std::string_view prefix = "camera_coverage") const;
};

/// The rectangle {corner + a u + b v : a ∈ [0, width_m], b ∈ [0, height_m]}, world frame.
/// Its front face, the one that counts, is the side n = u × v points to. For a
/// planning::WallRectangle, u = right and v = up give n = the wall's outward normal.
struct InspectionRectangle {
    Eigen::Vector3d corner_world = Eigen::Vector3d::Zero();
    Eigen::Vector3d u_world = Eigen::Vector3d::UnitX();  ///< unit, along the width
    Eigen::Vector3d v_world = Eigen::Vector3d::UnitY();  ///< unit, along the height, ⊥ u
    double width_m = 1.0;                                ///< along u, > 0
    double height_m = 1.0;                               ///< along v, > 0

    /// Throws ConfigError naming "<prefix>.<field>": non-finite values, u or v not unit or not
    /// orthogonal (to 1e-6), sizes not finite > 0.
    void validate(std::string_view prefix = "inspection_rectangle") const;

    Eigen::Vector3d normal_world() const { return u_world.cross(v_world); }
};

/// A connected (4-neighbour) patch of uncovered cells.
struct CoverageHole {
    std::size_t cells = 0;
    double area_m2 = 0.0;
    Eigen::Vector3d centroid_world = Eigen::Vector3d::Zero();  ///< mean of its cell centres
    Eigen::Vector2d min_uv_m = Eigen::Vector2d::Zero();  ///< bounding box of its cells, (u, v)
    Eigen::Vector2d max_uv_m = Eigen::Vector2d::Zero();  ///< metres from the corner
};

struct CoverageResult {
    double covered_fraction = 0.0;  ///< covered_cells / cells (cells all have the same area)
    std::size_t cells = 0;
    std::size_t covered_cells = 0;
    double covered_area_m2 = 0.0;
    std::vector<CoverageHole> holes;  ///< largest first
};

/// `occluded(from_world, to_world)`: true when something hides `to` (a cell centre on the
/// rectangle) from `from` (the camera centre). A ray caster should ignore hits within a few
/// millimetres of `to`, which is on the wall itself.
using OcclusionTest = std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&)>;

class CameraCoverage {
  public:
    /// Throws ConfigError ("camera_coverage.*", "camera_coverage.rectangle.*",
    /// "camera_coverage.intrinsics.*") for a bad config, rectangle or intrinsics, or when the
    /// grid would exceed kMaxCoverageCells.
    CameraCoverage(const InspectionRectangle& rectangle, const PinholeIntrinsics& intrinsics,
                   const CameraCoverageConfig& config = {});

    /// Counts one view from the camera pose T_world_camera (camera frame as in the file
    /// comment). Throws InputError naming T_world_camera when it is not finite or its rotation
    /// is not orthonormal (to 1e-6); the counts are then unchanged.
    void add_view(const Eigen::Isometry3d& T_world_camera, const OcclusionTest& occluded = {});

    CoverageResult result() const;

    /// Grid: `columns()` cells along u, `rows()` along v, each cell_size_u_m() × cell_size_v_m()
    /// (the rectangle's sides split evenly, so each is at most config.cell_size_m).
    std::size_t columns() const { return columns_; }
    std::size_t rows() const { return rows_; }
    double cell_size_u_m() const { return cell_u_m_; }
    double cell_size_v_m() const { return cell_v_m_; }

    /// Views that saw each cell, row-major: index row · columns() + column, row 0 at the corner
    /// (v = 0). Saturates at UINT32_MAX.
    const std::vector<std::uint32_t>& view_counts() const { return view_counts_; }

    /// Centre of cell (column, row), world frame.
    Eigen::Vector3d cell_centre_world(std::size_t column, std::size_t row) const;

  private:
    struct View;
    struct CellRange;

    CellRange cells_to_test(const View& view) const;
    bool sees(const View& view, const Eigen::Vector3d& p_world,
              const OcclusionTest& occluded) const;
    Eigen::Vector2d cell_centre_uv(std::size_t column, std::size_t row) const;
    Eigen::Vector3d uv_to_world(const Eigen::Vector2d& uv_m) const;
    std::vector<CoverageHole> find_holes() const;

    InspectionRectangle rectangle_;
    PinholeIntrinsics intrinsics_;
    CameraCoverageConfig config_;
    std::size_t columns_ = 0;
    std::size_t rows_ = 0;
    double cell_u_m_ = 0.0;
    double cell_v_m_ = 0.0;
    double cos_max_incidence_ = 0.0;
    std::vector<std::uint32_t> view_counts_;
};

}  // namespace scantling::perception
