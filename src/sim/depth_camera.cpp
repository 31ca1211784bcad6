#include <scantling/core/error.hpp>
#include <scantling/sim/depth_camera.hpp>

#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace scantling::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

PointCloud nan_organised_cloud(std::size_t n, double stamp_s) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    PointCloud cloud;
    cloud.stamp_s = stamp_s;
    cloud.points.assign(n, Eigen::Vector3d::Constant(nan));
    cloud.intensities.assign(n, 0.0f);
    return cloud;
}

}  // namespace

void DepthCameraConfig::validate(std::string_view prefix) const {
    intrinsics.validate(detail::sub(prefix, "intrinsics"));
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require_positive(prefix, "min_depth_m", min_depth_m);
    detail::require(std::isfinite(max_depth_m) && max_depth_m > min_depth_m, prefix, "max_depth_m",
                    max_depth_m, fmt::format("finite and > min_depth_m = {}", min_depth_m));
    depth_noise.validate(detail::sub(prefix, "depth_noise"));
    validate_mount(T_body_sensor, prefix);
}

DepthCameraConfig intel_l515(int width) {
    if (width != 320 && width != 640 && width != 1024) {
        throw ConfigError(
            fmt::format("intel_l515.width = {}, expected 320, 640 or 1024 (4:3 modes)", width));
    }
    DepthCameraConfig config;
    config.intrinsics = PinholeIntrinsics::from_fov(width, width * 3 / 4, 70.0 * kDeg, 55.0 * kDeg);
    return config;
}

DepthCameraConfig azure_kinect_nfov(bool binned) {
    DepthCameraConfig config;
    config.intrinsics = binned ? PinholeIntrinsics::from_fov(320, 288, 75.0 * kDeg, 65.0 * kDeg)
                               : PinholeIntrinsics::from_fov(640, 576, 75.0 * kDeg, 65.0 * kDeg);
    config.min_depth_m = 0.5;
    config.max_depth_m = binned ? 5.46 : 3.86;
    config.depth_noise = ReturnModel{.sigma_m = 0.001,
                                     .sigma_per_m2 = 0.001,
                                     .dropout_probability = 0.002,
                                     .weak_reflectivity = 0.03,
                                     .weak_dropout_probability = 0.5};
    return config;
}

DepthImage to_depth_image(const PointCloud& organised, int width, int height) {
    if (width < 0 || height < 0 ||
        organised.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
        throw InputError(fmt::format("to_depth_image: cloud has {} points, expected {} x {}",
                                     organised.size(), width, height));
    }
    DepthImage image{width, height, std::vector<float>(organised.size(), 0.0f)};
    for (std::size_t i = 0; i < organised.size(); ++i) {
        const double z = organised.points[i].z();
        if (std::isfinite(z)) image.depth_m[i] = static_cast<float>(z);
    }
    return image;
}

DepthCamera::DepthCamera(DepthCameraConfig config) : config_(std::move(config)) {
    config_.validate();
    const PinholeIntrinsics& k = config_.intrinsics;
    rays_camera_.reserve(static_cast<std::size_t>(k.width) * k.height);
    for (int v = 0; v < k.height; ++v) {
        for (int u = 0; u < k.width; ++u)
            rays_camera_.push_back(k.ray_direction(Eigen::Vector2d(u, v)));
    }
}

PointCloud DepthCamera::scan(const SceneView& scene, const Eigen::Isometry3d& T_world_body,
                             Rng& rng, double stamp_s, const ParallelConfig& parallel) const {
    const Eigen::Isometry3d T_world_camera = T_world_body * config_.T_body_sensor;
    std::vector<Ray> rays(rays_camera_.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Eigen::Vector3d& d = rays_camera_[i];
        // The far limit is on depth: the range at which this pixel's ray reaches max_depth_m.
        rays[i] = Ray{T_world_camera.translation(), (T_world_camera.linear() * d).normalized(),
                      config_.max_depth_m / d.z(), 0.0};
    }
    const std::vector<RayHit> hits = scene.cast_batch(rays, parallel);
    PointCloud cloud = nan_organised_cloud(rays.size(), stamp_s);
    for (std::size_t i = 0; i < hits.size(); ++i) {
        if (!hits[i].hit) continue;
        const Eigen::Vector3d& d = rays_camera_[i];
        const double z = hits[i].range_m * d.z();
        if (z < config_.min_depth_m) continue;
        const double rho =
            lambertian_reflectivity(surface_of(scene.metadata, hits[i].surface_tag).albedo,
                                    rays[i].direction, hits[i].normal);
        const ReturnSample sample = sample_return(config_.depth_noise, z, rho, rng);
        if (!sample.kept) continue;
        cloud.points[i] = (sample.distance_m / d.z()) * d;
        cloud.intensities[i] = static_cast<float>(rho);
    }
    return cloud;
}

DepthImage DepthCamera::depth_image(const SceneView& scene, const Eigen::Isometry3d& T_world_body,
                                    Rng& rng, const ParallelConfig& parallel) const {
    return to_depth_image(scan(scene, T_world_body, rng, 0.0, parallel), config_.intrinsics.width,
                          config_.intrinsics.height);
}

}  // namespace scantling::sim
