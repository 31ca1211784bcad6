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
#include <string_view>

#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/world.hpp>

namespace scantling::sim {

/// What a sensor looks at: a ray caster over a world's mesh and that world's metadata (surface
/// albedo and texture, defects). Non-owning: both must outlive the view. Build it as
/// `SceneView{caster, world.metadata}` with the caster built from `world.mesh` and
/// `world.surface_tags`.
struct SceneView {
    const RayCaster& caster;
    const WorldMetadata& metadata;
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
