// The magnetic crawler's stack (crawler_stack.hpp).
#include <scantling/mission/crawler_stack.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::mission {
namespace {

using control::MissionState;
using control::OperatorCommandType;

}  // namespace

void CrawlerStackConfig::validate(std::string_view prefix) const {
    particle_filter.validate(std::string(prefix) + ".particle_filter");
    follower.validate(std::string(prefix) + ".follower");
    walk.validate(std::string(prefix) + ".walk");
    config_checks::require_positive(max_wheel_age_s, prefix, "max_wheel_age_s");
    config_checks::require_non_negative(gyro_calibration_s, prefix, "gyro_calibration_s");
    config_checks::require_positive(max_uwb_age_s, prefix, "max_uwb_age_s");
    config_checks::require_positive(max_position_sigma_m, prefix, "max_position_sigma_m");
    config_checks::require_non_negative(anchor_hidden_margin_m, prefix, "anchor_hidden_margin_m");
    config_checks::require_non_negative(obstacle_slow_distance_m, prefix,
                                        "obstacle_slow_distance_m");
    config_checks::require_non_negative(obstacle_stop_distance_m, prefix,
                                        "obstacle_stop_distance_m");
    if (obstacle_slow_distance_m > 0.0 && obstacle_slow_distance_m <= obstacle_stop_distance_m) {
        config_checks::require(false, prefix, "obstacle_slow_distance_m", obstacle_slow_distance_m,
                               "0 (off) or > obstacle_stop_distance_m");
    }
    config_checks::require_positive(corridor_half_width_m, prefix, "corridor_half_width_m");
    detour.validate(std::string(prefix) + ".detour");
    config_checks::require_non_negative(stop_spacing_m, prefix, "stop_spacing_m");
    config_checks::require_non_negative(stop_settle_s, prefix, "stop_settle_s");
    config_checks::require(std::isfinite(stop_duration_s) && stop_duration_s > stop_settle_s,
                           prefix, "stop_duration_s", stop_duration_s,
                           "finite and > stop_settle_s");
    stop_and_map.validate(std::string(prefix) + ".stop_and_map");
    corridor.validate(std::string(prefix) + ".corridor");
    config_checks::require_non_negative(corridor_join_m, prefix, "corridor_join_m");
    if (texture.enabled) texture.map.validate("texture_map");
}

CrawlerStack::CrawlerStack(const CrawlerStackConfig& config, const SurfaceProjector& surface,
                           const TriangleMesh* mesh, std::vector<planning::SurfaceTask> tasks,
                           const Eigen::Isometry3d& T_world_body_start, std::uint64_t seed)
    : config_((config.validate(), config)),
      filter_(config_.particle_filter, surface, T_world_body_start, seed),
      surface_(surface),
      mesh_(mesh),
      tasks_(std::move(tasks)) {
    if (tasks_.empty()) throw InputError("mission.tasks: a mission needs a task");
    check_tasks(T_world_body_start.translation());
    if (config_.T_body_lidar) mapper_.emplace(config_.stop_and_map, *config_.T_body_lidar);
    if (config_.texture.enabled && config_.T_body_camera) texture_.emplace(config_.texture.map);
}

bool CrawlerStack::screen(bool finite, const std::string& sensor, double stamp_s) {
    const auto it = std::find(rejecting_.begin(), rejecting_.end(), sensor);
    if (finite) {
        if (it != rejecting_.end()) rejecting_.erase(it);
        return true;
    }
    ++inputs_rejected_;
    if (it == rejecting_.end()) {
        rejecting_.push_back(sensor);
        pending_.push_back({std::isfinite(stamp_s) ? stamp_s : start_s_, "input_rejected",
                            fmt::format(R"({{"sensor":"{}","reason":"a sample with )"
                                        R"(non-finite values was dropped before the filter"}})",
                                        sensor)});
    }
    return false;
}

void CrawlerStack::add_imu(const io::ImuRecord& sample) {
    const bool finite = std::isfinite(sample.stamp_s) && sample.specific_force_mps2.allFinite() &&
                        sample.angular_rate_radps.allFinite();
    if (!screen(finite, "imu", sample.stamp_s)) return;
    if (!gyro_bias_radps_) {
        // Standing still: the rate is the bias (no turn is given before the calibration ends).
        if (started_s_ && config_.gyro_calibration_s > 0.0) {
            gyro_sum_radps_ += sample.angular_rate_radps;
            ++gyro_samples_;
        }
        return;
    }
    io::ImuRecord corrected = sample;
    corrected.angular_rate_radps -= *gyro_bias_radps_;
    filter_.add_imu(corrected);
}

bool CrawlerStack::calibrating(double t_s, std::vector<StackEvent>& events) {
    if (gyro_bias_radps_) return false;
    if (!started_s_) started_s_ = t_s;
    if (t_s - *started_s_ < config_.gyro_calibration_s) return true;
    gyro_bias_radps_ = gyro_samples_ > 0 ? Eigen::Vector3d(gyro_sum_radps_ / gyro_samples_)
                                         : Eigen::Vector3d::Zero();
    if (config_.gyro_calibration_s <= 0.0) return false;  // off: no bias taken, nothing to say
    const Eigen::Vector3d& b = *gyro_bias_radps_;
    events.push_back({t_s, "gyro_calibrated",
                      fmt::format(R"({{"bias_radps":[{:.6f},{:.6f},{:.6f}],"samples":{}}})", b.x(),
                                  b.y(), b.z(), gyro_samples_)});
    return false;
}

void CrawlerStack::add_wheel_odometry(const io::WheelOdometryRecord& sample) {
    const bool finite = std::isfinite(sample.stamp_s) && std::isfinite(sample.forward_speed_mps) &&
                        std::isfinite(sample.yaw_rate_radps);
    if (!screen(finite, "wheel_odometry", sample.stamp_s)) return;
    filter_.add_wheel_odometry(sample);
    last_wheel_s_ = sample.stamp_s;
}

void CrawlerStack::add_uwb(const io::UwbRecord& range) {
    // An invalid record (no reply from that anchor) carries no range: it is not a bad sample.
    if (!range.valid) return;
    const bool finite = std::isfinite(range.stamp_s) && std::isfinite(range.range_m);
    if (!screen(finite, "uwb", range.stamp_s)) return;
    if (anchor_hidden(range)) return;
    const localization::UpdateResult result = filter_.update_uwb(range);
    if (result.status == localization::UpdateStatus::kApplied) last_uwb_s_ = range.stamp_s;
}

bool CrawlerStack::anchor_hidden(const io::UwbRecord& range) {
    const auto& anchors = config_.particle_filter.uwb_anchors_world_m;
    const auto anchor = anchors.find(range.anchor_id);
    if (anchor == anchors.end()) return false;  // the filter refuses and counts it
    const Eigen::Isometry3d T = filter_.estimate().T_world_body;
    const double in_front_m = (anchor->second - T.translation()).dot(T.linear().col(2));
    const bool hidden = in_front_m < -config_.anchor_hidden_margin_m;
    const auto it = std::find(hidden_anchors_.begin(), hidden_anchors_.end(), range.anchor_id);
    if (hidden && it == hidden_anchors_.end()) {
        hidden_anchors_.push_back(range.anchor_id);
        pending_.push_back(
            {range.stamp_s, "uwb_anchor_hidden",
             fmt::format(R"({{"anchor":{},"behind_m":{:.2f},"reason":"the anchor is behind the )"
                         R"(surface: its ranges are dropped"}})",
                         range.anchor_id, -in_front_m)});
    } else if (!hidden && it != hidden_anchors_.end()) {
        hidden_anchors_.erase(it);
    }
    return hidden;
}

void CrawlerStack::watch_uwb(double t_s, std::vector<StackEvent>& events) {
    if (config_.particle_filter.uwb_anchors_world_m.empty()) return;
    const double age_s = t_s - last_uwb_s_.value_or(start_s_);
    const bool lost = age_s > config_.max_uwb_age_s;
    if (lost == uwb_lost_) return;
    uwb_lost_ = lost;
    events.push_back({t_s, lost ? "sensor_lost" : "sensor_restored",
                      lost
                          ? fmt::format(R"({{"sensor":"uwb","reason":"no range for {:.1f} s: dead )"
                                        R"(reckoning on the IMU and the wheels"}})",
                                        age_s)
                          : std::string(R"({"sensor":"uwb","reason":"ranges again"})")});
}

bool CrawlerStack::estimate_usable(double t_s, std::vector<StackEvent>& events) {
    const double sigma_m = std::sqrt(filter_.estimate().position_covariance_m2.trace());
    const bool invalid = !(sigma_m <= config_.max_position_sigma_m);
    if (invalid != estimate_invalid_) {
        estimate_invalid_ = invalid;
        events.push_back({t_s, invalid ? "estimate_invalid" : "estimate_valid",
                          fmt::format(R"({{"sigma_m":{:.3f},"reason":"{}"}})", sigma_m,
                                      invalid ? "position too uncertain: standing still"
                                              : "position certain again: going on")});
    }
    return !invalid;
}

void CrawlerStack::change_state(MissionState to, const std::string& reason, double t_s,
                                std::vector<StackEvent>& events) {
    events.push_back({t_s, "state_changed",
                      fmt::format(R"({{"from":"{}","to":"{}","reason":"{}"}})",
                                  control::to_string(state_), control::to_string(to), reason)});
    state_ = to;
}

void CrawlerStack::apply(const control::OperatorCommand& command, double t_s,
                         std::vector<StackEvent>& events) {
    const auto refuse = [&](const std::string& why) {
        events.push_back({t_s, "command_refused",
                          fmt::format(R"({{"command":"{}","reason":"{}"}})",
                                      control::to_string(command.type), why)});
    };
    switch (command.type) {
        case OperatorCommandType::kStart:
            if (state_ != MissionState::kIdle) return refuse("already started");
            return change_state(MissionState::kRunning,
                                fmt::format("start: {} tasks", tasks_.size()), t_s, events);
        case OperatorCommandType::kPause:
            if (state_ != MissionState::kRunning) return refuse("not running");
            return change_state(MissionState::kPaused, "pause: standing still", t_s, events);
        case OperatorCommandType::kResume:
            if (state_ != MissionState::kPaused) return refuse("not paused");
            if (task_failed_) {  // the operator goes on with the rest of the mission
                task_failed_ = false;
                ++tasks_skipped_;
            }
            if (blocking_) {  // the operator judged the obstacle passable
                cleared_world_m_.push_back(obstacles_.at(*blocking_).centroid_world_m);
                blocking_.reset();
            }
            return change_state(MissionState::kRunning, "resume", t_s, events);
        case OperatorCommandType::kAbort:
            if (state_ == MissionState::kAborted) return refuse("already aborted");
            return change_state(MissionState::kAborted, "abort: standing still", t_s, events);
        default:
            return refuse("the crawler takes start, pause, resume and abort");
    }
}

void CrawlerStack::watch_wheels(double t_s, std::vector<StackEvent>& events) {
    const double age_s = t_s - last_wheel_s_.value_or(start_s_);
    const bool lost = age_s > config_.max_wheel_age_s;
    if (lost == wheels_lost_) return;
    wheels_lost_ = lost;
    events.push_back(
        {t_s, lost ? "sensor_lost" : "sensor_restored",
         fmt::format(R"({{"sensor":"wheel_odometry","reason":"no sample for {:.3f} s"}})", age_s)});
}

void CrawlerStack::follow(CrawlerStackCommand& out, double t_s) {
    const Eigen::Isometry3d T_world_body = filter_.estimate().T_world_body;
    while (leg_ < legs_.size() || next_task(out, t_s)) {
        if (!follower_) follower_.emplace(legs_[leg_].segments, config_.follower);
        const control::FollowerCommand c = follower_->update(T_world_body);
        if (!c.done) {
            out.forward_mps = c.v_mps;
            out.yaw_rate_radps = c.omega_radps;
            out.error = c.error;
            return;
        }
        out.events.push_back(
            {t_s, "waypoint_reached",
             fmt::format(R"({{"waypoint":{},"reason":"waypoint {} reached"}})", leg_, leg_)});
        follower_.reset();
        passing_world_m_.clear();
        ++leg_;
        // Map at the waypoint before the next leg; not where a stiffener drive joins its
        // corridor, measured a moment ago (its stops re-measure it every stop_spacing_m).
        const bool joined_corridor = corridor_leg_ && leg_ == *corridor_leg_;
        if (mapper_ && !joined_corridor && (leg_ < legs_.size() || task_ < tasks_.size())) {
            stop_due_ = true;
            return;
        }
    }
}

CrawlerStackCommand CrawlerStack::command(
    double t_s, std::span<const control::OperatorCommand> operator_commands) {
    CrawlerStackCommand out;
    out.events = std::move(pending_);
    pending_.clear();
    for (const control::OperatorCommand& c : operator_commands) apply(c, t_s, out.events);
    watch_wheels(t_s, out.events);
    watch_uwb(t_s, out.events);
    const bool usable = estimate_usable(t_s, out.events);
    const bool moving_allowed = state_ == MissionState::kRunning && !wheels_lost_ && usable;
    if (moving_allowed && !calibrating(t_s, out.events) && !stopped_to_map(out, t_s)) {
        follow(out, t_s);
        if (state_ == MissionState::kRunning) slow_for_obstacles(out, t_s);
        count_distance();
    }
    if (!std::isfinite(out.forward_mps) || !std::isfinite(out.yaw_rate_radps)) {
        out.forward_mps = 0.0;  // the follower's inputs are screened; never pass a NaN on
        out.yaw_rate_radps = 0.0;
    }
    out.state = state_;
    out.leg = leg_;
    return out;
}

}  // namespace scantling::mission
