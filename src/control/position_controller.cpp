#include <scantling/control/position_controller.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::control {
namespace {

PidConfig axis_config(const PositionControllerConfig& config) {
    return {config.kp_per_s,       config.ki_per_s2,    config.kd_s, config.derivative_filter_s,
            -config.max_speed_mps, config.max_speed_mps};
}

void require_finite(const Eigen::Vector3d& v, std::string_view what) {
    if (!v.allFinite()) {
        throw InputError(
            fmt::format("position_controller.update: {} = ({}, {}, {}), expected finite", what,
                        v.x(), v.y(), v.z()));
    }
}

void require_finite(double value, std::string_view what) {
    if (!std::isfinite(value)) {
        throw InputError(
            fmt::format("position_controller.update: {} = {}, expected finite", what, value));
    }
}

}  // namespace

Eigen::Vector3d clamp_along_error(const Eigen::Vector3d& v_mps, const Eigen::Vector3d& error_m,
                                  double max_speed_mps) {
    const double error_norm = error_m.norm();
    if (!(error_norm > 1e-9)) return v_mps * (max_speed_mps / v_mps.norm());
    const Eigen::Vector3d along = error_m / error_norm;
    const Eigen::Vector3d v_along = along * along.dot(v_mps);
    const Eigen::Vector3d v_across = v_mps - v_along;
    const double across = v_across.norm();
    if (across >= max_speed_mps) return v_across * (max_speed_mps / across);
    const double room = std::sqrt(max_speed_mps * max_speed_mps - across * across);
    const double along_speed = v_along.norm();
    return v_across + (along_speed > room ? v_along * (room / along_speed) : v_along);
}

void PositionControllerConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_non_negative(kp_per_s, prefix, "kp_per_s");
    require_non_negative(ki_per_s2, prefix, "ki_per_s2");
    require_non_negative(kd_s, prefix, "kd_s");
    require_non_negative(derivative_filter_s, prefix, "derivative_filter_s");
    require_positive(max_speed_mps, prefix, "max_speed_mps");
    require_non_negative(yaw_gain_per_s, prefix, "yaw_gain_per_s");
    require_positive(max_yaw_rate_radps, prefix, "max_yaw_rate_radps");
}

PositionController::PositionController(const PositionControllerConfig& config)
    : config_((config.validate(), config)),
      axes_{{Pid(axis_config(config), "position_controller.x"),
             Pid(axis_config(config), "position_controller.y"),
             Pid(axis_config(config), "position_controller.z")}} {}

void PositionController::reset() {
    for (Pid& pid : axes_) pid.reset();
}

double wrap_angle_rad(double angle_rad) {
    const double two_pi = 2.0 * std::numbers::pi;
    const double wrapped = angle_rad - two_pi * std::floor(angle_rad / two_pi);  // [0, 2π)
    return wrapped > std::numbers::pi ? wrapped - two_pi : wrapped;
}

double PositionController::yaw_rate(double yaw_rad, std::optional<double> target_yaw_rad) const {
    if (!target_yaw_rad) return 0.0;
    const double rate = config_.yaw_gain_per_s * wrap_angle_rad(*target_yaw_rad - yaw_rad);
    return std::clamp(rate, -config_.max_yaw_rate_radps, config_.max_yaw_rate_radps);
}

VelocityCommand PositionController::update(const Eigen::Vector3d& p_world_m, double yaw_rad,
                                           const Eigen::Vector3d& p_target_world_m,
                                           std::optional<double> target_yaw_rad, double dt_s) {
    require_finite(p_world_m, "p_world_m");
    require_finite(p_target_world_m, "p_target_world_m");
    require_finite(yaw_rad, "yaw_rad");
    if (target_yaw_rad) require_finite(*target_yaw_rad, "target_yaw_rad");
    if (!(std::isfinite(dt_s) && dt_s > 0.0)) {
        throw InputError(
            fmt::format("position_controller.update: dt_s = {}, expected finite > 0", dt_s));
    }
    VelocityCommand command;
    Eigen::Vector3d integral_before;
    for (Eigen::Index i = 0; i < 3; ++i) {
        Pid& pid = axes_[static_cast<std::size_t>(i)];
        integral_before[i] = pid.integral();
        pid.update(p_target_world_m[i], p_world_m[i], dt_s);
        command.v_cmd_world_mps[i] = pid.last_terms().unsaturated;
    }
    if (command.v_cmd_world_mps.norm() > config_.max_speed_mps) {
        // Anti-windup on the vector clamp: no integration while it acts. Chasing a VTP δ ahead
        // keeps δ of along-track error, whose integral would otherwise wind up and, through
        // the clamp that keeps the cross-track part, push the vehicle off its line.
        for (Eigen::Index i = 0; i < 3; ++i) {
            Pid& pid = axes_[static_cast<std::size_t>(i)];
            command.v_cmd_world_mps[i] -= pid.integral() - integral_before[i];
            pid.restore_integral(integral_before[i]);
        }
        command.v_cmd_world_mps = clamp_along_error(
            command.v_cmd_world_mps, p_target_world_m - p_world_m, config_.max_speed_mps);
        command.speed_clamped = true;
    }
    command.yaw_rate_cmd_radps = yaw_rate(yaw_rad, target_yaw_rad);
    return command;
}

}  // namespace scantling::control
