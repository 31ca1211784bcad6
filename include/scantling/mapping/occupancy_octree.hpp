#pragma once
/// @file
/// The exploration's occupancy map (SPEC §8; issue 16 item 1): an OctoMap `OcTree` (Debian's
/// liboctomap, a private dependency: no OctoMap type appears here) fed with depth frames at the
/// fused pose. Every point is a ray from the sensor: the voxels it crosses are updated as free,
/// the voxel it ends in as occupied (log-odds, clamped). A voxel never reached is unknown.
///
/// Frame: world (metres); each frame's points arrive in the sensor frame with T_world_sensor.
/// Voxel edge = resolution_m; the map spans ±32768 · resolution_m per axis (±3.3 km at 0.1 m).
/// Thread-safety: const members may run concurrently; insert_depth_frame needs exclusive access.
/// @note Deterministic: the same frames in the same order give the same tree, bit for bit
/// (OctoMap is built without OpenMP here, and updates are applied in a fixed order per frame).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/point_cloud.hpp>

namespace scantling::mapping {

struct OccupancyOctreeConfig {
    /// Voxel edge, metres, finite > 0 (SPEC §8 reports 0.1 and 0.05 m).
    double resolution_m = 0.1;
    /// The depth camera's maximum depth, metres, finite > 0 (SPEC §8: 5 m). A point farther
    /// away (or a longer ray) is cut to this length and clears free space only: nothing was
    /// seen within reach along it.
    double max_range_m = 5.0;
    /// P(occupied | a return ends in the voxel), in (0.5, 1). OctoMap's default.
    double prob_hit = 0.7;
    /// P(occupied | a ray crosses the voxel), in (0, 0.5). OctoMap's default.
    double prob_miss = 0.4;
    /// Lower clamp of the occupancy probability, in (0, occupied_threshold). OctoMap's default
    /// (0.1192): a voxel seen free many times still turns occupied after a few hits.
    double clamp_min = 0.12;
    /// Upper clamp of the occupancy probability, in (occupied_threshold, 1). OctoMap's default.
    double clamp_max = 0.97;
    /// A known voxel with P(occupied) >= this is occupied, else free; in (clamp_min, clamp_max).
    double occupied_threshold = 0.5;
    /// Cast one ray per end voxel rather than per point (OctoMap's `discretize`). Why: a depth
    /// frame puts many points in each voxel (320 × 240 over 70° at 3 m: ~ 8 × 8 points on a
    /// 0.1 m voxel face), and the rays to one voxel cross nearly the same voxels; measured 6.1×
    /// faster at 0.1 m, 1.8× at 0.05 m. Cost: the ray goes to the voxel's centre, so a few
    /// grazed free voxels beside the surface differ: ~1 % of the leaves, ~0.001 % of the
    /// explored volume (docs/benchmarks.md, "Occupancy octree insertion (issue 16)").
    bool discretize = true;

    /// Throws ConfigError naming the field: "<prefix>.resolution_m = 0, expected finite > 0".
    void validate(std::string_view prefix = "occupancy_octree") const;
};

/// The state of a point in the map.
enum class Occupancy {
    kUnknown,   ///< never observed (or outside the map)
    kFree,      ///< known, P(occupied) < occupied_threshold
    kOccupied,  ///< known, P(occupied) >= occupied_threshold
};

/// What one insert_depth_frame did: points = inserted rays (misses included), plus
/// dropped_non_finite = the frame's size.
struct DepthInsertStats {
    std::size_t points = 0;              ///< finite points cast as rays
    std::size_t misses = 0;              ///< of those, farther than max_range_m: free space only
    std::size_t dropped_non_finite = 0;  ///< NaN / infinite points (no return), skipped
};

/// A camera's view for next-best-view gains (SPEC §8, E(M, ξ)): it looks along its x axis
/// (x forward, y left, z up: the body convention, not the optical frame), with this field of
/// view, reach and grid of rays.
struct ViewFrustum {
    /// Full horizontal field of view, radians, in (0, pi) (default ~66°).
    double horizontal_fov_rad = 1.15;
    /// Full vertical field of view, radians, in (0, pi) (default ~49°).
    double vertical_fov_rad = 0.86;
    /// Reach of every ray (range, not depth along x), metres, finite > 0 (SPEC §8: 5 m).
    double max_depth_m = 5.0;
    /// Rays per row, >= 2 (the first and last on the FOV's edges).
    int rays_horizontal = 32;
    /// Rays per column, >= 2 (the first and last on the FOV's edges).
    int rays_vertical = 24;

    /// Throws ConfigError naming the field: "<prefix>.max_depth_m = 0, expected finite > 0".
    void validate(std::string_view prefix = "view_frustum") const;
};

/// What visible_unknown_volume saw.
struct VisibleVolume {
    double unknown_m3 = 0.0;         ///< unknown_voxels × resolution_m³
    std::size_t unknown_voxels = 0;  ///< distinct unknown voxels reached by at least one ray
    std::size_t rays = 0;            ///< rays cast: rays_horizontal × rays_vertical
    std::size_t rays_blocked = 0;    ///< of those, stopped by an occupied voxel before max depth
};

class OccupancyOctree {
  public:
    /// An empty map (everything unknown). Throws ConfigError for an invalid config.
    explicit OccupancyOctree(const OccupancyOctreeConfig& config = {});
    ~OccupancyOctree();
    /// Moves the map; a moved-from map may only be assigned to or destroyed.
    OccupancyOctree(OccupancyOctree&&) noexcept;
    /// Moves the map; a moved-from map may only be assigned to or destroyed.
    OccupancyOctree& operator=(OccupancyOctree&&) noexcept;
    OccupancyOctree(const OccupancyOctree&) = delete;
    OccupancyOctree& operator=(const OccupancyOctree&) = delete;

    /// Integrates one depth frame: `points_sensor` in the sensor frame (the rays' origin),
    /// `T_world_sensor` the fused pose of that frame. Points farther than max_range_m are cut
    /// to max_range_m and clear free space only; non-finite points are skipped and counted.
    /// Throws InputError for a non-finite pose, or a sensor closer than max_range_m to the
    /// map's edge (±32768 · resolution_m). Cost: O(points · max_range_m / resolution_m · 16),
    /// less with discretize (see the config).
    DepthInsertStats insert_depth_frame(const PointCloud& points_sensor,
                                        const Eigen::Isometry3d& T_world_sensor);

    /// The state of the voxel holding `p_world` (kUnknown outside the map). O(16). Throws
    /// InputError for a non-finite point.
    Occupancy query(const Eigen::Vector3d& p_world) const;

    /// The volume of the known leaves (free + occupied), m³. O(leaves).
    double explored_volume_m3() const;
    /// The volume of the free leaves, m³. O(leaves).
    double free_volume_m3() const;
    /// The volume of the occupied leaves, m³. O(leaves).
    double occupied_volume_m3() const;

    /// Unknown volume inside an axis-aligned box, m³ (for next-best-view gains): the number
    /// of unknown voxels of the map's resolution whose centre lies in `box_world`, times the
    /// voxel volume; so within one voxel layer of the exact volume. An empty box gives 0.
    /// Throws InputError for a non-finite box or one beyond the map's extent.
    /// Cost: O(voxels in the box · 16).
    double unknown_volume_in_m3(const Eigen::AlignedBox3d& box_world) const;

    /// The unknown volume visible from a camera pose (SPEC §8's E(M, ξ), the NBV gain's
    /// core): rays on a regular grid of angles over `view`'s FOV (each axis from −fov/2 to
    /// +fov/2 inclusive, i.e. a pinhole's rectangular pyramid) walk the voxels from the camera
    /// to max_depth_m, stopping at the first occupied voxel; the distinct unknown voxels they
    /// reach are counted once each, times the voxel volume. Rays are clipped to the map.
    /// @note A sampled lower bound of the frustum's unknown volume where the rays are sparser
    /// than the voxels: with the defaults neighbouring rays are 0.037 rad apart, ~ 0.18 m at 5 m
    /// (both ways), so at 0.1 m far voxels between rays are missed. Near the camera, where the
    /// rays are denser than the voxels, the voxels they graze on the pyramid's faces count whole
    /// (within a voxel skin of the pyramid). The voxel holding the camera is counted if unknown.
    /// Deterministic. Throws InputError for a non-finite pose or a camera outside the map
    /// (±32768 · resolution_m). Throws ConfigError for an invalid view.
    /// Cost: O(rays · max_depth_m / resolution_m · 16).
    VisibleVolume visible_unknown_volume(const Eigen::Isometry3d& T_world_camera,
                                         const ViewFrustum& view = {}) const;

    /// visible_unknown_volume with every ray also clipped to `bounds_world` (an exploration
    /// volume): only unknown voxels the rays reach inside it count, so unknown space beyond the
    /// region to explore (outside a tank, past an open side) adds no gain. A camera outside
    /// `bounds_world` sees nothing (0). Throws as the overload above, and InputError for a
    /// non-finite box. Cost: as above.
    VisibleVolume visible_unknown_volume(const Eigen::Isometry3d& T_world_camera,
                                         const ViewFrustum& view,
                                         const Eigen::AlignedBox3d& bounds_world) const;

    /// True when every voxel the closed box touches is known free (none occupied, none
    /// unknown): a collision check for a vehicle's bounding box that is conservative at the
    /// voxel level. An empty box is free; a box reaching outside the map is not. Throws
    /// InputError for a non-finite box. Cost: O(leaves intersecting the box · 16), walking
    /// OctoMap's merged leaves (a big free leaf counts once), not O(voxels).
    bool box_is_free(const Eigen::AlignedBox3d& box_world) const;

    /// True when no voxel on the segment from `from_world` to `to_world` is occupied, the
    /// voxel holding `to_world` excluded (a target on a surface is seen, not blocked by its
    /// own voxel); unknown voxels do not block. False when the segment leaves the map.
    /// Throws InputError for a non-finite point. Cost: O(length / resolution_m · 16).
    bool line_of_sight(const Eigen::Vector3d& from_world, const Eigen::Vector3d& to_world) const;

    /// Frontiers inside `bounds_world` (free space next to unknown space, SPEC §8), on the
    /// tree cut to cells of 2^coarse_levels voxels (0: voxels; 2 at 0.05 m: 0.2 m cells). A
    /// cell is free when it holds known voxels, none occupied (unknown holes allowed); a face
    /// is a frontier when some cell just across it holds no known voxel at all, so holes
    /// smaller than a cell between sparse rays are not frontiers. For each free cell (or
    /// larger merged leaf) and each of its 6 faces that is a frontier (the voxel layer across
    /// it centred inside `bounds_world`), one point: the middle of its boundary layer of voxels
    /// on that face (for a merged leaf the point stands for the whole face). A point is never in
    /// an occupied voxel; it is in a known free voxel when coarse_levels = 0 (with coarse cells
    /// it may fall on an unknown hole of its free cell). Ordered by
    /// OctoMap's leaf order: deterministic. Throws InputError for a non-finite box or
    /// coarse_levels outside [0, 8]. Cost: O(free cells in the box · 6 · 16) plus the descent
    /// into faces whose neighbour is split finer (down to cells).
    std::vector<Eigen::Vector3d> frontier_points(const Eigen::AlignedBox3d& bounds_world,
                                                 int coarse_levels = 0) const;

    /// Sets every unknown voxel the closed box touches free (one miss each: P = prob_miss),
    /// leaving known voxels as they are; returns how many it set. Why: the space a vehicle
    /// occupies is free whatever its sensors saw there (a forward camera never sees below or
    /// behind its own vehicle), so the planner's start box can pass box_is_free. An empty box
    /// sets nothing. Throws InputError for a non-finite box or one beyond the map's extent.
    /// Cost: O(voxels in the box · 16).
    std::size_t mark_free(const Eigen::AlignedBox3d& box_world);

    /// Number of leaves of the tree (known voxels, merged where 8 siblings agree).
    std::size_t num_leaves() const;
    /// The voxel edge, metres.
    double resolution_m() const;
    /// The validated config.
    const OccupancyOctreeConfig& config() const;

    /// Writes OctoMap's binary .bt (maximum likelihood: free / occupied per leaf), readable by
    /// octovis and the ROS octomap tools. Atomic: a temporary beside `path` renamed over it,
    /// so a failure never leaves a partial file. Throws FileError naming `path` on failure.
    void write_binary(const std::string& path) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace scantling::mapping
