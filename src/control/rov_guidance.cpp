#include <scantling/control/rov_guidance.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include <scantling/core/angles.hpp>
#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::control {

void RovGuidanceConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(max_approach_speed_mps, prefix, "max_approach_speed_mps");
    require_positive(transient_m, prefix, "transient_m");
    require_positive(max_speed_mps, prefix, "max_speed_mps");
    require_positive(yaw_gain_per_s, prefix, "yaw_gain_per_s");
    require_positive(max_yaw_rate_radps, prefix, "max_yaw_rate_radps");
    depth.validate(std::string(prefix) + ".depth");
    require_positive(max_heading_error_rad, prefix, "max_heading_error_rad");
    require_positive(max_depth_error_m, prefix, "max_depth_error_m");
    require(std::isfinite(resume_fraction) && resume_fraction > 0.0 && resume_fraction <= 1.0,
            prefix, "resume_fraction", resume_fraction, "in (0, 1]");
}

RovGuidance::RovGuidance(const RovGuidanceConfig& config)
    : config_((config.validate(), config)), depth_(config_.depth, "rov_guidance.depth") {}

void RovGuidance::reset() {
    depth_.reset();
    paused_ = false;
}

void RovGuidance::update_pause(double heading_error_rad, double depth_error_m) {
    const double h = std::abs(heading_error_rad), z = std::abs(depth_error_m);
    if (!paused_) {
        paused_ = h > config_.max_heading_error_rad || z > config_.max_depth_error_m;
        return;
    }
    const double f = config_.resume_fraction;
    paused_ = !(h < f * config_.max_heading_error_rad && z < f * config_.max_depth_error_m);
}

Eigen::Vector2d RovGuidance::horizontal(const Eigen::Vector3d& p_world_m,
                                        const GuidanceTarget& target) const {
    const Eigen::Vector2d error = p_world_m.head<2>() - target.p_world_m.head<2>();
    const double delta = config_.transient_m;
    const Eigen::Vector2d v_approach =
        -config_.max_approach_speed_mps * error / std::sqrt(error.squaredNorm() + delta * delta);
    Eigen::Vector2d v = (paused_ ? Eigen::Vector2d::Zero() : target.v_horizontal_mps) + v_approach;
    const double speed = v.norm();
    if (speed > config_.max_speed_mps) v *= config_.max_speed_mps / speed;
    return v;
}

GuidanceCommand RovGuidance::update(const Eigen::Vector3d& p_world_m, double yaw_rad,
                                    const GuidanceTarget& target, double dt_s) {
    if (!p_world_m.allFinite() || !std::isfinite(yaw_rad) || !target.p_world_m.allFinite() ||
        !target.v_horizontal_mps.allFinite() || !std::isfinite(target.v_vertical_mps) ||
        !std::isfinite(target.yaw_rad) || !std::isfinite(dt_s) || dt_s <= 0.0) {
        throw InputError(fmt::format(
            "rov_guidance.update: position ({}, {}, {}), yaw {}, target ({}, {}, {}) yaw {}, dt "
            "{} s: expected finite values and dt > 0",
            p_world_m.x(), p_world_m.y(), p_world_m.z(), yaw_rad, target.p_world_m.x(),
            target.p_world_m.y(), target.p_world_m.z(), target.yaw_rad, dt_s));
    }
    GuidanceCommand command;
    command.heading_error_rad = wrap_angle_rad(target.yaw_rad - yaw_rad);
    command.depth_error_m = target.p_world_m.z() - p_world_m.z();
    update_pause(command.heading_error_rad, command.depth_error_m);
    command.paused = paused_;
    command.v_world_mps.head<2>() = horizontal(p_world_m, target);
    command.v_world_mps.z() =
        std::clamp(target.v_vertical_mps + depth_.update(target.p_world_m.z(), p_world_m.z(), dt_s),
                   config_.depth.output_min, config_.depth.output_max);
    command.yaw_rate_radps = std::clamp(config_.yaw_gain_per_s * command.heading_error_rad,
                                        -config_.max_yaw_rate_radps, config_.max_yaw_rate_radps);
    return command;
}

}  // namespace scantling::control
