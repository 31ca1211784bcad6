// The ROV's hull-survey stack: the command tick, the mission's states and the re-inspection
// (rov_stack.hpp).
#include <scantling/mission/rov_stack.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "detail/frames.hpp"

namespace scantling::mission {
namespace {

using control::MissionState;

/// A hole of the believed coverage in the re-inspection planner's terms.
planning::ReinspectionHole reinspection_hole(const perception::CoverageHole& hole,
                                             const perception::InspectionRectangle& r) {
    const Eigen::Vector3d c = hole.centroid_world;
    const Eigen::Vector2d c_uv((c - r.corner_world).dot(r.u_world),
                               (c - r.corner_world).dot(r.v_world));
    // The box of the hole's cell centres, grown by nothing: the pass reaches its ends with the
    // footprint's half width, and the centroid is a mean of the same centres, so it lies inside.
    const Eigen::Vector2d lo = (hole.min_uv_m - c_uv).cwiseMin(0.0);
    const Eigen::Vector2d hi = (hole.max_uv_m - c_uv).cwiseMax(0.0);
    return {.centroid_world_m = c,
            .axis_u_world = r.u_world,
            .axis_v_world = r.v_world,
            .box_min_u_m = lo.x(),
            .box_max_u_m = hi.x(),
            .box_min_v_m = lo.y(),
            .box_max_v_m = hi.y()};
}

}  // namespace

void RovStack::set_state(MissionState to, double t_s, std::string_view reason) {
    if (to == state_) return;
    event(
        t_s, std::string(control::to_string(control::MissionEventType::kStateChanged)),
        fmt::format(R"({{"from":"{}","to":"{}","reason":"{}","phase":"{}"}})",
                    control::to_string(state_), control::to_string(to), reason, to_string(phase_)));
    state_ = to;
}

void RovStack::apply_operator(const control::OperatorCommand& c, double t_s) {
    using Type = control::OperatorCommandType;
    const bool ended = state_ == MissionState::kCompleted || state_ == MissionState::kAborted;
    if (c.type == Type::kStart && state_ == MissionState::kIdle) {
        return set_state(MissionState::kRunning, t_s, "start");
    }
    if (c.type == Type::kPause && state_ == MissionState::kRunning) {
        return set_state(MissionState::kPaused, t_s, "operator pause");
    }
    if (c.type == Type::kResume && state_ == MissionState::kPaused) {
        return set_state(MissionState::kRunning, t_s, "operator resume");
    }
    if (c.type == Type::kAbort && !ended) return set_state(MissionState::kAborted, t_s, "abort");
    event(t_s, std::string(control::to_string(control::MissionEventType::kCommandRefused)),
          fmt::format(
              R"({{"command":"{}","state":"{}","reason":"{}"}})", control::to_string(c.type),
              control::to_string(state_),
              c.type == Type::kTakeOver || c.type == Type::kHandBack || c.type == Type::kGoHome
                  ? "not supported by the ROV stack"
                  : "not valid in this state"));
}

void RovStack::watch_dvl(double t_s) {
    const double since_s = t_s - last_dvl_lock_s_.value_or(start_s_);
    const bool lost = since_s > config_.max_dvl_age_s;
    if (lost == dvl_lost_) return;
    dvl_lost_ = lost;
    event(t_s, lost ? "sensor_lost" : "sensor_restored",
          lost ? fmt::format(R"({{"sensor":"dvl","silent_s":{:.2f},"reaction":"survey held"}})",
                             since_s)
               : std::string(R"({"sensor":"dvl"})"));
}

void RovStack::finish_path(double t_s) {
    const bool may_reinspect =
        static_cast<int>(counters_.reinspection_rounds) < config_.max_reinspection_rounds;
    std::vector<planning::ReinspectionHole> holes;
    double area_m2 = 0.0;
    if (may_reinspect) {
        for (const perception::CoverageHole& hole : coverage_.result().holes) {
            if (hole.area_m2 < config_.min_hole_area_m2) continue;
            holes.push_back(reinspection_hole(hole, inspected_));
            area_m2 += hole.area_m2;
        }
    }
    if (holes.empty()) {
        phase_ = SurveyPhase::kDone;
        return set_state(MissionState::kCompleted, t_s, "survey done");
    }
    const Eigen::Vector3d p_camera = T_world_body() * config_.T_body_camera.translation();
    planning::WaypointPath path = planning::plan_hole_reinspection(holes, inspected_.normal_world(),
                                                                   p_camera, config_.reinspection);
    for (planning::Waypoint& w : path.waypoints) {
        w.p_world_m.z() =
            std::clamp(w.p_world_m.z(), config_.min_waypoint_z_m, config_.max_waypoint_z_m);
    }
    adapter_ = planning::HullRelativeAdapter(std::move(path), config_.adapter);
    cursor_.restart(p_camera, detail::yaw_of(T_world_body().linear()));
    phase_ = SurveyPhase::kReinspection;
    ++counters_.reinspection_rounds;
    counters_.holes_found += holes.size();
    event(t_s, "reinspection_started",
          fmt::format(R"({{"round":{},"holes":{},"area_m2":{:.3f},"waypoints":{}}})",
                      counters_.reinspection_rounds, holes.size(), area_m2,
                      adapter_.path().waypoints.size()));
}

RovStackCommand RovStack::guide(double t_s, double dt_s) {
    RovStackCommand out;
    const Eigen::Isometry3d T = T_world_body();
    const Eigen::Vector3d p_camera = T * config_.T_body_camera.translation();
    const bool backing_off = contact_.backing_off(t_s);
    const bool hold =
        state_ != MissionState::kRunning || guidance_.paused() || dvl_lost_ || backing_off;
    const std::size_t before = cursor_.next_index();
    if (cursor_.advance(adapter_.path(), p_camera, dt_s, hold)) {
        event(t_s, std::string(control::to_string(control::MissionEventType::kWaypointReached)),
              fmt::format(R"({{"waypoint":{},"phase":"{}"}})", before, to_string(phase_)));
    }
    const control::GuidanceTarget target = cursor_.target(adapter_.path());
    const control::GuidanceCommand g =
        guidance_.update(p_camera, detail::yaw_of(T.linear()), target, dt_s);
    out.v_world_mps = g.v_world_mps;
    out.yaw_rate_radps = g.yaw_rate_radps;
    out.guidance_paused = g.paused;
    out.heading_error_rad = g.heading_error_rad;
    out.depth_error_m = g.depth_error_m;
    if (backing_off) {
        out.v_world_mps = contact_.back_off_velocity(t_s);
        out.backing_off = true;
    }
    if (state_ == MissionState::kRunning && cursor_.done(adapter_.path())) finish_path(t_s);
    return out;
}

RovStackCommand RovStack::command(double t_s, std::span<const control::OperatorCommand> commands) {
    for (const control::OperatorCommand& c : commands) apply_operator(c, t_s);
    const double dt_s = last_command_s_ ? t_s - *last_command_s_ : 0.0;
    last_command_s_ = t_s;
    RovStackCommand out;
    if (state_ == MissionState::kRunning || state_ == MissionState::kPaused) watch_dvl(t_s);
    const bool valid = estimate_valid(t_s);
    if (valid == estimate_lost_) {
        estimate_lost_ = !valid;
        event(t_s,
              std::string(control::to_string(valid ? control::MissionEventType::kSensorRestored
                                                   : control::MissionEventType::kEstimateInvalid)),
              valid ? R"({"sensor":"imu"})" : R"({"sensor":"imu","reaction":"stop"})");
    }
    const bool active = state_ != MissionState::kIdle && state_ != MissionState::kAborted;
    // Station keeping continues after completion (at the last target) and while paused.
    if (valid && active && dt_s > 0.0) out = guide(t_s, dt_s);
    out.state = state_;
    out.events = std::move(pending_);
    pending_.clear();
    return out;
}

}  // namespace scantling::mission
