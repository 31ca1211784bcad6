// The crawler stack's tasks: laid when they begin, the stiffener drives on a stop's corridor
// (crawler_stack.hpp).
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/mission/crawler_stack.hpp>

namespace scantling::mission {
namespace {

/// What bounds each stiffener drive's face (perception::CorridorBounds).
perception::CorridorBounds bounds_of(planning::SurfaceTaskType type) {
    switch (type) {
        case planning::SurfaceTaskType::kDriveBetweenStiffeners:
            return perception::CorridorBounds::kWalls;  // the two webs
        case planning::SurfaceTaskType::kDriveOnStiffener:
            return perception::CorridorBounds::kEdges;  // the flange's edges
        case planning::SurfaceTaskType::kDriveOnStiffenerSide:
            return perception::CorridorBounds::kWallAndEdge;  // the plate, the web's top
        default:
            return perception::CorridorBounds::kAny;
    }
}

}  // namespace

std::string CrawlerStack::task_name(std::size_t i) const {
    return fmt::format("mission.tasks[{}] ({})", i, planning::to_string(tasks_.at(i).type));
}

void CrawlerStack::check_tasks(const Eigen::Vector3d& p_start_world_m) const {
    Eigen::Vector3d p = p_start_world_m;
    for (std::size_t i = 0; i < tasks_.size(); ++i) {
        const planning::SurfaceTask& task = tasks_[i];
        task.validate(task_name(i));
        if (task.needs_corridor()) {
            if (!config_.T_body_lidar) {
                throw InputError(fmt::format(
                    "{}: the stiffener's geometry comes from the LiDAR, and none is mounted",
                    task_name(i)));
            }
            continue;  // laid at run time; the next tasks start from where it ends, unknown
        }
        try {
            const planning::TaskPlan plan =
                planning::lay_surface_task(task, surface_, mesh_, p, config_.walk, task_name(i));
            if (!plan.waypoints_world_m.empty()) p = plan.waypoints_world_m.back();
        } catch (const InputError& e) {
            // The rectangle's planner names its own fields ("surface_rectangle.width_m ..."):
            // say which task; the transects' and go-to's messages name it already.
            const std::string what = e.what();
            if (what.rfind(task_name(i), 0) == 0) throw;
            throw InputError(fmt::format("{}: {}", task_name(i), what));
        }
    }
}

void CrawlerStack::add_plan(const planning::TaskPlan& plan) {
    legs_.insert(legs_.end(), plan.legs.begin(), plan.legs.end());
    ++legs_revision_;
    waypoints_.insert(waypoints_.end(), plan.waypoints_world_m.begin(),
                      plan.waypoints_world_m.end());
    if (plan.transects > 0 && transects_ == 0) {
        transects_ = plan.transects;
        step_m_ = plan.step_m;
    }
}

void CrawlerStack::fail_task(const std::string& reason, double t_s,
                             std::vector<StackEvent>& events) {
    const nlohmann::ordered_json json{{"task", task_ - 1},
                                      {"task_type", planning::to_string(tasks_[task_ - 1].type)},
                                      {"reason", reason + ": paused, a resume skips the task"}};
    events.push_back({t_s, "task_failed", json.dump()});
    task_open_ = false;
    task_failed_ = true;
    change_state(control::MissionState::kPaused, "task failed: a resume skips it", t_s, events);
}

perception::FaceCorridor CrawlerStack::corridor_of(const PointCloud& cloud_body,
                                                   Eigen::Vector3d& origin_world,
                                                   Eigen::Vector3d& direction_world) const {
    perception::FaceCorridorConfig config = config_.corridor;
    config.bounds = bounds_of(tasks_[task_ - 1].type);
    const perception::FaceCorridor corridor = perception::extract_face_corridor(cloud_body, config);
    // The crawler has not moved since the stop began: its newest estimate, the one the follower
    // will steer by, places the corridor (the stop's pose, 0.5 s into it, is older by 2.5 s of
    // UWB updates).
    const Eigen::Isometry3d T = filter_.estimate().T_world_body;
    origin_world = T * corridor.origin_m;
    direction_world = T.linear() * corridor.direction;
    return corridor;
}

bool CrawlerStack::lay_corridor(double t_s, std::vector<StackEvent>& events) {
    const PointCloud cloud_body = std::move(*stop_cloud_here_);
    stop_cloud_here_.reset();  // one corridor per stop: the next task drives away from it
    Eigen::Vector3d origin, direction;
    const perception::FaceCorridor corridor = corridor_of(cloud_body, origin, direction);
    if (!corridor.found) {
        fail_task("no corridor in the stop's cloud: " + corridor.status, t_s, events);
        return false;
    }
    events.push_back(
        {t_s, "corridor_found",
         fmt::format(R"({{"task":{},"origin":[{:.3f},{:.3f},{:.3f}],"width_m":{:.3f},)"
                     R"("left":"{}","right":"{}","rows":{}}})",
                     task_ - 1, origin.x(), origin.y(), origin.z(), corridor.width_m,
                     perception::to_string(corridor.left_bound),
                     perception::to_string(corridor.right_bound), corridor.rows_used)});
    try {
        add_plan(planning::lay_corridor_task(
            tasks_[task_ - 1], surface_, filter_.estimate().T_world_body.translation(), origin,
            direction, config_.corridor_join_m, config_.walk, task_name(task_ - 1)));
    } catch (const InputError& e) {
        fail_task(e.what(), t_s, events);
        return false;
    }
    corridor_leg_ = legs_.size() - 1;  // the drive along the centre line
    return true;
}

void CrawlerStack::remeasure_corridor(const perception::StopMap& stop, double t_s,
                                      std::vector<StackEvent>& events) {
    if (!corridor_leg_ || leg_ != *corridor_leg_ || legs_[leg_].segments.empty()) return;
    Eigen::Vector3d origin, direction;
    const perception::FaceCorridor corridor = corridor_of(stop.cloud_body, origin, direction);
    const Eigen::Vector3d p = filter_.estimate().T_world_body.translation();
    const Eigen::Vector3d end = legs_[leg_].segments.back().end_world_m;
    const Eigen::Vector3d d = direction.normalized();
    // Left to drive along the new centre line: from the crawler's foot on it, past the join,
    // to the old end's foot.
    const double left_m = d.dot(end - p) - config_.corridor_join_m;
    if (!corridor.found || !(left_m > config_.corridor_join_m)) {
        events.push_back(
            {t_s, "corridor_kept",
             nlohmann::ordered_json{{"task", task_ - 1},
                                    {"reason", corridor.found ? "near the end" : corridor.status}}
                 .dump()});
        return;
    }
    planning::SurfaceTask rest = tasks_[task_ - 1];
    rest.length_m = left_m;
    planning::TaskPlan plan;
    try {
        plan = planning::lay_corridor_task(rest, surface_, p, origin, d, config_.corridor_join_m,
                                           config_.walk, task_name(task_ - 1));
    } catch (const InputError& e) {
        events.push_back(
            {t_s, "corridor_kept",
             nlohmann::ordered_json{{"task", task_ - 1}, {"reason", e.what()}}.dump()});
        return;
    }
    std::vector<control::PathSegment> segments;
    for (const planning::TaskLeg& leg : plan.legs) {
        segments.insert(segments.end(), leg.segments.begin(), leg.segments.end());
    }
    const Eigen::Vector3d old_d = (end - legs_[leg_].segments.front().begin_world_m).normalized();
    legs_[leg_].segments = std::move(segments);
    ++legs_revision_;
    follower_.reset();
    events.push_back(
        {t_s, "corridor_remeasured",
         fmt::format(R"({{"task":{},"width_m":{:.3f},"turned_rad":{:.4f},"rows":{}}})", task_ - 1,
                     corridor.width_m, std::acos(std::clamp(old_d.dot(d), -1.0, 1.0)),
                     corridor.rows_used)});
}

bool CrawlerStack::next_task(CrawlerStackCommand& out, double t_s) {
    if (task_failed_) return false;
    if (task_open_) {
        task_open_ = false;
        corridor_leg_.reset();
        out.events.push_back({t_s, "task_done",
                              fmt::format(R"({{"task":{},"task_type":"{}"}})", task_ - 1,
                                          planning::to_string(tasks_[task_ - 1].type))});
    }
    if (task_ >= tasks_.size()) {
        change_state(control::MissionState::kCompleted,
                     fmt::format("all {} tasks done ({} skipped)", tasks_.size(), tasks_skipped_),
                     t_s, out.events);
        return false;
    }
    const planning::SurfaceTask& task = tasks_[task_];
    if (task.needs_corridor() && !stop_cloud_here_) {
        stop_due_ = true;  // map here first: the corridor comes from the stop's cloud
        return false;
    }
    ++task_;
    task_open_ = true;
    out.events.push_back({t_s, "task_started",
                          fmt::format(R"({{"task":{},"task_type":"{}"}})", task_ - 1,
                                      planning::to_string(task.type))});
    if (task.needs_corridor()) return lay_corridor(t_s, out.events) && leg_ < legs_.size();
    try {
        add_plan(planning::lay_surface_task(task, surface_, mesh_,
                                            filter_.estimate().T_world_body.translation(),
                                            config_.walk, task_name(task_ - 1)));
    } catch (const InputError& e) {
        fail_task(e.what(), t_s, out.events);
        return false;
    }
    return leg_ < legs_.size() || next_task(out, t_s);
}

}  // namespace scantling::mission
