// Figures of a closed-loop run (detail/loop_metrics.hpp).
#include "detail/loop_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include <scantling/control/position_controller.hpp>
#include <scantling/core/se3.hpp>

namespace scantling::mission::detail {
namespace {

double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b) {
    const Eigen::Vector3d ab = b - a;
    const double length_sq = ab.squaredNorm();
    const double t = length_sq > 0.0 ? std::clamp((p - a).dot(ab) / length_sq, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).norm();
}

double yaw_of(const Eigen::Matrix3d& R) { return euler_zyx_from_rotation(R).z(); }

}  // namespace

double distance_to_polyline(const Eigen::Vector3d& p,
                            const std::vector<Eigen::Vector3d>& vertices) {
    if (vertices.size() == 1) return (p - vertices.front()).norm();
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i + 1 < vertices.size(); ++i) {
        best = std::min(best, segment_distance(p, vertices[i], vertices[i + 1]));
    }
    return best;
}

LoopMetrics::LoopMetrics(const planning::WaypointPath& path, const Eigen::Vector3d& p_start_world_m)
    : polyline_{p_start_world_m}, num_waypoints_(path.waypoints.size()) {
    for (const planning::Waypoint& wp : path.waypoints) polyline_.push_back(wp.p_world_m);
}

void LoopMetrics::add_sweep(const PointCloud& sweep_sensor) {
    ++sweeps_;
    for (const Eigen::Vector3d& p : sweep_sensor.points) {
        if (p.allFinite()) min_obstacle_m_ = std::min(min_obstacle_m_, p.norm());
    }
}

void LoopMetrics::add_odometry(const std::optional<odometry::FrameReport>& report) {
    if (!report || report->status == odometry::FrameStatus::kFirst) return;
    const bool degenerate = report->status == odometry::FrameStatus::kDegenerate;
    if (report->status == odometry::FrameStatus::kOk || degenerate) {
        ++odometry_registered_;
        odometry_degenerate_ += degenerate ? 1 : 0;
        odometry_iterations_ += static_cast<std::size_t>(std::max(report->iterations, 0));
    } else {
        ++odometry_unregistered_;
    }
}

void LoopMetrics::add_tick(const sim::MotionState& truth, const localization::DroneState& estimate,
                           const StackCommand& command, double t_s) {
    const Eigen::Vector3d p = truth.T_world_body.translation();
    const Eigen::Vector3d error = estimate.T_odom_body.translation() - p;
    error_sq_sum_ += error.squaredNorm();
    error_max_m_ = std::max(error_max_m_, error.norm());
    final_error_m_ = error.norm();
    const double yaw_error = control::wrap_angle_rad(yaw_of(estimate.T_odom_body.linear()) -
                                                     yaw_of(truth.T_world_body.linear()));
    yaw_sq_sum_ += yaw_error * yaw_error;
    const Eigen::Matrix3d P = estimate.covariance.topLeftCorner<3, 3>();
    if (P.allFinite() && P.determinant() > 0.0) {
        nees_sum_ += error.dot(P.ldlt().solve(error));
        ++nees_count_;
    }
    ++ticks_;
    if (previous_p_) path_length_m_ += (p - *previous_p_).norm();
    previous_p_ = p;
    const bool running = command.state == control::MissionState::kRunning;
    if (running) {
        if (!started_s_) started_s_ = t_s;
        const double d = distance_to_polyline(p, polyline_);
        deviation_sum_m_ += d;
        deviation_max_m_ = std::max(deviation_max_m_, d);
        ++deviation_count_;
    }
    for (const control::MissionEvent& e : command.events) {
        if (e.type == control::MissionEventType::kWaypointReached && !e.home_leg) ++reached_;
    }
    if (command.state == control::MissionState::kCompleted && !completed_s_) completed_s_ = t_s;
    interventions_ += command.limited ? 1 : 0;
    last_t_s_ = t_s;
}

MissionResult LoopMetrics::result(control::MissionState final_state) const {
    MissionResult r;
    r.final_state = final_state;
    r.completed = completed_s_.has_value();
    const double start_s = started_s_.value_or(0.0);
    r.mission_time_s = completed_s_.value_or(last_t_s_) - start_s;
    const auto mean = [](double sum, std::size_t n) { return n > 0 ? sum / n : 0.0; };
    r.path_deviation_mean_m = mean(deviation_sum_m_, deviation_count_);
    r.path_deviation_max_m = deviation_max_m_;
    r.position_error_rms_m = std::sqrt(mean(error_sq_sum_, ticks_));
    r.position_error_max_m = error_max_m_;
    r.final_position_error_m = final_error_m_;
    r.yaw_error_rms_rad = std::sqrt(mean(yaw_sq_sum_, ticks_));
    r.position_nees_mean = mean(nees_sum_, nees_count_);
    r.path_length_m = path_length_m_;
    r.waypoints_reached = reached_;
    r.waypoints = num_waypoints_;
    r.safety_interventions = interventions_;
    r.min_obstacle_distance_m = std::isfinite(min_obstacle_m_) ? min_obstacle_m_ : 0.0;
    r.lidar_sweeps = sweeps_;
    r.odometry_registered = odometry_registered_;
    r.odometry_degenerate = odometry_degenerate_;
    r.odometry_iterations = odometry_iterations_;
    r.odometry_unregistered = odometry_unregistered_;
    return r;
}

std::string summary_json(const MissionScenario& scenario, const MissionResult& r) {
    nlohmann::ordered_json j{{"scenario", scenario.name},
                             {"final_state", std::string(control::to_string(r.final_state))},
                             {"completed", r.completed},
                             {"mission_time_s", r.mission_time_s},
                             {"sim_time_s", r.sim_time_s},
                             {"path_deviation_mean_m", r.path_deviation_mean_m},
                             {"path_deviation_max_m", r.path_deviation_max_m},
                             {"position_error_rms_m", r.position_error_rms_m},
                             {"position_error_max_m", r.position_error_max_m},
                             {"final_position_error_m", r.final_position_error_m},
                             {"yaw_error_rms_rad", r.yaw_error_rms_rad},
                             {"position_nees_mean", r.position_nees_mean},
                             {"path_length_m", r.path_length_m},
                             {"waypoints_reached", r.waypoints_reached},
                             {"waypoints", r.waypoints},
                             {"safety_interventions", r.safety_interventions},
                             {"min_obstacle_distance_m", r.min_obstacle_distance_m},
                             {"lidar_sweeps", r.lidar_sweeps},
                             {"events", r.events},
                             {"increments_applied", r.increments_applied},
                             {"increments_rejected", r.increments_rejected},
                             {"ranges_applied", r.ranges_applied},
                             {"ranges_rejected", r.ranges_rejected},
                             {"uwb_applied", r.uwb_applied},
                             {"uwb_rejected", r.uwb_rejected},
                             {"uwb_reacquisitions", r.uwb_reacquisitions},
                             {"inputs_rejected", r.inputs_rejected},
                             {"odometry_registered", r.odometry_registered},
                             {"odometry_degenerate", r.odometry_degenerate},
                             {"odometry_iterations", r.odometry_iterations},
                             {"odometry_unregistered", r.odometry_unregistered}};
    const LoopTiming& t = r.timing;
    if (r.coverage) {
        const perception::CoverageResult& c = *r.coverage;
        nlohmann::ordered_json holes = nlohmann::json::array();
        // The 20 largest (holes come largest first): a sparse coverage has thousands of specks.
        for (std::size_t i = 0; i < std::min<std::size_t>(c.holes.size(), 20); ++i) {
            const perception::CoverageHole& h = c.holes[i];
            holes.push_back({{"area_m2", h.area_m2},
                             {"centroid_world_m",
                              {h.centroid_world.x(), h.centroid_world.y(), h.centroid_world.z()}}});
        }
        j["coverage"] = {{"fraction", c.covered_fraction},
                         {"covered_area_m2", c.covered_area_m2},
                         {"cells", c.cells},
                         {"holes_total", c.holes.size()},
                         {"largest_holes", holes}};
    }
    j["timing_s"] = {{"simulate", t.simulate_s}, {"record", t.record_s},
                     {"odometry", t.odometry_s}, {"estimators", t.estimators_s},
                     {"command", t.command_s},   {"log", t.log_s}};
    return j.dump(2) + "\n";
}

}  // namespace scantling::mission::detail
