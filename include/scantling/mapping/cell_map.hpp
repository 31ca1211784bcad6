#pragma once
/// @file
/// LiODOM's global map M_i = {H_i, C_i} (SPEC §2, D4.2 §II.2): space cut into cuboid cells of
/// s_xy × s_xy × s_z, a hash table from cell index to the points inside the cell, per-sweep
/// insertion of world points with voxel thinning of the cells that the sweep modified, and
/// retrieval of the cells around a position (the adaptive local map).
///
/// Storage: each cell keeps its points as float offsets from its centre, so the rounding error
/// is about s · 6e-8 m (under 1 µm for 4 m cells) wherever the cell is, instead of growing with
/// the distance from the origin as world coordinates in float would (0.5 mm at 8 km).
///
/// Thread-safety: const members may run concurrently; insert and clear need exclusive access.
/// @note Deterministic: every output (gather_near, all_points, thinning) is ordered by cell key
/// (lexicographic x, y, z) and, inside a cell, by insertion order or voxel index. It does not
/// depend on the hash kind, the bucket count or the table's iteration order.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <scantling/mapping/cell_hash.hpp>

namespace scantling::mapping {

struct CellMapConfig {
    /// Cell edge along x and y, metres, finite > 0. The source gives no number in the paper; its
    /// public code uses 30 m, which makes the local map a few huge cells. 4 m keeps the local
    /// map's boundary within half a cell (2 m) of the requested radius while a 50 m radius
    /// still probes only ~8k cells (measured: docs/benchmarks.md, "Hashed cell map").
    double cell_size_xy_m = 4.0;
    /// Cell edge along z, metres, finite > 0. Cubic cells by default: a drone climbing a hull
    /// side moves vertically as much as horizontally.
    double cell_size_z_m = 4.0;
    /// Point budget of a cell, >= 1. A cell modified by an insert that then holds more points is
    /// voxel-thinned. 500 leaves room for a full planar face of the cell at 0.2 m (400 voxels)
    /// or 15-25 edge lines before the thinning voxel has to grow.
    std::size_t max_points_per_cell = 500;
    /// Edge of the thinning voxel grid, metres, finite, > 0 and <= both cell sizes, with at
    /// most 2²⁰ voxels per cell edge. 0.2 m is LOAM's leaf size for its edge map (the source's
    /// code uses 0.4 m, too coarse for edges 1-10 m from a hull). When a cell still exceeds the
    /// budget at this voxel, the voxel is doubled until it fits (see CellMap::insert).
    double thinning_voxel_m = 0.2;
    /// Table hash. kMixed: on the real and simulated maps the source's xor hash leaves most
    /// cells sharing a hash value with others (docs/benchmarks.md, "Hashed cell map").
    CellHashKind hash = CellHashKind::kMixed;

    /// Throws ConfigError("<prefix>.cell_size_xy_m = -1, expected finite > 0").
    void validate(std::string_view prefix = "cell_map") const;
};

/// What one insert did.
struct InsertStats {
    std::size_t points_added = 0;          ///< points stored (before thinning)
    std::size_t non_finite_skipped = 0;    ///< NaN/inf points, skipped
    std::size_t out_of_range_skipped = 0;  ///< points whose cell index overflows int32, skipped
    std::size_t cells_created = 0;
    std::size_t cells_modified = 0;  ///< cells that received points (including created ones)
    std::size_t cells_thinned = 0;   ///< modified cells over the budget, voxel-thinned
};

class CellMap {
  public:
    /// Throws ConfigError for an invalid config.
    explicit CellMap(const CellMapConfig& config = {});

    const CellMapConfig& config() const { return config_; }

    /// Index of the cell holding `point`: floor(x / s_xy), floor(y / s_xy), floor(z / s_z)
    /// (floor, so -0.1 m is in cell -1). Throws InputError for a non-finite point or an index
    /// outside int32.
    CellKey key_of(const Eigen::Vector3d& point) const;

    /// Centre of a cell, SPEC §2: (⌊x/s_xy⌋ s_xy + s_xy/2, ⌊y/s_xy⌋ s_xy + s_xy/2,
    /// ⌊z/s_z⌋ s_z + s_z/2), i.e. (key + 1/2) · size per axis.
    Eigen::Vector3d cell_center(const CellKey& key) const;

    /// Adds world points (one sweep's edges, transformed with the optimised pose), then
    /// voxel-thins only the cells this call modified that exceed `max_points_per_cell`.
    /// Non-finite points and points whose cell index overflows int32 are skipped and counted.
    /// Thinning replaces a cell's points by one centroid per occupied voxel of a grid anchored
    /// at the cell's corner (voxels never straddle cells), ordered by voxel index; if that still
    /// exceeds the budget the voxel edge doubles until it fits (at the latest when one voxel
    /// covers the cell), so every cell ends within its budget. O(n) expected plus
    /// O(m) per thinned cell of m points and voxel size tried.
    InsertStats insert(std::span<const Eigen::Vector3d> world_points);

    /// Appends to `out` the points of every existing cell whose centre lies within `radius_m`
    /// (Euclidean, inclusive) of the centre of the cell containing `position`: a ball of cells
    /// that does not depend on where `position` is inside its cell. Ordered by cell key
    /// (lexicographic x, y, z), insertion/voxel order inside a cell. Cost: probes the ball's keys,
    /// about (4/3)π r³ / (s_xy² s_z) lookups, or, when the ball's bounding box holds more keys
    /// than the map has cells, scans the table and sorts the cells found.
    /// Throws InputError for a non-finite position or a negative or non-finite radius.
    void gather_near(const Eigen::Vector3d& position, double radius_m,
                     std::vector<Eigen::Vector3d>& out) const;

    /// Appends every point of the map to `out`, ordered as gather_near. O(n + c log c).
    void all_points(std::vector<Eigen::Vector3d>& out) const;

    /// Every existing cell key, sorted. O(c log c).
    std::vector<CellKey> keys() const;

    bool contains(const CellKey& key) const { return cells_.find(key) != cells_.end(); }
    /// Points stored in a cell; 0 when the cell does not exist.
    std::size_t num_points_in(const CellKey& key) const;

    std::size_t num_cells() const { return cells_.size(); }
    std::size_t num_points() const { return num_points_; }

    /// Estimated heap + object bytes: bucket array, one table node per cell (next pointer,
    /// key, cell record) and each cell's point buffer at its capacity, each heap block counted
    /// with glibc malloc's 8-byte header and 16-byte rounding.
    std::size_t memory_bytes() const;

    /// Hash-value spread of the existing keys under the table's hash and the table's bucket
    /// occupancy. O(c log c + buckets).
    HashStats hash_stats() const;

    /// Pre-sizes the table's bucket array for `num_cells` cells (results do not change).
    void reserve(std::size_t num_cells) { cells_.reserve(num_cells); }

    /// Removes every cell and point; keeps the configuration.
    void clear();

  private:
    struct Cell {
        std::vector<Eigen::Vector3f> offsets;  ///< point - cell centre, metres
        std::uint64_t touched_in = 0;          ///< insert call that last modified the cell
    };
    using Table = std::unordered_map<CellKey, Cell, CellKeyHash>;

    Cell& cell_for(const CellKey& key, InsertStats& stats);
    void thin(Cell& cell) const;
    void append_cell(const CellKey& key, const Cell& cell, std::vector<Eigen::Vector3d>& out) const;

    CellMapConfig config_;
    Table cells_;
    std::size_t num_points_ = 0;
    std::uint64_t insert_count_ = 0;
};

}  // namespace scantling::mapping
