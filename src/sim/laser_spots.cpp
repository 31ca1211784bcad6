#include <scantling/core/error.hpp>
#include <scantling/sim/laser_spots.hpp>

#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace scantling::sim {
namespace {

[[noreturn]] void bad_vector(std::string_view prefix, std::string_view field,
                             const Eigen::Vector3d& value, std::string_view expected) {
    throw ConfigError(fmt::format("{}.{} = [{}, {}, {}], expected {}", prefix, field, value.x(),
                                  value.y(), value.z(), expected));
}

// The laser's hit when its spot is visible from the camera (see the header), else nullopt.
std::optional<Eigen::Vector3d> visible_hit(const LaserPointer& laser, double max_range_m,
                                           const SceneView& scene,
                                           const Eigen::Isometry3d& T_world_camera) {
    const Eigen::Vector3d origin_world = T_world_camera * laser.origin_camera;
    const Eigen::Vector3d direction_world =
        (T_world_camera.linear() * laser.direction_camera).normalized();
    const RayHit hit = scene.cast(origin_world, direction_world, max_range_m);
    if (!hit.hit) return std::nullopt;
    const Eigen::Vector3d eye_world = T_world_camera.translation();
    if ((hit.point - eye_world).norm() > max_range_m) return std::nullopt;
    if (scene.occluded(eye_world, hit.point)) return std::nullopt;
    return hit.point;
}

// Share of pixel (u, v) inside the disc, from kSpotSubsamples² samples.
double coverage(int u, int v, const Eigen::Vector2d& centre, double radius_px) {
    constexpr int n = kSpotSubsamples;
    int inside = 0;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const Eigen::Vector2d sample(u - 0.5 + (i + 0.5) / n, v - 0.5 + (j + 0.5) / n);
            if ((sample - centre).squaredNorm() <= radius_px * radius_px) ++inside;
        }
    }
    return static_cast<double>(inside) / (n * n);
}

std::uint8_t blend(std::uint8_t below, double above, double alpha) {
    return static_cast<std::uint8_t>(
        std::lround(std::clamp((1.0 - alpha) * below + alpha * above, 0.0, 255.0)));
}

void draw_disc(const LaserSpot& spot, const Eigen::Vector3d& rgb, io::RgbImage& image) {
    const double r = spot.radius_px;
    const int u0 = std::max(0, static_cast<int>(std::floor(spot.pixel.x() - r)));
    const int u1 = std::min(image.width - 1, static_cast<int>(std::ceil(spot.pixel.x() + r)));
    const int v0 = std::max(0, static_cast<int>(std::floor(spot.pixel.y() - r)));
    const int v1 = std::min(image.height - 1, static_cast<int>(std::ceil(spot.pixel.y() + r)));
    for (int v = v0; v <= v1; ++v) {
        for (int u = u0; u <= u1; ++u) {
            const double alpha = coverage(u, v, spot.pixel, r);
            if (alpha <= 0.0) continue;
            Rgb8& pixel = image.pixels[static_cast<std::size_t>(v) * image.width + u];
            for (int c = 0; c < 3; ++c) pixel[c] = blend(pixel[c], rgb[c], alpha);
        }
    }
}

}  // namespace

void LaserPointer::validate(std::string_view prefix) const {
    if (!origin_camera.allFinite()) bad_vector(prefix, "origin_camera", origin_camera, "finite");
    if (!direction_camera.allFinite() || direction_camera.norm() <= 0.0) {
        bad_vector(prefix, "direction_camera", direction_camera, "finite and non-zero");
    }
    detail::require_positive(prefix, "spot_radius_m", spot_radius_m);
    if (!(rgb.minCoeff() >= 0.0 && rgb.maxCoeff() <= 255.0)) {
        bad_vector(prefix, "rgb", rgb, "each channel in [0, 255]");
    }
}

std::vector<LaserSpot> cast_laser_spots(const std::vector<LaserPointer>& lasers,
                                        const PinholeIntrinsics& intrinsics, double max_range_m,
                                        const SceneView& scene,
                                        const Eigen::Isometry3d& T_world_camera) {
    std::vector<LaserSpot> spots;
    const Eigen::Isometry3d T_camera_world = T_world_camera.inverse();
    for (std::size_t i = 0; i < lasers.size(); ++i) {
        const std::optional<Eigen::Vector3d> hit_world =
            visible_hit(lasers[i], max_range_m, scene, T_world_camera);
        if (!hit_world) continue;
        const Eigen::Vector3d p_camera = T_camera_world * *hit_world;
        const std::optional<Eigen::Vector2d> pixel = intrinsics.project(p_camera);
        if (!pixel) continue;
        const double radius_px =
            std::max(1.0, intrinsics.fx * lasers[i].spot_radius_m / p_camera.z());
        spots.push_back({static_cast<int>(i), p_camera, *pixel, radius_px});
    }
    return spots;
}

void draw_laser_spots(const std::vector<LaserSpot>& spots, const std::vector<LaserPointer>& lasers,
                      io::RgbImage& image) {
    for (const LaserSpot& spot : spots) {
        draw_disc(spot, lasers.at(static_cast<std::size_t>(spot.laser)).rgb, image);
    }
}

}  // namespace scantling::sim
