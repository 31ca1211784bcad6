#include <scantling/sim/stereo_points.hpp>

#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace scantling::sim {

void StereoPointsConfig::validate(std::string_view prefix) const {
    intrinsics.validate(detail::sub(prefix, "intrinsics"));
    detail::require_positive(prefix, "baseline_m", baseline_m);
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require(std::isfinite(feature_spacing_px) && feature_spacing_px >= 1.0, prefix,
                    "feature_spacing_px", feature_spacing_px, ">= 1");
    detail::require_non_negative(prefix, "disparity_sigma_px", disparity_sigma_px);
    detail::require_positive(prefix, "min_depth_m", min_depth_m);
    detail::require(std::isfinite(max_depth_m) && max_depth_m > min_depth_m, prefix, "max_depth_m",
                    max_depth_m, fmt::format("finite and > min_depth_m = {}", min_depth_m));
    validate_mount(T_body_sensor, prefix);
}

StereoPoints::StereoPoints(StereoPointsConfig config) : config_(std::move(config)) {
    config_.validate();
}

double StereoPoints::depth_sigma_m(double depth_m) const {
    return depth_m * depth_m * config_.disparity_sigma_px /
           (config_.intrinsics.fx * config_.baseline_m);
}

std::vector<Eigen::Vector2d> StereoPoints::candidate_pixels(Rng& rng) const {
    const PinholeIntrinsics& k = config_.intrinsics;
    const double s = config_.feature_spacing_px;
    const int cols = std::max(1, static_cast<int>(std::floor(k.width / s)));
    const int rows = std::max(1, static_cast<int>(std::floor(k.height / s)));
    // Cells tile the image exactly: the spacing is stretched to fill the last partial cell.
    const double cell_u = k.width / static_cast<double>(cols);
    const double cell_v = k.height / static_cast<double>(rows);
    std::vector<Eigen::Vector2d> pixels;
    pixels.reserve(static_cast<std::size_t>(rows) * cols);
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < cols; ++c) {
            const double u = (c + rng.uniform()) * cell_u - 0.5;
            const double v = (r + rng.uniform()) * cell_v - 0.5;
            pixels.emplace_back(u, v);
        }
    }
    return pixels;
}

bool StereoPoints::seen_by_right(const SceneView& scene, const Eigen::Isometry3d& T_world_camera,
                                 const Eigen::Vector3d& p_left,
                                 const Eigen::Vector3d& p_world) const {
    const Eigen::Vector3d right_in_left(config_.baseline_m, 0.0, 0.0);
    if (!config_.intrinsics.project(p_left - right_in_left)) return false;
    return !scene.occluded(T_world_camera * right_in_left, p_world);
}

PointCloud StereoPoints::scan(const SceneView& scene, const Eigen::Isometry3d& T_world_body,
                              Rng& rng, double stamp_s, const ParallelConfig& parallel) const {
    const Eigen::Isometry3d T_world_camera = T_world_body * config_.T_body_sensor;
    const std::vector<Eigen::Vector2d> pixels = candidate_pixels(rng);
    std::vector<Ray> rays(pixels.size());
    std::vector<Eigen::Vector3d> rays_camera(pixels.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        rays_camera[i] = config_.intrinsics.ray_direction(pixels[i]);
        rays[i] = Ray{T_world_camera.translation(),
                      (T_world_camera.linear() * rays_camera[i]).normalized(),
                      config_.max_depth_m / rays_camera[i].z(), 0.0};
    }
    const std::vector<RayHit> hits = scene.cast_batch(rays, parallel);
    PointCloud cloud;
    cloud.stamp_s = stamp_s;
    for (std::size_t i = 0; i < hits.size(); ++i) {
        if (!hits[i].hit || !surface_of(scene.metadata, hits[i].surface_tag).textured) continue;
        const Eigen::Vector3d p_left = hits[i].range_m * rays_camera[i];
        if (p_left.z() < config_.min_depth_m) continue;
        if (!seen_by_right(scene, T_world_camera, p_left, hits[i].point)) continue;
        const double z = p_left.z() + depth_sigma_m(p_left.z()) * rng.normal();
        cloud.points.push_back((z / rays_camera[i].z()) * rays_camera[i]);
    }
    return cloud;
}

}  // namespace scantling::sim
