// Queries of the scene a sensor sees: the static mesh and the moving obstacles (sensor_mount.hpp).
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim {
namespace {

// Rays per parallel chunk of the obstacle pass: a few obstacles cost ~10 ns per ray, so this
// hides the ~1 µs scheduling cost.
constexpr std::size_t kObstacleGrain = 4096;

/// Replaces `hit` by the obstacles' hit when that is strictly nearer (ties stay on the mesh).
void merge(const MovingObstacles& obstacles, std::span<const Eigen::Vector3d> centres,
           const Ray& ray, RayHit& hit) {
    const double limit_m = hit.hit ? hit.range_m : ray.max_range_m;
    const std::optional<ObstacleHit> o =
        obstacles.intersect_at(centres, ray.origin, ray.direction, ray.min_range_m, limit_m);
    if (!o || (hit.hit && !(o->range_m < hit.range_m))) return;
    hit = RayHit{.hit = true,
                 .range_m = o->range_m,
                 .point = o->point,
                 .normal = o->normal,
                 .triangle = RayHit::kNoTriangle,
                 .surface_tag = MovingObstacles::kSurfaceTag};
}

}  // namespace

SceneView SceneView::at_time(double t_s) const {
    SceneView view = *this;
    view.time_s = t_s;
    return view;
}

RayHit SceneView::cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& unit_direction,
                       double max_range_m) const {
    if (!has_obstacles()) return caster.cast(origin, unit_direction, max_range_m);
    return cast(Ray{origin, unit_direction, max_range_m, 0.0});
}

RayHit SceneView::cast(const Ray& ray) const {
    RayHit hit = caster.cast(ray);  // checks the ray
    if (has_obstacles()) merge(*obstacles, obstacles->centres_at(time_s), ray, hit);
    return hit;
}

void SceneView::cast_batch(std::span<const Ray> rays, std::span<RayHit> out,
                           const ParallelConfig& parallel) const {
    caster.cast_batch(rays, out, parallel);  // checks every ray and the sizes
    if (has_obstacles()) add_obstacles(rays, out, parallel);
}

std::vector<RayHit> SceneView::cast_batch(std::span<const Ray> rays,
                                          const ParallelConfig& parallel) const {
    std::vector<RayHit> hits = caster.cast_batch(rays, parallel);
    if (has_obstacles()) add_obstacles(rays, hits, parallel);
    return hits;
}

bool SceneView::occluded(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
    if (caster.occluded(from, to)) return true;  // checks the end points
    return has_obstacles() && obstacles->occluded(from, to, time_s);
}

void SceneView::add_obstacles(std::span<const Ray> rays, std::span<RayHit> hits,
                              const ParallelConfig& parallel) const {
    const std::vector<Eigen::Vector3d> centres = obstacles->centres_at(time_s);
    // Each ray writes only its own hit: the result does not depend on the split.
    parallel_for(parallel, rays.size(), kObstacleGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) merge(*obstacles, centres, rays[i], hits[i]);
    });
}

}  // namespace scantling::sim
