#include <scantling/core/error.hpp>
#include <scantling/sim/helix_trajectory.hpp>

#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

constexpr double kPi = std::numbers::pi;

void require_finite(std::string_view prefix, std::string_view field, double value) {
    detail::require(std::isfinite(value), prefix, field, value, "finite");
}

OrbitTrajectoryConfig orbit_of(const HelixTrajectoryConfig& helix) {
    helix.validate();
    OrbitTrajectoryConfig orbit;
    orbit.centre_m = Eigen::Vector3d(helix.x0_m, helix.y0_m, helix.z0_m);
    orbit.radius_m = helix.radius_m;
    orbit.angular_rate_radps = -helix.omega_radps;  // θ = π − ωt gives x = −r cos ωt
    orbit.start_angle_rad = kPi;
    orbit.climb_rate_mps = helix.v_z_mps;
    orbit.turns = helix.rotations;
    orbit.heading = OrbitHeading::kFaceCentre;  // θ + π = 2π − ωt ≡ −ωt
    orbit.yaw_offset_rad = helix.yaw0_rad;
    return orbit;
}

}  // namespace

void OrbitTrajectoryConfig::validate(std::string_view prefix) const {
    if (!centre_m.allFinite()) {
        throw ConfigError(fmt::format("{}.centre_m = ({}, {}, {}), expected finite", prefix,
                                      centre_m.x(), centre_m.y(), centre_m.z()));
    }
    detail::require_positive(prefix, "radius_m", radius_m);
    detail::require(std::isfinite(angular_rate_radps) && angular_rate_radps != 0.0, prefix,
                    "angular_rate_radps", angular_rate_radps, "finite and != 0");
    require_finite(prefix, "start_angle_rad", start_angle_rad);
    require_finite(prefix, "climb_rate_mps", climb_rate_mps);
    detail::require_positive(prefix, "turns", turns);
    require_finite(prefix, "yaw_offset_rad", yaw_offset_rad);
}

OrbitTrajectory::OrbitTrajectory(const OrbitTrajectoryConfig& config) : config_(config) {
    config_.validate();
    duration_s_ = 2.0 * kPi * config_.turns / std::abs(config_.angular_rate_radps);
}

MotionState OrbitTrajectory::at(double t_s) const {
    const OrbitTrajectoryConfig& c = config_;
    const double t = std::clamp(t_s, 0.0, duration_s_);
    const double moving = (t_s >= 0.0 && t_s <= duration_s_) ? 1.0 : 0.0;
    const double w = c.angular_rate_radps;
    const double theta = c.start_angle_rad + w * t;
    const Eigen::Vector3d radial(std::cos(theta), std::sin(theta), 0.0);
    const Eigen::Vector3d tangent(-std::sin(theta), std::cos(theta), 0.0);
    const Eigen::Vector3d p =
        c.centre_m + c.radius_m * radial + Eigen::Vector3d(0, 0, c.climb_rate_mps * t);
    const Eigen::Vector3d v = c.radius_m * w * tangent + Eigen::Vector3d(0, 0, c.climb_rate_mps);
    const Eigen::Vector3d a = -c.radius_m * w * w * radial;
    const double facing = c.heading == OrbitHeading::kFaceCentre ? kPi : std::copysign(kPi / 2, w);
    return level_state(t_s, p, moving * v, moving * a, theta + facing + c.yaw_offset_rad,
                       moving * w);
}

void HelixTrajectoryConfig::validate(std::string_view prefix) const {
    require_finite(prefix, "x0_m", x0_m);
    require_finite(prefix, "y0_m", y0_m);
    require_finite(prefix, "z0_m", z0_m);
    detail::require_positive(prefix, "radius_m", radius_m);
    detail::require(std::isfinite(omega_radps) && omega_radps != 0.0, prefix, "omega_radps",
                    omega_radps, "finite and != 0");
    require_finite(prefix, "v_z_mps", v_z_mps);
    require_finite(prefix, "yaw0_rad", yaw0_rad);
    detail::require_positive(prefix, "rotations", rotations);
}

HelixTrajectory::HelixTrajectory(const HelixTrajectoryConfig& config)
    : config_(config), orbit_(orbit_of(config_)) {}

}  // namespace scantling::sim
