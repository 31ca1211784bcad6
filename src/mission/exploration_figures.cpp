// The exploration loop's figures (detail/exploration_figures.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "detail/exploration_figures.hpp"

namespace scantling::mission::detail {
namespace {

constexpr double kClearancePeriod_s = 0.5;
constexpr double kClearanceReach_m = 3.0;

/// The nearest surface along 26 directions (the faces, edges and corners of a cube).
double clearance_m(const sim::SceneView& scene, const Eigen::Vector3d& p) {
    double nearest = kClearanceReach_m;
    for (int x = -1; x <= 1; ++x) {
        for (int y = -1; y <= 1; ++y) {
            for (int z = -1; z <= 1; ++z) {
                if (x == 0 && y == 0 && z == 0) continue;
                const Eigen::Vector3d d = Eigen::Vector3d(x, y, z).normalized();
                const sim::RayHit hit = scene.cast(p, d, kClearanceReach_m);
                if (hit.hit) nearest = std::min(nearest, hit.range_m);
            }
        }
    }
    return nearest;
}

}  // namespace

ExplorationFigures::ExplorationFigures(const ExplorationMissionScenario& scenario,
                                       ReachableVolume reachable)
    : scenario_(scenario), reachable_(std::move(reachable)) {
    result_.reachable_free_m3 = reachable_.volume_m3();
    result_.min_wall_distance_m = kClearanceReach_m;
}

void ExplorationFigures::add_tick(const sim::SceneView& scene, const sim::MotionState& truth,
                                  const localization::DroneState& estimate,
                                  control::MissionState state, double t_s) {
    const Eigen::Vector3d p = truth.T_world_body.translation();
    if (previous_p_) result_.path_length_m += (p - *previous_p_).norm();
    previous_p_ = p;
    const double error = (estimate.T_odom_body.translation() - p).norm();
    error_sq_sum_ += error * error;
    ++ticks_;
    result_.position_error_final_m = error;
    const bool flying = state == control::MissionState::kRunning &&
                        p.z() > scenario_.T_world_body_start().translation().z() + 0.3;
    if (flying && t_s >= next_clearance_s_) {
        result_.min_wall_distance_m = std::min(result_.min_wall_distance_m, clearance_m(scene, p));
        next_clearance_s_ = t_s + kClearancePeriod_s;
    }
}

void ExplorationFigures::add_image(std::size_t sightings) {
    ++result_.images;
    result_.detections += sightings;
}

double ExplorationFigures::reachable_share(const mapping::OccupancyOctree& map) const {
    if (reachable_.centres_world.empty()) return 0.0;
    std::size_t known = 0;
    for (const Eigen::Vector3d& c : reachable_.centres_world) {
        known += map.query(c) != mapping::Occupancy::kUnknown;
    }
    return static_cast<double>(known) / static_cast<double>(reachable_.centres_world.size());
}

void ExplorationFigures::sample_volume(const ExplorationStack& stack, double t_s, bool force) {
    if (!force && t_s < next_sample_s_) return;
    next_sample_s_ = t_s + scenario_.volume_every_s;
    result_.curve.push_back({.t_s = t_s,
                             .explored_m3 = stack.map().explored_volume_m3(),
                             .reachable_share = reachable_share(stack.map()),
                             .path_length_m = result_.path_length_m});
}

void ExplorationFigures::mark_ended(double t_s) {
    if (!ended_s_) ended_s_ = t_s;
}

ExplorationMissionResult ExplorationFigures::result(const ExplorationStack& stack) const {
    ExplorationMissionResult r = result_;
    r.final_state = stack.state();
    r.completed = stack.no_gain_left();
    r.exploration_time_s = ended_s_.value_or(r.curve.empty() ? 0.0 : r.curve.back().t_s);
    r.explored_m3 = stack.map().explored_volume_m3();
    r.reachable_share = reachable_share(stack.map());
    r.plans = stack.plans().size();
    double sum = 0.0;
    for (const PlanRecord& p : stack.plans()) {
        sum += p.wall_s;
        r.plan_time_max_s = std::max(r.plan_time_max_s, p.wall_s);
        r.plans_failed += p.status != planning::NbvStatus::kOk;
    }
    r.plan_time_mean_s = r.plans == 0 ? 0.0 : sum / static_cast<double>(r.plans);
    r.detections_per_image =
        r.images == 0 ? 0.0 : static_cast<double>(r.detections) / static_cast<double>(r.images);
    r.defects_mapped = stack.defects().size();
    r.position_error_rms_m = ticks_ == 0 ? 0.0 : std::sqrt(error_sq_sum_ / ticks_);
    r.inputs_rejected = stack.inputs_rejected();
    return r;
}

std::string exploration_summary_json(const ExplorationMissionScenario& scenario,
                                     const ExplorationMissionResult& r) {
    return fmt::format(
        R"({{"name":"{}","vehicle":"mav","mission":"explore","final_state":"{}","completed":{},)"
        R"("exploration_time_s":{:.2f},"sim_time_s":{:.2f},"wall_time_s":{:.2f},)"
        R"("real_time_factor":{:.3f},"path_length_m":{:.3f},"reachable_free_m3":{:.3f},)"
        R"("explored_m3":{:.3f},"reachable_share":{:.4f},"plans":{},"plans_failed":{},)"
        R"("plan_time_mean_s":{:.4f},"plan_time_max_s":{:.4f},"images":{},"detections":{},)"
        R"("detections_per_image":{:.4f},"defects_mapped":{},"defects_in_world":{},)"
        R"("position_error_rms_m":{:.4f},"position_error_final_m":{:.4f},)"
        R"("min_wall_distance_m":{:.3f},"inputs_rejected":{},"events":{},"defect_aware":{}}})"
        "\n",
        scenario.name, control::to_string(r.final_state), r.completed, r.exploration_time_s,
        r.sim_time_s, r.wall_time_s, r.real_time_factor, r.path_length_m, r.reachable_free_m3,
        r.explored_m3, r.reachable_share, r.plans, r.plans_failed, r.plan_time_mean_s,
        r.plan_time_max_s, r.images, r.detections, r.detections_per_image, r.defects_mapped,
        r.defects_in_world, r.position_error_rms_m, r.position_error_final_m, r.min_wall_distance_m,
        r.inputs_rejected, r.events, scenario.stack.nbv.defect_aware);
}

std::string exploration_curve_csv(const ExplorationMissionResult& result) {
    std::string text = "# t_s explored_m3 reachable_share path_length_m\n";
    for (const ExploredSample& s : result.curve) {
        text += fmt::format("{:.2f} {:.4f} {:.5f} {:.3f}\n", s.t_s, s.explored_m3,
                            s.reachable_share, s.path_length_m);
    }
    return text;
}

std::string exploration_plans_csv(const ExplorationStack& stack) {
    std::string text = "# t_s wall_s nodes best_gain goal_gain_m3 gain_evaluations status\n";
    for (const PlanRecord& p : stack.plans()) {
        text += fmt::format("{:.3f} {:.5f} {} {:.5f} {:.5f} {} {}\n", p.t_s, p.wall_s, p.nodes,
                            p.best_gain, p.first_gain, p.gain_evaluations, to_string(p.status));
    }
    return text;
}

}  // namespace scantling::mission::detail
