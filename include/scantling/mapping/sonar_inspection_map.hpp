#pragma once
/// @file
/// The ROV's sonar inspection map (SPEC §5; issue 14 item 4): the reliable sonar features of
/// every ping, already in the world frame, accumulated into cubic voxels. A voxel "exists" only
/// when enough reliable points fell into it; each existing voxel carries its mean, covariance and
/// an uncertainty for the operator. `coverage_of` grids a planar rectangle of the hull and finds
/// the holes (4-connected uncovered cells) the planner re-inspects.
///
/// Frame: world (metres). Voxel key = floor(p / voxel_size_m) per axis (mapping::CellKey).
/// Thread-safety: const members may run concurrently; add and clear need exclusive access.
/// @note Deterministic: voxels() and every coverage output are sorted (voxel key; cell rows),
/// independent of the hash table. Per-voxel statistics are running (Welford) sums, so the same
/// points in another order give the same counts and the same means up to rounding (~1e-15 m).

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <scantling/mapping/cell_hash.hpp>

namespace scantling::mapping {

struct SonarInspectionMapConfig {
    /// Voxel edge, metres, finite > 0. 0.2 m: a few sonar beams' footprint at the 1-1.3 m
    /// stand-off of SPEC §5, small against the hull's curvature (locally flat, SPEC §5).
    double voxel_size_m = 0.2;
    /// A voxel exists only with at least this many reliable points (SPEC §5), >= 3 (a plane's
    /// normal needs three points). 5: two pings' worth at the beam density of a 0.2 m voxel.
    std::size_t min_points_per_voxel = 5;
    /// Points whose 1σ exceeds this are rejected as unreliable (counted, never stored), metres,
    /// finite > 0. Half a voxel: a less certain point cannot be trusted to fall in its voxel.
    double max_point_sigma_m = 0.1;
    /// Memory bound: voxels stored (existing or still short of min_points_per_voxel), >= 1.
    /// A reliable point that would open a voxel beyond it is refused and counted. 2e5 voxels
    /// (~40 MB) hold 50 surveys of a 30 × 5 m hull section at 0.2 m.
    std::size_t max_voxels = 200'000;

    /// Throws ConfigError("<prefix>.voxel_size_m = -1, expected finite > 0").
    void validate(std::string_view prefix = "sonar_map") const;
};

/// What one add() did; added + rejected_unreliable + refused_memory = points given.
struct SonarAddResult {
    std::size_t added = 0;                ///< points accumulated into voxels
    std::size_t rejected_unreliable = 0;  ///< sigma_m > max_point_sigma_m, not counted
    std::size_t refused_memory = 0;       ///< would have opened a voxel beyond max_voxels
    std::size_t voxels_created = 0;       ///< voxels stored for the first time
};

/// One existing voxel, for reports and for coverage.
struct SonarVoxel {
    CellKey key;
    std::size_t num_points = 0;
    Eigen::Vector3d mean_world_m = Eigen::Vector3d::Zero();
    /// Sample covariance S of the points (divided by n − 1), m².
    Eigen::Matrix3d covariance_m2 = Eigen::Matrix3d::Zero();
    /// Covariance of the mean position, S / n (the standard error, squared), m².
    Eigen::Matrix3d mean_covariance_m2 = Eigen::Matrix3d::Zero();
    /// Unit eigenvector of S's smallest eigenvalue λ_min: the local hull normal (sign arbitrary).
    Eigen::Vector3d normal_world = Eigen::Vector3d::UnitZ();
    /// sqrt(λ_min): the points' scatter across the locally flat hull (≈ the range noise), m.
    double normal_spread_m = 0.0;
    double mean_point_sigma_m = 0.0;  ///< mean of the points' 1σ, m
    /// Uncertainty of the hull position in this voxel, along its normal, metres:
    ///   sqrt(λ_min / n + mean_point_sigma_m²).
    /// The first term is the standard error of the mean across the surface (the random scatter
    /// averages down with n); the point sigma is added undivided because its main part, the
    /// vehicle pose error, is shared by the points of a pass and does not average down.
    double uncertainty_m = 0.0;
    double first_stamp_s = 0.0;  ///< earliest stamp of the voxel's points
    double last_stamp_s = 0.0;   ///< latest stamp of the voxel's points
};

class SonarInspectionMap {
  public:
    /// Throws ConfigError for an invalid config.
    explicit SonarInspectionMap(const SonarInspectionMapConfig& config = {});

    const SonarInspectionMapConfig& config() const { return config_; }

    /// Accumulates one ping's features. `sigma_m[i]` is the 1σ of `points_world[i]`, metres.
    /// Throws InputError, before changing anything, naming the field ("points_world[3]",
    /// "sigma_m", "stamp_s") for a size mismatch, a non-finite point, sigma or stamp, a negative
    /// sigma or a point whose voxel index overflows int32. O(n) expected.
    SonarAddResult add(std::span<const Eigen::Vector3d> points_world,
                       std::span<const double> sigma_m, double stamp_s);

    /// Voxel of a finite point (floor per axis). Throws InputError as add().
    CellKey key_of(const Eigen::Vector3d& p_world) const;

    /// The existing voxels (>= min_points_per_voxel points), sorted by key. O(v log v).
    std::vector<SonarVoxel> voxels() const;

    std::size_t num_existing_voxels() const;                          ///< O(v)
    std::size_t num_stored_voxels() const { return voxels_.size(); }  ///< memory bound counts
    std::size_t num_points() const { return num_points_; }            ///< reliable points added

    /// Removes every voxel; keeps the configuration.
    void clear();

  private:
    struct Accumulator {
        std::size_t n = 0;
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        Eigen::Matrix3d m2 = Eigen::Matrix3d::Zero();  ///< Σ (p − mean)(p − mean)ᵀ (Welford)
        double sigma_sum_m = 0.0;
        double first_stamp_s = 0.0;
        double last_stamp_s = 0.0;
    };

    void check_input(std::span<const Eigen::Vector3d> points_world, std::span<const double> sigma_m,
                     double stamp_s) const;

    SonarInspectionMapConfig config_;
    std::unordered_map<CellKey, Accumulator, CellKeyHash> voxels_;
    std::size_t num_points_ = 0;
};

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
