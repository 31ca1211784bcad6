// The figures of an ROV run (detail/rov_metrics.hpp).
#include "detail/rov_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include <scantling/core/angles.hpp>
#include <scantling/sim/world.hpp>

#include "detail/frames.hpp"

namespace scantling::mission::detail {

std::optional<StandOffSample> true_stand_off(const sim::SceneView& scene,
                                             const Eigen::Vector3d& p_camera_world, double yaw_rad,
                                             std::span<const int> skipped_tags) {
    const Eigen::Vector3d heading(std::cos(yaw_rad), std::sin(yaw_rad), 0.0);
    const sim::RayHit hit = scene.cast(p_camera_world, heading, kMaxStandOffRayM);
    if (!std::isfinite(hit.range_m)) return std::nullopt;
    if (std::find(skipped_tags.begin(), skipped_tags.end(), hit.surface_tag) != skipped_tags.end())
        return std::nullopt;
    const Eigen::Vector2d inward = -hit.normal.head<2>();
    if (inward.norm() < 1e-6) return std::nullopt;  // a horizontal surface: not the side
    const double heading_error = std::atan2(heading.x() * inward.y() - heading.y() * inward.x(),
                                            heading.head<2>().dot(inward.normalized()));
    return StandOffSample{.stand_off_m = hit.range_m * std::abs(heading.dot(hit.normal)),
                          .heading_error_rad = heading_error};
}

std::vector<int> appendage_tags(const sim::SceneView& scene) {
    std::vector<int> tags;
    for (const char* name : {"anode", "bilge_keel", "sea_chest_grating"}) {
        if (const int tag = sim::find_surface(scene.metadata, name); tag >= 0) tags.push_back(tag);
    }
    return tags;
}

RovMetrics::RovMetrics(double wanted_stand_off_m, const Eigen::Isometry3d& T_body_camera,
                       std::vector<int> skipped_tags)
    : wanted_m_(wanted_stand_off_m),
      T_body_camera_(T_body_camera),
      skipped_tags_(std::move(skipped_tags)) {}

void RovMetrics::add_tick(const sim::SceneView& scene, const sim::MotionState& truth,
                          const localization::DroneState& estimate, const RovStackCommand& command,
                          double t_s) {
    const Eigen::Vector3d p = truth.T_world_body.translation();
    const double e = (estimate.T_odom_body.translation() - p).norm();
    error_sq_sum_ += e * e;
    error_max_m_ = std::max(error_max_m_, e);
    const double yaw_error =
        wrap_angle_rad(yaw_of(estimate.T_odom_body.linear()) - yaw_of(truth.T_world_body.linear()));
    yaw_sq_sum_ += yaw_error * yaw_error;
    ++ticks_;
    if (previous_p_) path_length_m_ += (p - *previous_p_).norm();
    previous_p_ = p;
    last_t_s_ = t_s;
    const bool running = command.state == control::MissionState::kRunning;
    if (running && !started_s_) started_s_ = t_s;
    if (command.state == control::MissionState::kCompleted && !completed_s_) completed_s_ = t_s;
    if (!running) return;
    paused_ += command.guidance_paused ? 1 : 0;
    backing_off_ += command.backing_off ? 1 : 0;
    const auto sample = true_stand_off(scene, truth.T_world_body * T_body_camera_.translation(),
                                       yaw_of(truth.T_world_body.linear()), skipped_tags_);
    if (!sample) return;
    const double error_m = std::abs(sample->stand_off_m - wanted_m_);
    stand_off_sum_m_ += error_m;
    stand_off_max_m_ = std::max(stand_off_max_m_, error_m);
    heading_sum_rad_ += std::abs(sample->heading_error_rad);
    heading_max_rad_ = std::max(heading_max_rad_, std::abs(sample->heading_error_rad));
    ++stand_off_samples_;
}

void RovMetrics::add_laser(const sim::SceneView& scene, const Eigen::Isometry3d& T_world_camera,
                           double distance_m) {
    const sim::RayHit hit = scene.cast(T_world_camera.translation(), T_world_camera.linear().col(2),
                                       2.0 * kMaxStandOffRayM);
    if (!std::isfinite(hit.range_m)) return;
    laser_error_sum_m_ += std::abs(distance_m - hit.range_m);
    ++laser_samples_;
}

RovMissionResult RovMetrics::result(control::MissionState final_state) const {
    RovMissionResult r;
    r.final_state = final_state;
    r.completed = final_state == control::MissionState::kCompleted;
    const auto mean = [](double sum, std::size_t n) { return n > 0 ? sum / n : 0.0; };
    r.stand_off_error_mean_m = mean(stand_off_sum_m_, stand_off_samples_);
    r.stand_off_error_max_m = stand_off_max_m_;
    r.heading_error_mean_rad = mean(heading_sum_rad_, stand_off_samples_);
    r.heading_error_max_rad = heading_max_rad_;
    r.stand_off_samples = stand_off_samples_;
    r.position_error_rms_m = std::sqrt(mean(error_sq_sum_, ticks_));
    r.position_error_max_m = error_max_m_;
    r.yaw_error_rms_rad = std::sqrt(mean(yaw_sq_sum_, ticks_));
    r.path_length_m = path_length_m_;
    r.guidance_paused_ticks = paused_;
    r.backing_off_ticks = backing_off_;
    r.laser_distance_error_mean_m = mean(laser_error_sum_m_, laser_samples_);
    if (started_s_) r.mission_time_s = completed_s_.value_or(last_t_s_) - *started_s_;
    return r;
}

namespace {

nlohmann::ordered_json coverage_json(const perception::CoverageResult& c) {
    nlohmann::ordered_json j{{"covered_fraction", c.covered_fraction},
                             {"covered_area_m2", c.covered_area_m2},
                             {"holes", c.holes.size()}};
    if (!c.holes.empty()) j["largest_hole_m2"] = c.holes.front().area_m2;
    return j;
}

}  // namespace

std::string rov_summary_json(const RovMissionScenario& scenario, const RovMissionResult& r) {
    nlohmann::ordered_json j{{"scenario", scenario.name},
                             {"vehicle", "rov"},
                             {"final_state", std::string(control::to_string(r.final_state))},
                             {"completed", r.completed},
                             {"mission_time_s", r.mission_time_s},
                             {"sim_time_s", r.sim_time_s},
                             {"wall_time_s", r.wall_time_s},
                             {"real_time_factor", r.real_time_factor},
                             {"stand_off_wanted_m", scenario.plan.stand_off_m},
                             {"stand_off_error_mean_m", r.stand_off_error_mean_m},
                             {"stand_off_error_max_m", r.stand_off_error_max_m},
                             {"heading_error_mean_deg", r.heading_error_mean_rad * 180.0 / M_PI},
                             {"heading_error_max_deg", r.heading_error_max_rad * 180.0 / M_PI},
                             {"position_error_rms_m", r.position_error_rms_m},
                             {"position_error_max_m", r.position_error_max_m},
                             {"yaw_error_rms_deg", r.yaw_error_rms_rad * 180.0 / M_PI},
                             {"path_length_m", r.path_length_m},
                             {"waypoints_survey", r.waypoints_survey},
                             {"guidance_paused_ticks", r.guidance_paused_ticks},
                             {"backing_off_ticks", r.backing_off_ticks},
                             {"contacts", r.contacts},
                             {"pings", r.pings},
                             {"hull_lines", r.hull_lines},
                             {"images", r.images},
                             {"laser_measurements", r.laser_measurements},
                             {"laser_distance_error_mean_m", r.laser_distance_error_mean_m},
                             {"dvl_invalid", r.dvl_invalid},
                             {"inputs_rejected", r.inputs_rejected},
                             {"events", r.events},
                             {"believed_coverage_survey", r.believed_coverage_survey},
                             {"believed_coverage_final", r.believed_coverage_final},
                             {"holes_found", r.holes_found},
                             {"reinspection_rounds", r.reinspection_rounds},
                             {"sonar_voxels", r.sonar_voxels},
                             {"sonar_voxel_uncertainty_mean_m", r.sonar_voxel_uncertainty_mean_m},
                             {"sonar_coverage", r.sonar_coverage}};
    if (r.coverage_survey) j["camera_coverage_survey"] = coverage_json(*r.coverage_survey);
    if (r.coverage) j["camera_coverage"] = coverage_json(*r.coverage);
    const LoopTiming& t = r.timing;
    j["timing_s"] = {{"simulate", t.simulate_s},     {"record", t.record_s},
                     {"estimators", t.estimators_s}, {"perception", t.odometry_s},
                     {"command", t.command_s},       {"log", t.log_s}};
    return j.dump(2) + "\n";
}

}  // namespace scantling::mission::detail
