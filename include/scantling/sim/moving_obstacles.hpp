#pragma once
/// @file
/// Moving obstacles (issue 13, item 3): spheres and axis-aligned boxes that move along
/// piecewise-linear paths through the world, seen by every ray-casting sensor next to the static
/// mesh (SceneView in sensor_mount.hpp), e.g. a ball flying at a hovering drone.
///
/// Frames and units: world frame, metres, seconds of simulated time (the clock's t, 0 at the
/// start of a run). An obstacle does not rotate; a box stays axis-aligned in the world.
///
/// Motion: the centre follows `waypoints` linearly in time. Before the first waypoint's time it
/// is held at the first position, after the last at the last; a single waypoint is a static
/// obstacle. Obstacles pass through the world and each other: nothing collides with them.
///
/// Sensors see them through SceneView (sensor_mount.hpp), frozen at each firing's stamp; a
/// scenario lists them under `moving_obstacles:` (scenario.hpp, scenarios/README.md).
///
/// Ray intersection is analytic. Surfaces are closed and double-sided like the mesh's
/// triangles: a ray starting inside an obstacle hits its inside (the exit point), a grazing
/// (tangent) ray counts as a hit, and the normal is turned to face the ray.
///
/// Thread-safety: all queries are const and may run concurrently. Determinism: a query depends
/// only on the obstacles, the ray and the time; ties between obstacles at the same range go to
/// the lowest index.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace scantling::sim {

enum class ObstacleShape {
    kSphere,  ///< radius_m about the centre
    kBox,     ///< axis-aligned, half_extents_m about the centre
};

/// Where an obstacle's centre is at one time.
struct ObstacleWaypoint {
    double t_s = 0.0;                               ///< simulated time, seconds
    Eigen::Vector3d xyz = Eigen::Vector3d::Zero();  ///< centre, world frame, metres
};

/// One obstacle: a shape moving along waypoints.
struct MovingObstacle {
    std::string name;  ///< non-empty, unique in a scenario
    ObstacleShape shape = ObstacleShape::kSphere;
    double radius_m = 0.5;  ///< kSphere: > 0
    /// kBox: half the edge lengths along world x, y, z, each > 0.
    Eigen::Vector3d half_extents_m = Eigen::Vector3d::Constant(0.5);
    /// At least one, times strictly increasing (see the file comment for the motion).
    std::vector<ObstacleWaypoint> waypoints;

    /// Throws ConfigError naming the field ("<prefix>.radius_m = -1, expected > 0",
    /// "<prefix>.waypoints[2].t_s = 1, expected > 2 (the previous waypoint's)") for an empty
    /// name, a size of the shape not finite and > 0, no waypoints, a non-finite waypoint or
    /// times not strictly increasing. Only the size of `shape` is checked.
    void validate(std::string_view prefix = "moving_obstacle") const;

    /// Centre at `t_s`, world frame: linear between waypoints, held outside them. Throws
    /// InputError for a non-finite time or no waypoints. O(log waypoints).
    Eigen::Vector3d position_at(double t_s) const;

    /// Velocity of the centre at `t_s`, world frame, m/s: the slope of the segment holding t_s
    /// (at a waypoint's time, of the segment that starts there), zero outside the waypoints.
    /// Throws as position_at.
    Eigen::Vector3d velocity_at(double t_s) const;

    /// Signed distance from `p_world` to the obstacle's surface at `t_s`, metres: positive
    /// outside, negative inside. Throws InputError for a non-finite point or time.
    double distance_m(const Eigen::Vector3d& p_world, double t_s) const;
};

/// The nearest obstacle surface along a ray.
struct ObstacleHit {
    double range_m = 0.0;                              ///< distance along the ray, metres
    Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< origin + range_m * direction, world
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit surface normal, facing the ray
    std::size_t obstacle = 0;                          ///< index into MovingObstacles
};

/// An immutable, validated set of obstacles.
class MovingObstacles {
  public:
    /// No obstacles: every ray misses.
    MovingObstacles() = default;
    /// Validates each obstacle (ConfigError prefixed "moving_obstacles[i]", also for a repeated
    /// name).
    explicit MovingObstacles(std::vector<MovingObstacle> obstacles);

    /// Validates each obstacle with prefix "<list_key>[i]" and refuses a repeated name
    /// (ConfigError "<list_key>[i].name = 'ball', expected unique ...").
    static void validate(std::span<const MovingObstacle> obstacles,
                         std::string_view list_key = "moving_obstacles");

    /// RayHit::surface_tag of a hit on an obstacle (SceneView): negative, so surface_of() gives
    /// the default Surface (albedo 0.5, textured) and defect_at() finds no defect (a world's
    /// defects lie on tags >= 0, World validation); its RayHit::triangle is kNoTriangle.
    static constexpr int kSurfaceTag = -1;

    bool empty() const { return obstacles_.empty(); }
    std::size_t size() const { return obstacles_.size(); }
    const MovingObstacle& operator[](std::size_t i) const { return obstacles_[i]; }
    std::span<const MovingObstacle> obstacles() const { return obstacles_; }
    /// Index of the obstacle named `name`, or nullopt.
    std::optional<std::size_t> find(std::string_view name) const;

    /// Centres of all obstacles at `t_s`, in index order (InputError for a non-finite time).
    /// O(n log waypoints); look them up once per sensor firing and use `intersect_at`.
    std::vector<Eigen::Vector3d> centres_at(double t_s) const;

    /// The nearest obstacle surface along `origin + r * unit_direction` for r in
    /// [min_range_m, max_range_m], with the obstacles at `t_s`; nullopt when none. Throws
    /// InputError for a non-finite origin or time, a direction whose norm differs from 1 by
    /// more than 1e-6, or not 0 <= min_range_m < max_range_m (max may be +infinity).
    /// O(n log waypoints).
    std::optional<ObstacleHit> intersect(const Eigen::Vector3d& origin,
                                         const Eigen::Vector3d& unit_direction, double min_range_m,
                                         double max_range_m, double t_s) const;

    /// Unchecked form of `intersect` for the hot path, with the centres from `centres_at`
    /// (one per obstacle, not checked): the caller has checked the ray (SceneView: the
    /// RayCaster has). O(n).
    std::optional<ObstacleHit> intersect_at(std::span<const Eigen::Vector3d> centres_world,
                                            const Eigen::Vector3d& origin,
                                            const Eigen::Vector3d& unit_direction,
                                            double min_range_m, double max_range_m) const;

    /// True when an obstacle at `t_s` crosses the segment from `from` to `to`, ignoring the
    /// first and last RayCaster::kLineOfSightMargin_m as RayCaster::occluded does. An end point
    /// inside an obstacle is occluded (the ray leaves through its surface). Throws InputError
    /// for non-finite end points or time.
    bool occluded(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double t_s) const;

    /// Smallest signed distance from `p_world` to any obstacle's surface at `t_s` (metres,
    /// negative inside; +infinity without obstacles). Throws as MovingObstacle::distance_m.
    double distance_m(const Eigen::Vector3d& p_world, double t_s) const;

  private:
    std::vector<MovingObstacle> obstacles_;
};

}  // namespace scantling::sim
