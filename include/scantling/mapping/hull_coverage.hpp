#pragma once
/// @file
/// Coverage of a planar hull rectangle by the sonar inspection map (SPEC §5; issue 14 item 4):
/// the rectangle gridded into cells of the map's voxel size, the covered share, and the holes
/// (4-connected components of uncovered cells, largest first) that the planner re-inspects
/// (planning/hole_reinspection.hpp).
///
/// Frame: world (metres); plane coordinates (u, v) along the rectangle's axes.
/// Thread-safety: pure functions. Deterministic: outputs in cell-row order.

#include <Eigen/Core>
#include <cstddef>
#include <string_view>
#include <vector>

#include <scantling/mapping/sonar_inspection_map.hpp>

namespace scantling::mapping {

/// A planar rectangle of the hull to cover: points origin + u·axis_u + v·axis_v with
/// u ∈ [0, extent_u_m], v ∈ [0, extent_v_m]. Its normal is axis_u × axis_v.
struct InspectedSurface {
    Eigen::Vector3d origin_world_m = Eigen::Vector3d::Zero();  ///< a corner, world, m
    Eigen::Vector3d axis_u_world = Eigen::Vector3d::UnitX();   ///< unit, in-plane
    Eigen::Vector3d axis_v_world = Eigen::Vector3d::UnitZ();   ///< unit, ⟂ axis_u
    double extent_u_m = 30.0;  ///< along axis_u, m, > 0 (SPEC §5: a ~30 × 5 m section)
    double extent_v_m = 5.0;   ///< along axis_v, m, > 0
    double tolerance_m = 0.3;  ///< largest distance of a voxel mean off the plane, m, >= 0

    /// Throws ConfigError naming "<prefix>.<field>": non-finite values, non-unit or
    /// non-orthogonal axes (1e-6), extents <= 0, a negative tolerance.
    void validate(std::string_view prefix = "surface") const;
};

struct HullCoverageConfig {
    /// Holes smaller than this are not listed (still uncovered and counted), m², finite >= 0.
    /// 0 lists every hole; 0.05 would drop single stray cells of a 0.2 m grid (0.04 m²).
    double min_hole_area_m2 = 0.0;
    /// Refuse a grid of more cells (a unit mistake), >= 1. 1e7 cells: a 600 × 600 m surface.
    std::size_t max_cells = 10'000'000;

    void validate(std::string_view prefix = "coverage") const;
};

/// A surface grid cell: column iu along axis_u, row iv along axis_v.
struct SurfaceCell {
    std::size_t iu = 0, iv = 0;
    friend bool operator==(const SurfaceCell&, const SurfaceCell&) = default;
};

/// A 4-connected component of uncovered cells.
struct CoverageHole {
    std::size_t num_cells = 0;
    double area_m2 = 0.0;                                        ///< cells clipped to the rectangle
    Eigen::Vector3d centroid_world_m = Eigen::Vector3d::Zero();  ///< area-weighted, on the plane
    Eigen::Vector2d centroid_plane_m = Eigen::Vector2d::Zero();  ///< (u, v)
    Eigen::Vector2d box_min_plane_m = Eigen::Vector2d::Zero();   ///< bounding box (u, v) corners
    Eigen::Vector2d box_max_plane_m = Eigen::Vector2d::Zero();
};

struct HullCoverage {
    double cell_size_m = 0.0;                      ///< the map's voxel size
    std::size_t num_cells_u = 0, num_cells_v = 0;  ///< the last column/row may be clipped
    double total_area_m2 = 0.0;
    double covered_area_m2 = 0.0;
    double covered_fraction = 0.0;             ///< covered / total area
    std::vector<SurfaceCell> uncovered_cells;  ///< row-major (iv, then iu)
    std::vector<CoverageHole> holes;           ///< by area, largest first (ties: row-major)
    std::size_t num_ignored_holes = 0;         ///< below min_hole_area_m2
};

/// Grids `surface` with cells of the map's voxel size (ceil(extent / size) per axis, the last
/// ones clipped). A cell is covered when the mean of an existing voxel lies within tolerance_m of
/// the plane and projects into it or within half a cell diagonal of its centre (on a surface not
/// aligned with the voxel grid the means do not fall one per cell; the disc closes those gaps, so
/// a hole narrower than about one voxel is not resolved). Holes are the 4-connected components
/// of uncovered cells. Throws ConfigError for a bad surface or config. O(v + cells).
HullCoverage coverage_of(const SonarInspectionMap& map, const InspectedSurface& surface,
                         const HullCoverageConfig& config = {});

}  // namespace scantling::mapping
