#pragma once
// Analytic ray and distance queries on spheres and axis-aligned boxes (moving_obstacles.hpp).
// Unchecked: callers pass a unit direction, finite origin and 0 <= min_range_m <= max_range_m.
#include <Eigen/Core>
#include <optional>

namespace scantling::sim::detail {

/// A surface crossing along a ray: its range and the unit normal facing the ray.
struct ShapeHit {
    double range_m = 0.0;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};

/// First crossing of the sphere's surface with range in [min_range_m, max_range_m]: the entry,
/// or the exit when the entry is nearer than min_range_m (a ray from inside). Tangent rays hit.
std::optional<ShapeHit> intersect_sphere(const Eigen::Vector3d& centre, double radius_m,
                                         const Eigen::Vector3d& origin,
                                         const Eigen::Vector3d& unit_direction, double min_range_m,
                                         double max_range_m);

/// As intersect_sphere for the axis-aligned box `centre ± half_extents_m` (slab method).
std::optional<ShapeHit> intersect_box(const Eigen::Vector3d& centre,
                                      const Eigen::Vector3d& half_extents_m,
                                      const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& unit_direction, double min_range_m,
                                      double max_range_m);

/// Signed distance to the surface: positive outside, negative inside.
double sphere_distance_m(const Eigen::Vector3d& centre, double radius_m, const Eigen::Vector3d& p);
double box_distance_m(const Eigen::Vector3d& centre, const Eigen::Vector3d& half_extents_m,
                      const Eigen::Vector3d& p);

}  // namespace scantling::sim::detail
