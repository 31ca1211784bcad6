#include <scantling/core/error.hpp>
#include <scantling/sim/pinhole_camera.hpp>

#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace scantling::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// Pixels per parallel chunk: a few rows, so chunk overhead stays small.
constexpr std::size_t kShadeGrain = 4096;

// Brightness factor of the world-fixed texture cube containing p, in [1 − c, 1 + c).
double texture_factor(const Eigen::Vector3d& p_world, double cell_m, double contrast) {
    std::uint64_t h = 0x9E3779B97F4A7C15ULL;
    for (int a = 0; a < 3; ++a) {
        const auto cell = static_cast<std::int64_t>(std::floor(p_world[a] / cell_m));
        h = splitmix64(h ^ static_cast<std::uint64_t>(cell));
    }
    const double unit = static_cast<double>(h >> 11) * 0x1.0p-53;
    return 1.0 + contrast * (2.0 * unit - 1.0);
}

std::uint8_t to_dn(double value) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 255.0)));
}

Rgb8 scaled(const Rgb8& colour, double factor) {
    return Rgb8(to_dn(colour[0] * factor), to_dn(colour[1] * factor), to_dn(colour[2] * factor));
}

// Colour of a hit seen along `direction` (see the header for the model).
Rgb8 shade(const RayHit& hit, const Eigen::Vector3d& direction, const SceneView& scene,
           const PinholeCameraConfig& config) {
    const double light = config.ambient + (1.0 - config.ambient) *
                                              lambertian_reflectivity(1.0, direction, hit.normal);
    const int defect_id = defect_at(scene.metadata, hit.point, hit.surface_tag);
    if (defect_id >= 0) {
        // defect_at returns an id, not an index: look the kind up by id.
        const auto& defects = scene.metadata.defects;
        const auto it = std::find_if(defects.begin(), defects.end(),
                                     [&](const Defect& d) { return d.id == defect_id; });
        const bool crack = it != defects.end() && it->kind == DefectKind::Crack;
        return scaled(crack ? kCrackRgb : kCorrosionRgb, light);
    }
    const Surface& surface = surface_of(scene.metadata, hit.surface_tag);
    const double texture =
        surface.textured ? texture_factor(hit.point, config.texture_cell_m, config.texture_contrast)
                         : 1.0;
    const double grey = 255.0 * std::clamp(surface.albedo, 0.0, 1.0) * light * texture;
    return Rgb8(to_dn(grey), to_dn(grey), to_dn(grey));
}

}  // namespace

void PinholeCameraConfig::validate(std::string_view prefix) const {
    intrinsics.validate(detail::sub(prefix, "intrinsics"));
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require_positive(prefix, "max_range_m", max_range_m);
    detail::require_probability(prefix, "ambient", ambient);
    detail::require_positive(prefix, "texture_cell_m", texture_cell_m);
    detail::require(texture_contrast >= 0.0 && texture_contrast < 1.0, prefix, "texture_contrast",
                    texture_contrast, "in [0, 1)");
    detail::require_non_negative(prefix, "pixel_noise_dn", pixel_noise_dn);
    detail::require_angle(prefix, "max_defect_view_angle_rad", max_defect_view_angle_rad,
                          std::numbers::pi / 2.0 + 1e-12);
    validate_mount(T_body_sensor, prefix);
    detail::require(lasers.size() <= kMaxLaserPointers, prefix, "lasers",
                    static_cast<double>(lasers.size()),
                    fmt::format("at most {} lasers", kMaxLaserPointers));
    for (std::size_t i = 0; i < lasers.size(); ++i) {
        lasers[i].validate(fmt::format("{}.lasers[{}]", prefix, i));
    }
}

PinholeCameraConfig uav3d_camera() { return PinholeCameraConfig{}; }

PinholeCameraConfig rov_camera(int width) {
    if (width < 16) {
        throw ConfigError(fmt::format("rov_camera.width = {}, expected >= 16", width));
    }
    PinholeCameraConfig config;
    const int height = static_cast<int>(std::lround(width * 9.0 / 16.0));
    config.intrinsics = PinholeIntrinsics::from_fov(width, height, 77.0 * kDeg, 48.0 * kDeg);
    config.max_range_m = 20.0;
    return config;
}

PinholeCamera::PinholeCamera(PinholeCameraConfig config) : config_(std::move(config)) {
    config_.validate();
    const PinholeIntrinsics& k = config_.intrinsics;
    rays_camera_.reserve(static_cast<std::size_t>(k.width) * k.height);
    for (int v = 0; v < k.height; ++v) {
        for (int u = 0; u < k.width; ++u) {
            rays_camera_.push_back(k.ray_direction(Eigen::Vector2d(u, v)));
        }
    }
}

RgbImage PinholeCamera::render(const SceneView& scene, const Eigen::Isometry3d& T_world_body,
                               Rng& rng, const ParallelConfig& parallel) const {
    const Eigen::Isometry3d T_world_camera = T_world_body * config_.T_body_sensor;
    std::vector<Ray> rays(rays_camera_.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        rays[i] =
            Ray{T_world_camera.translation(),
                (T_world_camera.linear() * rays_camera_[i]).normalized(), config_.max_range_m, 0.0};
    }
    const std::vector<RayHit> hits = scene.cast_batch(rays, parallel);
    RgbImage image{config_.intrinsics.width, config_.intrinsics.height,
                   std::vector<Rgb8>(rays.size(), config_.background)};
    parallel_for(parallel, hits.size(), kShadeGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            if (hits[i].hit) image.pixels[i] = shade(hits[i], rays[i].direction, scene, config_);
        }
    });
    if (!config_.lasers.empty()) {
        draw_laser_spots(laser_spots(scene, T_world_body), config_.lasers, image);
    }
    if (config_.pixel_noise_dn > 0.0) {
        for (Rgb8& pixel : image.pixels) {
            for (int c = 0; c < 3; ++c) {
                pixel[c] = to_dn(pixel[c] + config_.pixel_noise_dn * rng.normal());
            }
        }
    }
    return image;
}

std::vector<LaserSpot> PinholeCamera::laser_spots(const SceneView& scene,
                                                  const Eigen::Isometry3d& T_world_body) const {
    return cast_laser_spots(config_.lasers, config_.intrinsics, config_.max_range_m, scene,
                            T_world_body * config_.T_body_sensor);
}

std::vector<int> PinholeCamera::visible_defects(const SceneView& scene,
                                                const Eigen::Isometry3d& T_world_body) const {
    std::vector<int> visible;
    for (const io::DefectSighting& s : sight_defects(scene, T_world_body))
        visible.push_back(s.defect_id);
    return visible;
}

std::vector<io::DefectSighting> PinholeCamera::sight_defects(
    const SceneView& scene, const Eigen::Isometry3d& T_world_body) const {
    const Eigen::Isometry3d T_world_camera = T_world_body * config_.T_body_sensor;
    const Eigen::Isometry3d T_camera_world = T_world_camera.inverse();
    const Eigen::Vector3d eye_world = T_world_camera.translation();
    const double min_cos = std::cos(config_.max_defect_view_angle_rad);
    std::vector<io::DefectSighting> sightings;
    for (const Defect& defect : scene.metadata.defects) {  // ids ascend with the list
        const Eigen::Vector3d to_eye = eye_world - defect.centre;
        const double distance_m = to_eye.norm();
        if (distance_m > config_.max_range_m || distance_m <= 0.0) continue;
        if (defect.normal.dot(to_eye) / distance_m <= min_cos) continue;
        const Eigen::Vector3d centre_camera = T_camera_world * defect.centre;
        const std::optional<Eigen::Vector2d> pixel = config_.intrinsics.project(centre_camera);
        if (!pixel) continue;
        if (scene.occluded(eye_world, defect.centre)) continue;
        sightings.push_back(
            {.image = 0,
             .stamp_s = 0.0,
             .defect_id = defect.id,
             .pixel = *pixel,
             .radius_px = config_.intrinsics.fx * defect.radius_m / centre_camera.z()});
    }
    return sightings;
}

}  // namespace scantling::sim
