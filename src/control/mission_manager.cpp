#include <scantling/control/mission_manager.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/planning/recorded_points.hpp>

namespace scantling::control {
namespace {

using State = MissionState;
using Command = OperatorCommandType;

bool is_finite(const EstimatedState& estimate) {
    return estimate.p_world_m.allFinite() && std::isfinite(estimate.yaw_rad) &&
           estimate.v_world_mps.allFinite();
}

/// States whose command needs the position estimate (the failsafe watches only these).
bool needs_estimate(State state) {
    return state == State::kRunning || state == State::kPaused || state == State::kGoingHome ||
           state == State::kCompleted || state == State::kAborted;
}

/// Where hand back returns: a paused mission resumes (SPEC §4: the mission continues).
State after_hand_back(State taken_from) {
    return taken_from == State::kPaused ? State::kRunning : taken_from;
}

Eigen::Vector3d clamp_norm(const Eigen::Vector3d& v, double max_norm) {
    const double norm = v.norm();
    return norm > max_norm ? Eigen::Vector3d(v * (max_norm / norm)) : v;
}

}  // namespace

void MissionManagerConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    position_controller.validate(fmt::format("{}.position_controller", prefix));
    tracking.validate(fmt::format("{}.tracking", prefix));
    require_non_negative(estimate_timeout_s, prefix, "estimate_timeout_s");
    require_non_negative(home_height_offset_m, prefix, "home_height_offset_m");
    require_positive(home_tolerance_m, prefix, "home_tolerance_m");
}

MissionManager::MissionManager(planning::WaypointPath path, const MissionManagerConfig& config)
    : config_((config.validate(), config)),
      path_(std::move(path)),
      controller_(config.position_controller) {
    planning::validate(path_, "mission_manager.path");
}

std::size_t MissionManager::current_waypoint() const {
    return mission_ ? mission_->current_index() : 0;
}

MissionTick MissionManager::update(const EstimatedState& estimate, double t_s,
                                   std::span<const OperatorCommand> commands) {
    if (!std::isfinite(t_s) || (last_t_s_ && t_s <= *last_t_s_)) {
        throw InputError(fmt::format(
            "mission_manager.update: t_s = {}, expected finite and > the previous tick's", t_s));
    }
    const double dt_s = last_t_s_ ? t_s - *last_t_s_ : 0.0;
    last_t_s_ = t_s_ = t_s;
    MissionTick tick;
    const bool valid = track_estimate(estimate, tick);
    for (const OperatorCommand& command : commands) apply(command, tick);
    if (dt_s > 0.0 && (valid || state_ == State::kOperator)) {
        command_vehicle(estimate, dt_s, tick);
    } else if (dt_s > 0.0 && p_invalid_hold_world_m_ && estimate.holdable && is_finite(estimate) &&
               state_ != State::kIdle) {
        hold(estimate, *p_invalid_hold_world_m_, dt_s, tick);
    }
    replace_non_finite(tick);
    tick.state = state_;
    return tick;
}

bool MissionManager::track_estimate(const EstimatedState& estimate, MissionTick& tick) {
    if (estimate.valid && is_finite(estimate)) {
        invalid_since_t_s_.reset();
        p_invalid_hold_world_m_.reset();
        last_valid_p_world_m_ = estimate.p_world_m;
        return true;
    }
    const std::string why = estimate.valid ? "non-finite" : "marked invalid";
    if (!p_invalid_hold_world_m_ && estimate.holdable && is_finite(estimate)) {
        p_invalid_hold_world_m_ = estimate.p_world_m;  // where the hold starts, on the estimate
    }
    if (!invalid_since_t_s_) {
        invalid_since_t_s_ = t_s_;
        tick.events.push_back(
            event(MissionEventType::kEstimateInvalid, "estimate " + why + ": hovering"));
    }
    const double invalid_for_s = t_s_ - *invalid_since_t_s_;
    if (needs_estimate(state_) && invalid_for_s >= config_.estimate_timeout_s) {
        change_state(State::kFailsafe,
                     fmt::format("estimate {} for {:.2f} s (timeout {:.2f} s)", why, invalid_for_s,
                                 config_.estimate_timeout_s),
                     tick);
    }
    return false;
}

void MissionManager::apply(const OperatorCommand& command, MissionTick& tick) {
    switch (command.type) {
        case Command::kStart:
            return start(tick);
        case Command::kPause:
            return pause(tick);
        case Command::kResume:
            return resume(tick);
        case Command::kTakeOver:
            return take_over(command, tick);
        case Command::kHandBack:
            return hand_back(tick);
        case Command::kGoHome:
            return go_home(tick);
        case Command::kAbort:
            return abort(tick);
    }
}

MissionEvent MissionManager::event(MissionEventType type, std::string reason) const {
    return {.type = type, .t_s = t_s_, .from = state_, .to = state_, .reason = std::move(reason)};
}

void MissionManager::refuse(Command command, std::string reason, MissionTick& tick) const {
    MissionEvent& refused =
        tick.events.emplace_back(event(MissionEventType::kCommandRefused, std::move(reason)));
    refused.command = command;
}

void MissionManager::change_state(State to, std::string reason, MissionTick& tick) {
    tick.events.emplace_back(event(MissionEventType::kStateChanged, std::move(reason))).to = to;
    state_ = to;
    controller_.reset();  // the integrals and derivative history belong to the old target
}

void MissionManager::start(MissionTick& tick) {
    if (state_ != State::kIdle) {
        return refuse(Command::kStart, fmt::format("already started ({})", to_string(state_)),
                      tick);
    }
    if (!last_valid_p_world_m_) return refuse(Command::kStart, "no valid estimate yet", tick);
    home_world_m_ = *last_valid_p_world_m_;
    mission_.emplace(path_, *home_world_m_);
    change_state(State::kRunning,
                 fmt::format("start: {} waypoints, home recorded", path_.waypoints.size()), tick);
}

void MissionManager::pause(MissionTick& tick) {
    if (state_ != State::kRunning && state_ != State::kGoingHome) {
        return refuse(Command::kPause, fmt::format("nothing to pause in {}", to_string(state_)),
                      tick);
    }
    paused_from_ = state_;
    p_hold_world_m_ = *last_valid_p_world_m_;  // set: kRunning and kGoingHome need one
    change_state(State::kPaused, "pause: hovering in place", tick);
}

void MissionManager::resume(MissionTick& tick) {
    if (state_ != State::kPaused) {
        return refuse(Command::kResume, fmt::format("not paused ({})", to_string(state_)), tick);
    }
    change_state(paused_from_, "resume: back on the segment to the current waypoint", tick);
}

void MissionManager::take_over(const OperatorCommand& command, MissionTick& tick) {
    if (!command.v_world_mps.allFinite() || !std::isfinite(command.yaw_rate_radps)) {
        return refuse(Command::kTakeOver, "the operator's velocity is not finite", tick);
    }
    operator_command_ = command;
    if (state_ == State::kOperator) return;  // a new velocity from the operator
    taken_from_ = state_;
    change_state(State::kOperator, "take over: the operator's velocity passes through", tick);
}

void MissionManager::hand_back(MissionTick& tick) {
    if (state_ != State::kOperator) {
        return refuse(Command::kHandBack, fmt::format("not taken over ({})", to_string(state_)),
                      tick);
    }
    change_state(after_hand_back(taken_from_), "hand back: resuming", tick);
}

void MissionManager::go_home(MissionTick& tick) {
    if (state_ == State::kGoingHome || state_ == State::kFailsafe || state_ == State::kIdle) {
        return refuse(Command::kGoHome, fmt::format("cannot go home from {}", to_string(state_)),
                      tick);
    }
    if (!home_world_m_) return refuse(Command::kGoHome, "no home: never started", tick);
    const Eigen::Vector3d target =
        *home_world_m_ + config_.home_height_offset_m * Eigen::Vector3d::UnitZ();
    home_leg_.emplace(planning::plan_go_home(target, {config_.home_tolerance_m}),
                      *last_valid_p_world_m_);  // set: home is recorded from one
    change_state(State::kGoingHome, "go home: straight to the take-off point", tick);
}

void MissionManager::abort(MissionTick& tick) {
    if (state_ == State::kAborted || state_ == State::kFailsafe) {
        return refuse(Command::kAbort, fmt::format("already stopped ({})", to_string(state_)),
                      tick);
    }
    p_hold_world_m_ = last_valid_p_world_m_.value_or(Eigen::Vector3d::Zero());
    change_state(State::kAborted, "abort: hovering in place", tick);
}

WaypointSequencer* MissionManager::active_sequencer() {
    if (home_leg_) return &*home_leg_;
    return mission_ ? &*mission_ : nullptr;
}

void MissionManager::command_vehicle(const EstimatedState& estimate, double dt_s,
                                     MissionTick& tick) {
    const PositionControllerConfig& limits = config_.position_controller;
    switch (state_) {
        case State::kOperator:
            tick.v_cmd_world_mps = clamp_norm(operator_command_.v_world_mps, limits.max_speed_mps);
            tick.yaw_rate_cmd_radps =
                std::clamp(operator_command_.yaw_rate_radps, -limits.max_yaw_rate_radps,
                           limits.max_yaw_rate_radps);
            return;
        case State::kRunning:
        case State::kGoingHome:
        case State::kCompleted:
            return fly_sequence(estimate, dt_s, tick);
        case State::kPaused:
            return hold(estimate, p_hold_world_m_, dt_s, tick);
        case State::kAborted:  // aborted before the start: on the ground, nothing to hold
            if (home_world_m_) hold(estimate, p_hold_world_m_, dt_s, tick);
            return;
        case State::kIdle:
        case State::kFailsafe:
            return;  // zero velocity
    }
}

void MissionManager::fly_sequence(const EstimatedState& estimate, double dt_s, MissionTick& tick) {
    WaypointSequencer& sequencer = *active_sequencer();  // set once started
    report_reached(sequencer.update(estimate.p_world_m), tick);
    if (sequencer.finished() && state_ != State::kCompleted) {
        change_state(State::kCompleted,
                     home_leg_ ? std::string("home reached")
                               : fmt::format("all {} waypoints reached", path_.waypoints.size()),
                     tick);
    }
    const TrackingTarget target = sequencer.target(estimate.p_world_m, config_.tracking);
    const VelocityCommand command = controller_.update(
        estimate.p_world_m, estimate.yaw_rad, target.p_target_world_m, target.yaw_rad, dt_s);
    tick.v_cmd_world_mps = command.v_cmd_world_mps;
    tick.yaw_rate_cmd_radps = command.yaw_rate_cmd_radps;
}

void MissionManager::hold(const EstimatedState& estimate, const Eigen::Vector3d& p_hold_world_m,
                          double dt_s, MissionTick& tick) {
    const VelocityCommand command = controller_.update(estimate.p_world_m, estimate.yaw_rad,
                                                       p_hold_world_m, std::nullopt, dt_s);
    tick.v_cmd_world_mps = command.v_cmd_world_mps;
    tick.yaw_rate_cmd_radps = command.yaw_rate_cmd_radps;
}

void MissionManager::report_reached(const std::vector<std::size_t>& reached,
                                    MissionTick& tick) const {
    for (const std::size_t index : reached) {
        MissionEvent& event_reached = tick.events.emplace_back(
            event(MissionEventType::kWaypointReached,
                  home_leg_ ? "home reached" : fmt::format("waypoint {} reached", index)));
        event_reached.waypoint_index = index;
        event_reached.home_leg = home_leg_.has_value();
    }
}

void MissionManager::replace_non_finite(MissionTick& tick) const {
    if (tick.v_cmd_world_mps.allFinite() && std::isfinite(tick.yaw_rate_cmd_radps)) return;
    tick.v_cmd_world_mps.setZero();
    tick.yaw_rate_cmd_radps = 0.0;
    tick.events.push_back(
        event(MissionEventType::kCommandReplaced, "non-finite command replaced by zero velocity"));
}

std::string_view to_string(MissionState state) {
    static constexpr std::array<std::string_view, 8> kNames = {
        "idle", "running", "paused", "operator", "going_home", "completed", "aborted", "failsafe"};
    return kNames.at(static_cast<std::size_t>(state));
}

std::string_view to_string(OperatorCommandType command) {
    static constexpr std::array<std::string_view, 7> kNames = {
        "start", "pause", "resume", "take_over", "hand_back", "go_home", "abort"};
    return kNames.at(static_cast<std::size_t>(command));
}

std::string_view to_string(MissionEventType type) {
    static constexpr std::array<std::string_view, 8> kNames = {
        "state_changed",    "waypoint_reached", "command_refused", "estimate_invalid",
        "command_replaced", "sensor_lost",      "sensor_restored", "input_rejected"};
    return kNames.at(static_cast<std::size_t>(type));
}

}  // namespace scantling::control
