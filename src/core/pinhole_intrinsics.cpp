#include <scantling/core/config_checks.hpp>
#include <scantling/core/pinhole_intrinsics.hpp>

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace scantling {
namespace {

void require_field_of_view(double value_rad, std::string_view prefix, std::string_view field) {
    config_checks::require(value_rad > 0.0 && value_rad < std::numbers::pi, prefix, field,
                           value_rad, fmt::format("in (0, {}) rad", std::numbers::pi));
}

}  // namespace

PinholeIntrinsics PinholeIntrinsics::from_fov(int width, int height, double hfov_rad,
                                              double vfov_rad) {
    constexpr std::string_view kWhat = "pinhole";
    config_checks::require_at_least(width, 1, kWhat, "width");
    config_checks::require_at_least(height, 1, kWhat, "height");
    require_field_of_view(hfov_rad, kWhat, "hfov_rad");
    require_field_of_view(vfov_rad, kWhat, "vfov_rad");
    return PinholeIntrinsics{.width = width,
                             .height = height,
                             .fx = 0.5 * width / std::tan(0.5 * hfov_rad),
                             .fy = 0.5 * height / std::tan(0.5 * vfov_rad),
                             .cx = 0.5 * (width - 1),
                             .cy = 0.5 * (height - 1)};
}

double PinholeIntrinsics::hfov_rad() const { return 2.0 * std::atan(0.5 * width / fx); }

double PinholeIntrinsics::vfov_rad() const { return 2.0 * std::atan(0.5 * height / fy); }

std::optional<Eigen::Vector2d> PinholeIntrinsics::project(const Eigen::Vector3d& p_camera) const {
    if (!(p_camera.z() > 0.0)) return std::nullopt;
    const Eigen::Vector2d pixel(fx * p_camera.x() / p_camera.z() + cx,
                                fy * p_camera.y() / p_camera.z() + cy);
    if (!contains(pixel)) return std::nullopt;
    return pixel;
}

Eigen::Vector3d PinholeIntrinsics::unproject(const Eigen::Vector2d& pixel, double depth_m) const {
    return {(pixel.x() - cx) / fx * depth_m, (pixel.y() - cy) / fy * depth_m, depth_m};
}

Eigen::Vector3d PinholeIntrinsics::ray_direction(const Eigen::Vector2d& pixel) const {
    return unproject(pixel, 1.0).normalized();
}

bool PinholeIntrinsics::contains(const Eigen::Vector2d& pixel) const {
    return pixel.x() >= -0.5 && pixel.x() < width - 0.5 && pixel.y() >= -0.5 &&
           pixel.y() < height - 0.5;
}

void PinholeIntrinsics::validate(std::string_view prefix) const {
    config_checks::require_at_least(width, 1, prefix, "width");
    config_checks::require_at_least(height, 1, prefix, "height");
    config_checks::require_positive(fx, prefix, "fx");
    config_checks::require_positive(fy, prefix, "fy");
    config_checks::require(std::isfinite(cx), prefix, "cx", cx, "finite");
    config_checks::require(std::isfinite(cy), prefix, "cy", cy, "finite");
}

}  // namespace scantling
