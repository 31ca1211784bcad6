#pragma once
/// @file
/// UAV 3D reconstruction by point-density planning (SPEC §9; source 004 l.43–63, l.98–120).
///
/// 1. `locate_object`: coarse voxel segmentation of the sparse cloud (edge `voxel_edge_m`); the
///    densest voxel is the object, its points' centre of mass the orbit centre (x, y), and
///    r_flight = standoff_m + r_object with one voxel edge = 2 r_object. The source's own
///    experiment gives both centre and r_flight (004 l.98): `fixed_centre` and
///    `fixed_flight_radius_m` override them.
/// 2. `count_sectors`: four equal sectors around the centre, counter-clockwise seen from above,
///    sector 0 starting at `start_angle_rad` (004 l.71: the start (r_flight, 0) lies on the
///    border of sectors 0 and 3, so the default 0 puts sector 0 at azimuths [0°, 90°)).
///    "Entropy" of a sector = its point count (004 l.59).
/// 3. `PointDensityPlanner::next`: one step of the segment-order rule of 004 l.118. The first
///    step of a round targets the sector with the fewest points, flown in the shorter
///    rotational direction, and designates its neighbour with fewer points as the next; the
///    remaining two follow in the rotational direction from the first to the second, so a
///    round visits all four sectors. A new round starts after four steps. The target is on the
///    circle of radius r_flight (absolute to the centre, 004 l.71) in the direction of the
///    centroid of the sector's points at half height (004 l.61), at the height of those points
///    or at `flight_height_m` (004 l.120: z = 3 m). Planning stops when every sector holds at
///    least `density_threshold_points` (004 l.63) or after `max_steps`.
///
/// Frames: world, z up, metres, radians. Deterministic (ties: lower sector index; equal
/// neighbour counts: the neighbour ahead in the direction of travel). Cost: O(points) per call.
/// Thread-safety: free functions are pure; the planner is a small state machine.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

namespace scantling::planning {

inline constexpr int kNumSectors = 4;
using SectorCounts = std::array<std::size_t, kNumSectors>;

struct PointDensityPlannerConfig {
    double voxel_edge_m = 2.0;  ///< coarse segmentation voxel edge = 2 r_object (SPEC §9)
    double standoff_m = 1.0;    ///< r_flight = standoff_m + r_object (SPEC §9: 1 m)
    /// > 0: r_flight given by the user (004 l.98), absolute to the centre; 0: from the voxel.
    double fixed_flight_radius_m = 0.0;
    /// Orbit centre (x, y) given by the user (004 l.98: "mass center determined already").
    std::optional<Eigen::Vector2d> fixed_centre_xy_m{};
    /// Flight height; nullopt: the half height of the target sector's points (004 l.61).
    std::optional<double> flight_height_m{};
    double start_angle_rad = 0.0;  ///< azimuth where sector 0 begins (border of sectors 0 and 3)
    /// Points "at half height": within ± this of the sector's mid height, metres.
    double half_height_band_m = 0.5;
    std::size_t density_threshold_points = 800;  ///< per sector; stop when all reach it
    std::size_t max_steps = 8;                   ///< stop after this many steps (2 rounds)

    /// Throws ConfigError naming the field ("point_density_planner.voxel_edge_m = 0, ...").
    void validate(std::string_view prefix = "point_density_planner") const;
};

/// Where the object is and the circle to fly around it.
struct ObjectEstimate {
    bool found = false;                                     ///< false: empty cloud, no centre
    Eigen::Vector2d centre_xy_m = Eigen::Vector2d::Zero();  ///< orbit centre
    double object_radius_m = 0.0;                           ///< r_object = voxel edge / 2
    double flight_radius_m = 0.0;                           ///< r_flight
    std::size_t points_in_voxel = 0;                        ///< points of the densest voxel
};

/// Step 2 of SPEC §9 (see the file comment). Empty cloud without a fixed centre: found = false.
/// Throws ConfigError for a bad config, InputError for a non-finite point.
ObjectEstimate locate_object(std::span<const Eigen::Vector3d> points_world,
                             const PointDensityPlannerConfig& config = {});

/// Sector (0–3) of a point around `centre_xy_m`, sector 0 beginning at `start_angle_rad`.
int sector_of(const Eigen::Vector3d& p_world, const Eigen::Vector2d& centre_xy_m,
              double start_angle_rad);

/// Points per sector.
SectorCounts count_sectors(std::span<const Eigen::Vector3d> points_world,
                           const Eigen::Vector2d& centre_xy_m, double start_angle_rad);

enum class PlannerStatus { kTarget, kThresholdReached, kMaxSteps, kNoObject };

/// One planning step: where to fly next and why.
struct DensityStep {
    PlannerStatus status = PlannerStatus::kNoObject;
    std::size_t step = 0;           ///< 1-based index of this step (step 0 is the initial turn)
    SectorCounts counts{};          ///< sector counts the decision used
    int sector = -1;                ///< sector targeted
    int next_sector = -1;           ///< sector designated for the following step (-1: new round)
    int direction = 0;              ///< +1 counter-clockwise, −1 clockwise (seen from above)
    double target_angle_rad = 0.0;  ///< target azimuth about the centre
    double arc_rad = 0.0;           ///< signed rotation to fly from the current azimuth
    Eigen::Vector3d target_world_m = Eigen::Vector3d::Zero();
};

/// The segment-order state machine of 004 l.118 (see the file comment).
class PointDensityPlanner {
  public:
    /// Validates the config (ConfigError).
    explicit PointDensityPlanner(PointDensityPlannerConfig config = {});

    /// The next step given the cloud so far and the vehicle's azimuth about the orbit centre.
    /// `object` is usually locate_object(cloud). Throws InputError for a non-finite azimuth.
    DensityStep next(std::span<const Eigen::Vector3d> points_world, const ObjectEstimate& object,
                     double current_angle_rad);

    std::size_t steps_taken() const { return steps_; }
    const PointDensityPlannerConfig& config() const { return config_; }

  private:
    int choose_sector(const SectorCounts& counts, double current_angle_rad);
    void aim(std::span<const Eigen::Vector3d> points_world, const ObjectEstimate& object,
             double current_angle_rad, DensityStep& step) const;

    PointDensityPlannerConfig config_;
    std::size_t steps_ = 0;
    int first_sector_ = -1;  ///< sector of the round's first step
    int order_ = 0;          ///< +1 / −1: sector order within the round
};

}  // namespace scantling::planning
