// The next-best-view gain E(M, ξ) of OccupancyOctree (SPEC §8): unknown voxels visible from a
// camera pose, over the whole map or inside an exploration box.
#include <scantling/mapping/occupancy_octree.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

#include "detail/occupancy_octree_impl.hpp"

namespace scantling::mapping {
namespace {

/// Unit rays of `view` in the camera frame (x forward), on an evenly spaced grid of the angles
/// atan(y / x) and atan(z / x): the edge rays are the edges of a pinhole's rectangular pyramid.
std::vector<Eigen::Vector3d> frustum_directions(const ViewFrustum& view) {
    std::vector<Eigen::Vector3d> directions;
    directions.reserve(static_cast<std::size_t>(view.rays_horizontal) *
                       static_cast<std::size_t>(view.rays_vertical));
    const auto angle = [](double fov_rad, int i, int n) {
        return fov_rad * (static_cast<double>(i) / (n - 1) - 0.5);
    };
    for (int v = 0; v < view.rays_vertical; ++v) {
        const double tan_v = std::tan(angle(view.vertical_fov_rad, v, view.rays_vertical));
        for (int h = 0; h < view.rays_horizontal; ++h) {
            const double tan_h = std::tan(angle(view.horizontal_fov_rad, h, view.rays_horizontal));
            directions.push_back(Eigen::Vector3d(1.0, tan_h, tan_v).normalized());
        }
    }
    return directions;
}

/// The length, at most `length_m`, for which the ray from `o` along `d` stays in `box`
/// (0 when `o` is outside it).
double clip_to_box(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double length_m,
                   const Eigen::AlignedBox3d& box) {
    if (!box.contains(o)) return 0.0;
    for (int i = 0; i < 3; ++i) {
        if (d[i] > 0.0) length_m = std::min(length_m, (box.max()[i] - o[i]) / d[i]);
        if (d[i] < 0.0) length_m = std::min(length_m, (box.min()[i] - o[i]) / d[i]);
    }
    return length_m;
}

}  // namespace

void ViewFrustum::validate(std::string_view prefix) const {
    using namespace config_checks;
    // A FOV of pi or more has no pinhole pyramid (tan of ±pi/2 diverges).
    require(horizontal_fov_rad > 0.0 && horizontal_fov_rad < std::numbers::pi, prefix,
            "horizontal_fov_rad", horizontal_fov_rad, "in (0, pi)");
    require(vertical_fov_rad > 0.0 && vertical_fov_rad < std::numbers::pi, prefix,
            "vertical_fov_rad", vertical_fov_rad, "in (0, pi)");
    require_positive(max_depth_m, prefix, "max_depth_m");
    require_at_least(rays_horizontal, 2, prefix, "rays_horizontal");
    require_at_least(rays_vertical, 2, prefix, "rays_vertical");
}

VisibleVolume OccupancyOctree::visible_unknown_volume(const Eigen::Isometry3d& T_world_camera,
                                                      const ViewFrustum& view) const {
    // One voxel inside the map's edge, so float rounding never puts a ray's end outside it.
    const double half_extent_m = (detail::kHalfKeyRange - 1.0) * impl_->config.resolution_m;
    const Eigen::AlignedBox3d map_box(Eigen::Vector3d::Constant(-half_extent_m),
                                      Eigen::Vector3d::Constant(half_extent_m));
    return visible_unknown_volume(T_world_camera, view, map_box);
}

VisibleVolume OccupancyOctree::visible_unknown_volume(
    const Eigen::Isometry3d& T_world_camera, const ViewFrustum& view,
    const Eigen::AlignedBox3d& bounds_world) const {
    if (!T_world_camera.matrix().allFinite())
        throw InputError("occupancy_octree: visible_unknown_volume T_world_camera is not finite");
    if (!bounds_world.min().allFinite() || !bounds_world.max().allFinite())
        throw InputError("occupancy_octree: visible_unknown_volume bounds are not finite");
    view.validate("view_frustum");
    const double res_m = impl_->config.resolution_m;
    const double half_extent_m = (detail::kHalfKeyRange - 1.0) * res_m;
    const Eigen::Vector3d o_world = T_world_camera.translation();
    if (o_world.cwiseAbs().maxCoeff() >= half_extent_m) {
        throw InputError(fmt::format(
            "occupancy_octree: visible_unknown_volume camera at ({}, {}, {}) m is outside the "
            "map (±{} m)",
            o_world.x(), o_world.y(), o_world.z(), half_extent_m));
    }
    const Eigen::AlignedBox3d clip = bounds_world.intersection(Eigen::AlignedBox3d(
        Eigen::Vector3d::Constant(-half_extent_m), Eigen::Vector3d::Constant(half_extent_m)));
    VisibleVolume result;
    octomap::KeySet unknown;  // a voxel crossed by several rays counts once
    octomap::KeyRay ray;
    for (const Eigen::Vector3d& d_camera : frustum_directions(view)) {
        const Eigen::Vector3d d_world = T_world_camera.linear() * d_camera;
        const double length_m = clip_to_box(o_world, d_world, view.max_depth_m, clip);
        ++result.rays;
        if (length_m <= 0.0) continue;
        const bool blocked =
            impl_->walk_ray(detail::to_point3d(o_world),
                            detail::to_point3d(o_world + length_m * d_world), ray, unknown);
        result.rays_blocked += blocked ? 1 : 0;
    }
    result.unknown_voxels = unknown.size();
    result.unknown_m3 = static_cast<double>(unknown.size()) * res_m * res_m * res_m;
    return result;
}

}  // namespace scantling::mapping
