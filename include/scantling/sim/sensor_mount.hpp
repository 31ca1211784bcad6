#pragma once
/// @file
/// What every simulated exteroceptive sensor shares: the scene it looks at, how it is mounted
/// on the vehicle, and how a pose is supplied during a moving sweep.
///
/// Frames: `T_world_body` is the vehicle pose (maps body points into the world);
/// `T_body_sensor` is the mounting extrinsic of a sensor (maps sensor points into the body), so
/// `T_world_sensor = T_world_body * T_body_sensor`. Sensors return points in their own frame.

#include <Eigen/Geometry>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include <scantling/sim/moving_obstacles.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/world.hpp>

namespace scantling::sim {

/// What a sensor looks at: a ray caster over a world's mesh, that world's metadata (surface
/// albedo and texture, defects) and optionally moving obstacles placed at `time_s`.
/// Non-owning: all must outlive the view. Build it as `SceneView{caster, world.metadata}` with
/// the caster built from `world.mesh` and `world.surface_tags`, or
/// `SceneView{caster, world.metadata, &obstacles, t_s}`.
///
/// Sensors query the scene through `cast`, `cast_batch` and `occluded`, which take the nearer
/// of the mesh's hit and the obstacles' (a tie goes to the mesh). An obstacle hit has
/// `triangle = RayHit::kNoTriangle` and `surface_tag = MovingObstacles::kSurfaceTag` (default
/// surface, no defect). Without obstacles (null or empty) every query is the caster's own, bit
/// for bit.
///
/// Time: the simulators give each sensor firing the view at its stamp (`at_time`), so the
/// obstacles are frozen for the whole firing. A sweep that lasts T sees an obstacle moving at v
/// up to v · T from where it really is when each ray is cast: 0.1 m for a 0.1 s LiDAR
/// revolution and a 1 m/s obstacle.
///
/// Thread-safety and determinism: as RayCaster (queries are const; results do not depend on
/// the thread count).
struct SceneView {
    const RayCaster& caster;
    const WorldMetadata& metadata;
    const MovingObstacles* obstacles = nullptr;  ///< null or empty: the static mesh only
    double time_s = 0.0;  ///< simulated time at which `obstacles` are placed, seconds

    /// The same scene with the obstacles placed at `t_s`.
    SceneView at_time(double t_s) const;

    /// As RayCaster::cast (same checks and InputError), obstacles included.
    RayHit cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& unit_direction,
                double max_range_m) const;
    RayHit cast(const Ray& ray) const;

    /// As RayCaster::cast_batch, obstacles included (their positions are looked up once per
    /// call: O(rays · obstacles) on top of the mesh).
    void cast_batch(std::span<const Ray> rays, std::span<RayHit> out,
                    const ParallelConfig& parallel = {}) const;
    std::vector<RayHit> cast_batch(std::span<const Ray> rays,
                                   const ParallelConfig& parallel = {}) const;

    /// As RayCaster::occluded (same end margins), obstacles included.
    bool occluded(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

  private:
    bool has_obstacles() const { return obstacles != nullptr && !obstacles->empty(); }
    void add_obstacles(std::span<const Ray> rays, std::span<RayHit> hits,
                       const ParallelConfig& parallel) const;
};

/// Vehicle pose as a function of absolute time (seconds), for sweeps during motion.
using PoseAtTime = std::function<Eigen::Isometry3d(double time_s)>;

/// The surface properties of `tag`; tags without an entry in `metadata.surfaces` (e.g. a bare
/// mesh with empty metadata) get the default Surface (albedo 0.5, textured). O(1).
const Surface& surface_of(const WorldMetadata& metadata, int tag);

/// Diffuse (Lambertian) reflectivity of a hit, albedo · cos(incidence), in [0, 1]:
/// the fraction of an emitter's light that a co-located receiver sees, relative to a white
/// target hit head-on. `unit_direction` is the ray direction and `normal` the unit normal
/// facing the ray (RayHit::normal).
double lambertian_reflectivity(double albedo, const Eigen::Vector3d& unit_direction,
                               const Eigen::Vector3d& normal);

/// Throws ConfigError "<prefix>.T_body_sensor ..." unless `T_body_sensor` is finite and its
/// rotation orthonormal with determinant +1 (to 1e-6), i.e. a rigid transform.
void validate_mount(const Eigen::Isometry3d& T_body_sensor, std::string_view prefix);

}  // namespace scantling::sim
