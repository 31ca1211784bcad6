// The exploring drone's guidance (exploration_stack.hpp): the phases, the operator's commands,
// the next-best-view plans and the flight along each plan's first edge.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include <scantling/core/angles.hpp>
#include <scantling/mission/exploration_stack.hpp>

#include "detail/frames.hpp"

namespace scantling::mission {
namespace {

using control::MissionState;
using control::OperatorCommandType;

double yaw_of(const Eigen::Isometry3d& T) { return detail::yaw_of(T.linear()); }

/// The period the controllers integrate over: the time since the previous command, or one
/// nominal tick for the first.
double step_s(std::optional<double> last_s, double t_s) {
    constexpr double kFirstStep_s = 0.02;
    if (!last_s || t_s <= *last_s) return kFirstStep_s;
    return t_s - *last_s;
}

/// E of the goal: the root's child at the best branch's first state.
double first_node_gain(const planning::NbvPlan& plan) {
    for (const planning::NbvNode& n : plan.tree) {
        if (n.parent == 0 && n.state.p_world_m == plan.next_goal.p_world_m) return n.unknown_m3;
    }
    return 0.0;
}

}  // namespace

const char* to_string(planning::NbvStatus status) {
    switch (status) {
        case planning::NbvStatus::kOk:
            return "ok";
        case planning::NbvStatus::kExhausted:
            return "exhausted";
        case planning::NbvStatus::kStartNotFree:
            return "start_not_free";
        case planning::NbvStatus::kNoFreeEdge:
            return "no_free_edge";
    }
    return "unknown";
}

void ExplorationStack::set_phase(ExplorationPhase phase, double t_s, const std::string& reason) {
    pending_events_.push_back({.t_s = t_s,
                               .type = "phase",
                               .json = fmt::format(R"({{"from":"{}","to":"{}","reason":"{}"}})",
                                                   to_string(phase_), to_string(phase), reason)});
    phase_ = phase;
}

void ExplorationStack::set_state(MissionState state, double t_s, const std::string& reason) {
    if (state == state_) return;
    pending_events_.push_back(
        {.t_s = t_s,
         .type = "state_changed",
         .json = fmt::format(R"({{"from":"{}","to":"{}","reason":"{}"}})",
                             control::to_string(state_), control::to_string(state), reason)});
    state_ = state;
}

void ExplorationStack::apply_operator(const control::OperatorCommand& command, double t_s) {
    const Eigen::Isometry3d T = T_world_body_estimate();
    const bool ended = state_ == MissionState::kCompleted || state_ == MissionState::kAborted;
    switch (command.type) {
        case OperatorCommandType::kStart:
            if (state_ == MissionState::kIdle) set_state(MissionState::kRunning, t_s, "start");
            return;
        case OperatorCommandType::kPause:
        case OperatorCommandType::kGoHome:  // hover: the way home is the operator's
            if (ended) return;
            p_hold_world_m_ = T.translation();
            yaw_hold_rad_ = yaw_of(T);
            set_state(MissionState::kPaused, t_s, std::string(control::to_string(command.type)));
            return;
        case OperatorCommandType::kResume:
        case OperatorCommandType::kHandBack:
            if (state_ == MissionState::kPaused || state_ == MissionState::kOperator) {
                goal_set_s_ = t_s;  // the goal's timeout restarts
                set_state(MissionState::kRunning, t_s, std::string(to_string(command.type)));
            }
            return;
        case OperatorCommandType::kTakeOver:
            if (!ended) set_state(MissionState::kOperator, t_s, "take_over");
            p_hold_world_m_ = T.translation();
            yaw_hold_rad_ = yaw_of(T);
            operator_velocity_ = command.v_world_mps;
            return;
        case OperatorCommandType::kAbort:
            p_hold_world_m_ = T.translation();
            yaw_hold_rad_ = yaw_of(T);
            set_state(MissionState::kAborted, t_s, "abort");
            return;
    }
}

ExplorationCommand ExplorationStack::command(
    double t_s, std::span<const control::OperatorCommand> operator_commands) {
    ExplorationCommand out;
    for (const control::OperatorCommand& c : operator_commands) apply_operator(c, t_s);
    if (state_ == MissionState::kRunning) {
        guide(t_s, out);
    } else if (state_ == MissionState::kOperator) {
        out.v_requested_world_mps = operator_velocity_;  // under the collision prevention too
        out.v_world_mps = safe_velocity(operator_velocity_, out);
    } else {
        hold(t_s, out);
    }
    last_command_s_ = t_s;
    out.state = state_;
    out.events = std::move(pending_events_);
    pending_events_.clear();
    return out;
}

void ExplorationStack::guide(double t_s, ExplorationCommand& out) {
    switch (phase_) {
        case ExplorationPhase::kTakeOff:
            return take_off(t_s, out);
        case ExplorationPhase::kSurvey:
            return survey(t_s, out);
        case ExplorationPhase::kExplore:
            return explore(t_s, out);
        case ExplorationPhase::kDone:
            return hold(t_s, out);
    }
}

void ExplorationStack::hold(double t_s, ExplorationCommand& out) {
    steer(p_hold_world_m_, yaw_hold_rad_, t_s, out);
}

void ExplorationStack::steer(const Eigen::Vector3d& target, std::optional<double> yaw, double t_s,
                             ExplorationCommand& out, double horizontal_scale) {
    const Eigen::Isometry3d T = T_world_body_estimate();
    const control::VelocityCommand c =
        controller_.update(T.translation(), yaw_of(T), target, yaw, step_s(last_command_s_, t_s));
    out.v_requested_world_mps = c.v_cmd_world_mps;
    out.v_requested_world_mps.head<2>() *= horizontal_scale;
    out.v_world_mps = safe_velocity(out.v_requested_world_mps, out);
    out.yaw_rate_radps = c.yaw_rate_cmd_radps;
}

void ExplorationStack::take_off(double t_s, ExplorationCommand& out) {
    const Eigen::Vector3d target =
        p_start_world_m_ + Eigen::Vector3d(0.0, 0.0, config_.takeoff_height_m);
    steer(target, yaw_hold_rad_, t_s, out);
    if ((T_world_body_estimate().translation() - target).norm() > config_.goal_tolerance_m) return;
    p_hold_world_m_ = target;
    set_phase(ExplorationPhase::kSurvey, t_s, "take-off height reached");
}

void ExplorationStack::survey(double t_s, ExplorationCommand& out) {
    const double yaw = yaw_of(T_world_body_estimate());
    if (!survey_start_yaw_rad_) {
        survey_start_yaw_rad_ = yaw;
        survey_last_yaw_rad_ = yaw;
    }
    survey_turned_rad_ += std::abs(wrap_angle_rad(yaw - survey_last_yaw_rad_));
    survey_last_yaw_rad_ = yaw;
    steer(p_hold_world_m_, std::nullopt, t_s, out);
    out.yaw_rate_radps = config_.max_yaw_rate_radps;
    if (survey_turned_rad_ < 2.0 * std::numbers::pi) return;
    yaw_hold_rad_ = yaw;
    clear_vehicle_box(config_.takeoff_clearance_m);
    set_phase(ExplorationPhase::kExplore, t_s, "the space around the vehicle is mapped");
}

bool ExplorationStack::goal_reached(double t_s) const {
    if (!goal_world_m_) return true;
    if (t_s - goal_set_s_ > config_.goal_timeout_s) return true;
    const Eigen::Isometry3d T = T_world_body_estimate();
    const bool at = (T.translation() - *goal_world_m_).norm() <= config_.goal_tolerance_m;
    const bool facing = !goal_yaw_rad_ || std::abs(wrap_angle_rad(yaw_of(T) - *goal_yaw_rad_)) <=
                                              config_.yaw_tolerance_rad;
    return at && facing;
}

bool ExplorationStack::depth_fresh(double t_s) {
    // Never a frame: as old as the mission.
    const double age_s = t_s - latest_depth_stamp_s_.value_or(0.0);
    if (age_s <= config_.max_depth_age_s) {
        if (depth_lost_) {
            pending_events_.push_back(
                {.t_s = t_s, .type = "sensor_restored", .json = R"({"sensor":"depth_camera"})"});
        }
        depth_lost_ = false;
        return true;
    }
    if (!depth_lost_) {
        depth_lost_ = true;
        goal_world_m_.reset();
        p_hold_world_m_ = T_world_body_estimate().translation();
        pending_events_.push_back(
            {.t_s = t_s,
             .type = "sensor_lost",
             .json = fmt::format(R"({{"sensor":"depth_camera","age_s":{:.2f}}})", age_s)});
    }
    if (age_s > config_.depth_lost_abort_s) {
        set_phase(ExplorationPhase::kDone, t_s, "no depth frames");
        set_state(MissionState::kAborted, t_s, "the depth camera is silent");
    }
    return false;
}

void ExplorationStack::explore(double t_s, ExplorationCommand& out) {
    if (!depth_fresh(t_s)) return hold(t_s, out);
    if (goal_reached(t_s) && t_s >= next_plan_s_) plan_next(t_s);
    if (phase_ != ExplorationPhase::kExplore) return hold(t_s, out);
    if (!goal_world_m_) return hold(t_s, out);
    fly_to_goal(t_s, out);
}

void ExplorationStack::fly_to_goal(double t_s, ExplorationCommand& out) {
    const Eigen::Isometry3d T = T_world_body_estimate();
    const control::VtpResult vtp = control::virtual_target_point(
        T.translation(), leg_start_world_m_, *goal_world_m_, config_.goal_tolerance_m, config_.vtp);
    const Eigen::Vector2d ahead = (*goal_world_m_ - T.translation()).head<2>();
    if (ahead.norm() <= config_.goal_tolerance_m)
        return steer(vtp.vtp_world_m, goal_yaw_rad_, t_s, out);
    // Face the way first, then fly: the camera, and so the collision prevention, sees only
    // ahead. Sideways along an edge the drone flew into space its camera had not seen for
    // seconds (seed 2: through the side shell, on an estimate 0.65 m off). The node's own
    // heading is taken at the goal.
    const double travel_yaw = std::atan2(ahead.y(), ahead.x());
    const double error = std::abs(wrap_angle_rad(travel_yaw - yaw_of(T)));
    const double scale = error > config_.max_travel_heading_error_rad ? 0.0 : std::cos(error);
    steer(vtp.vtp_world_m, travel_yaw, t_s, out, scale);
}

std::vector<Eigen::Vector3d> ExplorationStack::interest_points() const {
    std::vector<Eigen::Vector3d> points;
    for (const localization::MappedDefect& d : defect_map_.defects()) {
        points.push_back(d.position_world);
    }
    return points;
}

void ExplorationStack::plan_next(double t_s) {
    const Eigen::Isometry3d T = T_world_body_estimate();
    clear_vehicle_box(config_.self_clearance_m);
    const auto start = std::chrono::steady_clock::now();
    const std::vector<Eigen::Vector3d> interest = interest_points();
    const planning::NbvPlan plan =
        (exhausted_plans_in_row_ > 0 ? wide_planner_ : planner_)
            .plan(map_, {.p_world_m = T.translation(), .yaw_rad = yaw_of(T)}, interest);
    PlanRecord record{
        .t_s = t_s,
        .wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
        .nodes = plan.tree.size(),
        .best_gain = plan.best_value,
        .first_gain = 0.0,
        .status = plan.status,
        .gain_evaluations = plan.stats.gain_evaluations};
    on_plan(plan, record, t_s);
    plans_.push_back(record);
}

void ExplorationStack::back_track(double t_s) {
    constexpr double kRetry_s = 1.0;  // a new depth frame or two before trying again
    const Eigen::Isometry3d T = T_world_body_estimate();
    next_plan_s_ = t_s + kRetry_s;
    // Back along the way the vehicle came, one plan's start at a time: each was in known free
    // space with a free edge out of it when it was planned; here the map (or the estimate,
    // which drifts) has moved since.
    while (!plan_roots_.empty() &&
           (plan_roots_.back() - T.translation()).norm() <= config_.goal_tolerance_m) {
        plan_roots_.pop_back();
    }
    if (phase_ == ExplorationPhase::kExplore && !plan_roots_.empty()) {
        const Eigen::Vector3d back = plan_roots_.back();
        plan_roots_.pop_back();
        leg_start_world_m_ = T.translation();
        goal_world_m_ = back;
        goal_yaw_rad_.reset();
        goal_set_s_ = t_s;
        pending_events_.push_back({.t_s = t_s,
                                   .type = "back_track",
                                   .json = fmt::format(R"({{"goal":[{:.3f},{:.3f},{:.3f}]}})",
                                                       back.x(), back.y(), back.z())});
        return;
    }
    goal_world_m_.reset();
    p_hold_world_m_ = T.translation();  // hover here, never back to an old hold point
    yaw_hold_rad_ = yaw_of(T);
}

void ExplorationStack::on_plan(const planning::NbvPlan& plan, PlanRecord& record, double t_s) {
    if (plan.status == planning::NbvStatus::kExhausted &&
        ++exhausted_plans_in_row_ < config_.exhausted_plans_to_finish) {
        goal_world_m_.reset();  // another tree at the next tick, hovering here
        p_hold_world_m_ = T_world_body_estimate().translation();
        return;
    }
    if (plan.status == planning::NbvStatus::kExhausted) {
        goal_world_m_.reset();
        p_hold_world_m_ = T_world_body_estimate().translation();
        no_gain_left_ = true;
        set_phase(ExplorationPhase::kDone, t_s, "no gain left");
        set_state(MissionState::kCompleted, t_s, "exploration done");
        return;
    }
    if (plan.status != planning::NbvStatus::kOk || plan.branch.empty()) {
        pending_events_.push_back(
            {.t_s = t_s,
             .type = "plan_failed",
             .json =
                 nlohmann::json{{"status", to_string(plan.status)}, {"message", plan.message}}.dump(
                     -1, ' ', false, nlohmann::json::error_handler_t::replace)});
        if (++failed_plans_in_row_ >= config_.max_failed_plans) {
            set_phase(ExplorationPhase::kDone, t_s, "no plan after backing off");
            set_state(MissionState::kCompleted, t_s, "exploration stopped: no free edge");
        }
        return back_track(t_s);
    }
    failed_plans_in_row_ = 0;
    exhausted_plans_in_row_ = 0;
    const planning::NbvState& first = plan.next_goal;
    record.first_gain = first_node_gain(plan);
    leg_start_world_m_ = T_world_body_estimate().translation();
    plan_roots_.push_back(leg_start_world_m_);
    goal_world_m_ = first.p_world_m;
    goal_yaw_rad_ = first.yaw_rad;
    goal_set_s_ = t_s;
    goals_.push_back(first.p_world_m);
    pending_events_.push_back(
        {.t_s = t_s,
         .type = "nbv_planned",
         .json = fmt::format(
             R"({{"nodes":{},"best_gain":{:.4f},"goal_gain_m3":{:.4f},"goal":[{:.3f},{:.3f},{:.3f}],"goal_yaw_rad":{:.3f},"plan_s":{:.4f}}})",
             record.nodes, record.best_gain, record.first_gain, first.p_world_m.x(),
             first.p_world_m.y(), first.p_world_m.z(), first.yaw_rad, record.wall_s)});
}

}  // namespace scantling::mission
