#include <scantling/sim/camera_model.hpp>

#include "detail/sensor_checks.hpp"

#include <cmath>
#include <numbers>

namespace scantling::sim {

PinholeIntrinsics PinholeIntrinsics::from_fov(int width, int height, double hfov_rad,
                                              double vfov_rad) {
    constexpr std::string_view kWhat = "pinhole";
    detail::require(width >= 1, kWhat, "width", width, ">= 1");
    detail::require(height >= 1, kWhat, "height", height, ">= 1");
    detail::require_angle(kWhat, "hfov_rad", hfov_rad, std::numbers::pi);
    detail::require_angle(kWhat, "vfov_rad", vfov_rad, std::numbers::pi);
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
    detail::require(width >= 1, prefix, "width", width, ">= 1");
    detail::require(height >= 1, prefix, "height", height, ">= 1");
    detail::require_positive(prefix, "fx", fx);
    detail::require_positive(prefix, "fy", fy);
    detail::require(std::isfinite(cx), prefix, "cx", cx, "finite");
    detail::require(std::isfinite(cy), prefix, "cy", cy, "finite");
}

}  // namespace scantling::sim
