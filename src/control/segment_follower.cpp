// The crawler's segment-frame path follower (segment_follower.hpp, SPEC §6).
#include <scantling/control/segment_follower.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include <scantling/core/angles.hpp>
#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::control {
namespace {

// Below this a segment has no direction, and a normal no component across it.
constexpr double kMinLengthM = 1e-6;

void refuse(std::string_view prefix, std::size_t index, std::string_view why) {
    throw ConfigError(fmt::format("{}.path[{}]: {}", prefix, index, why));
}

}  // namespace

void SegmentFollowerConfig::validate(std::string_view prefix) const {
    config_checks::require_positive(k_y_per_m_s, prefix, "k_y_per_m_s");
    config_checks::require_positive(k_yaw_per_s, prefix, "k_yaw_per_s");
    config_checks::require_positive(v_ref_mps, prefix, "v_ref_mps");
    config_checks::require_positive(omega0_radps, prefix, "omega0_radps");
    config_checks::require_positive(max_omega_radps, prefix, "max_omega_radps");
}

Eigen::Isometry3d segment_frame(const PathSegment& segment, std::size_t index,
                                std::string_view prefix) {
    if (!segment.begin_world_m.allFinite() || !segment.end_world_m.allFinite() ||
        !segment.normal_world.allFinite()) {
        refuse(prefix, index, "non-finite begin, end or normal, expected finite");
    }
    const Eigen::Vector3d along = segment.end_world_m - segment.begin_world_m;
    const double length_m = along.norm();
    if (length_m < kMinLengthM) {
        refuse(prefix, index,
               fmt::format("length = {} m, expected >= {} m", length_m, kMinLengthM));
    }
    const Eigen::Vector3d x = along / length_m;
    // The facet normal need not be given exactly ⟂ the segment: keep its part across it.
    const Eigen::Vector3d normal_across = segment.normal_world - segment.normal_world.dot(x) * x;
    if (normal_across.norm() < kMinLengthM) {  // the normal is unit by contract
        refuse(prefix, index,
               "normal_world is zero or parallel to the segment, expected across it");
    }
    const Eigen::Vector3d z = normal_across.normalized();
    Eigen::Isometry3d T_world_segment = Eigen::Isometry3d::Identity();
    T_world_segment.linear().col(0) = x;
    T_world_segment.linear().col(1) = z.cross(x);
    T_world_segment.linear().col(2) = z;
    T_world_segment.translation() = segment.begin_world_m;
    return T_world_segment;
}

SegmentFrameError segment_frame_error(const Eigen::Isometry3d& T_world_segment,
                                      const Eigen::Isometry3d& T_world_body) {
    const Eigen::Isometry3d T_segment_body = T_world_segment.inverse() * T_world_body;
    // Locally flat: keep the in-plane position and the heading of body x in the x-y plane.
    const Eigen::Vector3d x_body_in_segment = T_segment_body.linear().col(0);
    return {T_segment_body.translation().x(), T_segment_body.translation().y(),
            wrap_angle_rad(std::atan2(x_body_in_segment.y(), x_body_in_segment.x()))};
}

FollowerCommand segment_follower_law(const SegmentFrameError& error,
                                     const SegmentFollowerConfig& config) {
    // SPEC §6's ω = k_y y + k_yaw yaw with its k's = −ours: positive gains stabilise.
    const double omega_radps =
        std::clamp(-(config.k_y_per_m_s * error.y_m + config.k_yaw_per_s * error.yaw_rad),
                   -config.max_omega_radps, config.max_omega_radps);
    const double ratio = omega_radps / config.omega0_radps;
    FollowerCommand command;
    command.omega_radps = omega_radps;
    command.v_mps = config.v_ref_mps * std::exp(-ratio * ratio);
    command.error = error;
    return command;
}

SegmentFollower::SegmentFollower(std::vector<PathSegment> path, const SegmentFollowerConfig& config)
    : path_(std::move(path)), config_(config) {
    config_.validate();
    frames_.reserve(path_.size());
    lengths_m_.reserve(path_.size());
    for (std::size_t i = 0; i < path_.size(); ++i) {
        frames_.push_back(segment_frame(path_[i], i));
        lengths_m_.push_back((path_[i].end_world_m - path_[i].begin_world_m).norm());
    }
}

FollowerCommand SegmentFollower::update(const Eigen::Isometry3d& T_world_body) {
    if (!T_world_body.matrix().allFinite()) {
        throw InputError("segment_follower.T_world_body: non-finite pose, expected finite");
    }
    while (!done()) {
        const SegmentFrameError error = segment_frame_error(frames_[segment_], T_world_body);
        if (error.x_m <= lengths_m_[segment_]) {
            FollowerCommand command = segment_follower_law(error, config_);
            command.segment = segment_;
            return command;
        }
        ++segment_;  // SPEC §6: done once x > |E_i − B_i|
    }
    FollowerCommand command;
    command.segment = segment_;
    command.done = true;
    return command;
}

}  // namespace scantling::control
