// The crawler's rectangle mission in closed loop (crawler_mission.hpp).
#include <scantling/mission/crawler_mission.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <variant>

#include <scantling/core/error.hpp>
#include <scantling/core/kdtree.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/sim/recording_writer.hpp>
#include <scantling/sim/simulator.hpp>

#include "detail/crawler_stop_metrics.hpp"
#include "detail/loop_support.hpp"

namespace scantling::mission {
namespace {

using detail::MissionFiles;
using detail::StageClock;

constexpr double kCoverageCellM = 0.02;
constexpr double kDenseStepM = 0.002;  ///< the intended path, densified for distances

/// Points every `step_m` along `segments` (begin of each, then inside).
std::vector<Eigen::Vector3d> densify(std::span<const control::PathSegment> segments,
                                     double step_m) {
    std::vector<Eigen::Vector3d> points;
    for (const control::PathSegment& s : segments) {
        const Eigen::Vector3d d = s.end_world_m - s.begin_world_m;
        const int n = std::max(1, static_cast<int>(std::ceil(d.norm() / step_m)));
        for (int i = 0; i < n; ++i) points.push_back(s.begin_world_m + d * (double(i) / n));
    }
    if (!segments.empty()) points.push_back(segments.back().end_world_m);
    return points;
}

/// Cell centres of the rectangle laid on the surface: columns walked across from the start,
/// rows walked up from each column's foot, the walking direction transported as the crawler
/// transports its heading.
std::vector<Eigen::Vector3d> rectangle_cells(const planning::SurfaceRectangleRequest& r,
                                             const SurfaceProjector& surface) {
    const auto march = [&](SurfacePoint p, Eigen::Vector3d d, double length_m) {
        std::vector<Eigen::Vector3d> marks;
        double next_mark_m = kCoverageCellM / 2.0;
        for (double s = 0.0; s < length_m; s += kCoverageCellM / 2.0) {
            d = (d - d.dot(p.normal) * p.normal).normalized();
            p = surface.project(p.point + d * (kCoverageCellM / 2.0));
            if (s + kCoverageCellM / 2.0 >= next_mark_m - 1e-9) {
                marks.push_back(p.point);
                next_mark_m += kCoverageCellM;
            }
        }
        return marks;
    };
    const SurfacePoint start = surface.project(r.start_world_m);
    const Eigen::Vector3d up = (r.up_world - r.up_world.dot(start.normal) * start.normal);
    const Eigen::Vector3d across = up.normalized().cross(start.normal);
    std::vector<Eigen::Vector3d> cells;
    for (const Eigen::Vector3d& foot : march(start, across, r.width_m)) {
        const SurfacePoint f = surface.project(foot);
        const std::vector<Eigen::Vector3d> column = march(f, r.up_world, r.height_m);
        cells.insert(cells.end(), column.begin(), column.end());
    }
    return cells;
}

/// The figures measured on the truth while the loop runs.
class CrawlerMetrics {
  public:
    explicit CrawlerMetrics(const CrawlerMissionScenario& scenario)
        : swath_m_(scenario.swath_width_m) {}

    void add_tick(const sim::MotionState& truth, const CrawlerStack& stack,
                  const CrawlerStackCommand& command, double t_s) {
        const Eigen::Vector3d p = truth.T_world_body.translation();
        const auto estimate = stack.estimate();
        const double error_m = (estimate.T_world_body.translation() - p).norm();
        error_sq_sum_ += error_m * error_m;
        error_max_m_ = std::max(error_max_m_, error_m);
        const Eigen::Vector3d x_true = truth.T_world_body.linear().col(0);
        const Eigen::Vector3d x_est = estimate.T_world_body.linear().col(0);
        const double yaw_error = std::atan2(x_true.cross(x_est).norm(), x_true.dot(x_est));
        yaw_sq_sum_ += yaw_error * yaw_error;
        ++ticks_;
        if (previous_p_) path_length_m_ += (p - *previous_p_).norm();
        previous_p_ = p;
        if (command.state == control::MissionState::kRunning) {
            if (!started_s_) started_s_ = t_s;
            end_s_ = t_s;
        }
        const auto& legs = stack.legs();
        const bool on_inspection = command.state == control::MissionState::kRunning &&
                                   command.leg < legs.size() && legs[command.leg].inspection;
        if (!on_inspection) return;
        if (stack.legs_revision() != revision_seen_) index_inspection_legs(stack);
        on_rectangle_points_.push_back(p);
        const auto nearest = intended_tree_->nearest(p);
        if (nearest) {
            const double distance_m = std::sqrt(nearest->distance_sq_m2);
            cross_sum_m_ += distance_m;
            cross_max_m_ = std::max(cross_max_m_, distance_m);
            ++cross_samples_;
        }
    }

    CrawlerMissionResult result(const CrawlerMissionScenario& scenario,
                                const SurfaceProjector& surface) const {
        CrawlerMissionResult r;
        r.mission_time_s = started_s_ ? end_s_ - *started_s_ : 0.0;
        r.cross_track_samples = cross_samples_;
        r.cross_track_mean_m = cross_samples_ > 0 ? cross_sum_m_ / cross_samples_ : 0.0;
        r.cross_track_max_m = cross_max_m_;
        r.position_error_rms_m = ticks_ > 0 ? std::sqrt(error_sq_sum_ / ticks_) : 0.0;
        r.position_error_max_m = error_max_m_;
        r.yaw_error_rms_rad = ticks_ > 0 ? std::sqrt(yaw_sq_sum_ / ticks_) : 0.0;
        r.path_length_m = path_length_m_;
        r.coverage = coverage(scenario, surface);
        return r;
    }

  private:
    /// The intended path of the inspection legs laid so far, densified (legs are laid as their
    /// task begins, and replanned around obstacles: the ticks before were scored on the path
    /// replaced, the ticks after on the detour).
    void index_inspection_legs(const CrawlerStack& stack) {
        intended_.clear();
        for (const planning::TaskLeg& leg : stack.legs()) {
            if (!leg.inspection) continue;
            const std::vector<Eigen::Vector3d> dense = densify(leg.segments, kDenseStepM);
            intended_.insert(intended_.end(), dense.begin(), dense.end());
        }
        revision_seen_ = stack.legs_revision();
        intended_tree_.emplace(intended_);
    }

    double coverage(const CrawlerMissionScenario& scenario, const SurfaceProjector& surface) const {
        std::vector<Eigen::Vector3d> cells;
        for (const planning::SurfaceTask& task : scenario.tasks) {
            if (task.type != planning::SurfaceTaskType::kRectangle) continue;
            const std::vector<Eigen::Vector3d> more = rectangle_cells(task.rectangle, surface);
            cells.insert(cells.end(), more.begin(), more.end());
        }
        if (cells.empty() || on_rectangle_points_.empty()) return 0.0;
        const KdTree path(on_rectangle_points_);
        std::size_t covered = 0;
        for (const Eigen::Vector3d& c : cells) {
            const auto nearest = path.nearest(c);
            if (nearest && nearest->distance_sq_m2 <= swath_m_ * swath_m_ / 4.0) ++covered;
        }
        return static_cast<double>(covered) / static_cast<double>(cells.size());
    }

    std::size_t revision_seen_ = 0;
    std::vector<Eigen::Vector3d> intended_;
    std::optional<KdTree> intended_tree_;
    double swath_m_;
    std::vector<Eigen::Vector3d> on_rectangle_points_;
    double cross_sum_m_ = 0.0;
    double cross_max_m_ = 0.0;
    std::size_t cross_samples_ = 0;
    double error_sq_sum_ = 0.0;
    double error_max_m_ = 0.0;
    double yaw_sq_sum_ = 0.0;
    std::size_t ticks_ = 0;
    double path_length_m_ = 0.0;
    std::optional<Eigen::Vector3d> previous_p_;
    std::optional<double> started_s_;
    double end_s_ = 0.0;
};

/// One reading to the stack, as the io type a recording gives.
void feed(CrawlerStack& stack, const sim::SensorReading& reading) {
    if (const auto* imu = std::get_if<sim::ImuSample>(&reading.data)) {
        stack.add_imu(detail::imu_record(*imu));
    } else if (const auto* wheel = std::get_if<sim::WheelOdometrySample>(&reading.data)) {
        stack.add_wheel_odometry(
            {wheel->stamp_s, wheel->forward_speed_mps, wheel->yaw_rate_radps, wheel->slipping});
    } else if (const auto* uwb = std::get_if<sim::UwbMeasurement>(&reading.data)) {
        for (const io::UwbRecord& record : detail::uwb_records(*uwb)) stack.add_uwb(record);
    } else if (const auto* rosette = std::get_if<sim::RosetteReading>(&reading.data)) {
        stack.add_lidar_frame(rosette->frame);
    } else if (const auto* image = std::get_if<sim::ImageReading>(&reading.data)) {
        stack.add_image(image->image, image->intrinsics);
    }
}

/// The recording keeps the LiDAR frames of the stops only: the Mid-70's 100 000 points a second
/// over a whole mission would be gigabytes, and only the stops' are used.
bool recorded(const sim::SensorReading& reading, const CrawlerStack& stack) {
    return !std::holds_alternative<sim::RosetteReading>(reading.data) || stack.mapping();
}

double share(std::size_t part, std::size_t whole) {
    return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

nlohmann::ordered_json stop_json(const CrawlerStopScores& s) {
    nlohmann::ordered_json j;
    j["stops"] = s.stops;
    j["stops_icp_applied"] = s.stops_icp_applied;
    j["map_pose_error_rms_m"] = s.map_error_rms_m;
    j["map_pose_error_max_m"] = s.map_error_max_m;
    j["pf_at_stops_error_rms_m"] = s.pf_error_rms_m;
    j["pf_at_stops_error_max_m"] = s.pf_error_max_m;
    nlohmann::ordered_json classes = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < s.classes.size(); ++k) {
        const CrawlerClassScore& c = s.classes[k];
        if (c.in_view == 0) continue;
        classes[std::string(sim::to_string(static_cast<sim::ObstacleKind>(k)))] = {
            {"in_view", c.in_view}, {"found", c.found}, {"recall", share(c.found, c.in_view)}};
    }
    j["recall"] = classes;
    j["positive_clusters"] = s.positive_clusters;
    j["positive_precision"] = share(s.positive_right, s.positive_clusters);
    j["negative_clusters"] = s.negative_clusters;
    j["negative_precision"] = share(s.negative_right, s.negative_clusters);
    return j;
}

/// The PF estimate as the estimates.csv record of the other loops.
localization::DroneState as_state(const CrawlerStack& stack) {
    const auto e = stack.estimate();
    localization::DroneState s;
    s.stamp_s = e.stamp_s;
    s.T_odom_body = e.T_world_body;
    s.covariance.topLeftCorner<3, 3>() = e.position_covariance_m2;
    s.covariance(5, 5) = e.yaw_variance_rad2;
    return s;
}

void log_command(MissionFiles& files, const CrawlerStackCommand& c, const sim::MotionState& truth,
                 double t_s) {
    // commands.csv holds world velocities: the forward speed along the true heading is what
    // the wheels were asked for (no slip), the turn rate about the normal as yaw_rate.
    const Eigen::Vector3d v = truth.T_world_body.linear().col(0) * c.forward_mps;
    files.commands.push_back({.stamp_s = t_s,
                              .v_world_mps = v,
                              .yaw_rate_radps = c.yaw_rate_radps,
                              .v_requested_world_mps = v,
                              .limited = false});
    for (const StackEvent& e : c.events) files.add_event(e.t_s, e.type, e.json);
}

std::string summary_json(const CrawlerMissionScenario& m, const CrawlerMissionResult& r) {
    nlohmann::ordered_json j;
    j["scenario"] = m.name;
    j["final_state"] = std::string(control::to_string(r.final_state));
    j["completed"] = r.completed;
    j["mission_time_s"] = r.mission_time_s;
    j["transects"] = r.transects;
    j["step_m"] = r.step_m;
    j["waypoints_reached"] = r.waypoints_reached;
    j["tasks"] = r.tasks;
    j["tasks_done"] = r.tasks_done;
    j["tasks_failed"] = r.tasks_failed;
    j["cross_track_mean_m"] = r.cross_track_mean_m;
    j["cross_track_max_m"] = r.cross_track_max_m;
    const bool rectangle = std::any_of(m.tasks.begin(), m.tasks.end(), [](const auto& t) {
        return t.type == planning::SurfaceTaskType::kRectangle;
    });
    if (rectangle) {
        j["coverage"] = r.coverage;
    } else {
        j["coverage"] = nullptr;  // no rectangle to cover
    }
    j["position_error_rms_m"] = r.position_error_rms_m;
    j["position_error_max_m"] = r.position_error_max_m;
    j["yaw_error_rms_rad"] = r.yaw_error_rms_rad;
    j["path_length_m"] = r.path_length_m;
    j["uwb_applied"] = r.uwb_applied;
    j["uwb_refused"] = r.uwb_refused;
    j["inputs_rejected"] = r.inputs_rejected;
    j["events"] = r.events;
    if (r.stop_scores.stops > 0) j["stop_and_map"] = stop_json(r.stop_scores);
    j["wall_time_s"] = r.wall_time_s;
    j["real_time_factor"] = r.real_time_factor;
    return j.dump(2);
}

/// The intended path for mission/intended_path.csv: every leg's end.
planning::WaypointPath intended_waypoints(const CrawlerStack& stack) {
    planning::WaypointPath path;
    for (const Eigen::Vector3d& p : stack.waypoints()) {
        path.waypoints.push_back({.p_world_m = p, .yaw_rad = std::nullopt});
    }
    return path;
}

}  // namespace

CrawlerMissionResult run_crawler_mission(const CrawlerMissionScenario& scenario,
                                         const std::string& directory,
                                         const MissionRunOptions& options) {
    const auto wall_start = std::chrono::steady_clock::now();
    scenario.validate();
    const sim::Scenario& simulation = scenario.simulation;
    sim::Simulator sim(simulation, scenario.T_world_body_start());
    const std::unique_ptr<SurfaceProjector> surface = sim::crawler_surface(simulation, sim.world());
    // A start far off the surface would be snapped onto it silently by the simulator.
    planning::snap_to_surface(*surface, scenario.T_world_body_start().translation(),
                              scenario.stack.walk.max_start_distance_m, "start.xyz");
    const auto* mesh_surface = dynamic_cast<const MeshSurface*>(surface.get());
    CrawlerStack stack(scenario.stack, *surface, mesh_surface ? &mesh_surface->mesh() : nullptr,
                       scenario.tasks, sim.truth().T_world_body,
                       Rng(simulation.seed).split(200).next_u64());
    sim::RecordingWriter writer(directory, options.overwrite);
    CrawlerMetrics metrics(scenario);
    detail::StopMetrics stop_metrics(sim.world().obstacles);
    control::OperatorScript script(scenario.operator_script);
    MissionFiles files;
    LoopTiming timing;
    FaultInjector faults(scenario.faults, detail::sensor_types(simulation));
    std::optional<double> ended_at_s;
    double next_progress_s = 0.0;
    control::MissionState state = control::MissionState::kIdle;
    std::size_t reached = 0;
    std::size_t tasks_done = 0;
    std::size_t tasks_failed = 0;

    sim::SimStep step = sim.start();
    while (true) {
        detail::throw_if_stop_requested(options, sim, directory);
        const double t_s = sim.now_s();
        {
            StageClock clock(timing.record_s);
            writer.add_ground_truth(t_s, step.truth.T_world_body);
        }
        detail::log_faults(files, faults, t_s);
        for (const sim::SensorReading& r : step.readings) {
            detail::deliver(
                r, faults, writer, timing.record_s,
                [&](const sim::SensorReading& in) {
                    StageClock clock(timing.estimators_s);
                    feed(stack, in);
                },
                recorded(r, stack));
        }
        std::vector<control::OperatorCommand> commands = detail::operator_commands_due(script, sim);
        detail::log_operator(files, commands, t_s);
        const CrawlerStackCommand command = [&] {
            StageClock clock(timing.command_s);
            return stack.command(t_s, commands);
        }();
        state = command.state;
        if (command.stop) stop_metrics.add(*command.stop, step.truth.T_world_body);
        for (const StackEvent& e : command.events) {
            reached += e.type == "waypoint_reached";
            tasks_done += e.type == "task_done";
            tasks_failed += e.type == "task_failed";
        }
        {
            StageClock clock(timing.log_s);
            log_command(files, command, step.truth, t_s);
            files.estimates.push_back(detail::estimate_record(as_state(stack), t_s, true));
            metrics.add_tick(step.truth, stack, command, t_s);
        }
        if (options.progress && t_s >= next_progress_s) {
            options.progress({t_s, simulation.duration_s, command.state});
            next_progress_s += 1.0;
        }
        if (detail::mission_ended(command.state) && !ended_at_s) ended_at_s = t_s;
        if (ended_at_s && t_s >= *ended_at_s + scenario.linger_s) break;
        if (t_s >= simulation.duration_s - 1e-9) {
            files.add_event(t_s, "timeout",
                            fmt::format(R"({{"state":"{}"}})", control::to_string(command.state)));
            break;
        }
        StageClock clock(timing.simulate_s);
        step = sim.step(
            {.yaw_rate_radps = command.yaw_rate_radps, .forward_mps = command.forward_mps});
    }
    CrawlerMissionResult result = metrics.result(scenario, *surface);
    result.final_state = state;
    result.completed = state == control::MissionState::kCompleted;
    result.transects = stack.transects();
    result.step_m = stack.step_m();
    result.waypoints_reached = reached;
    result.tasks = scenario.tasks.size();
    result.tasks_done = tasks_done;
    result.tasks_failed = tasks_failed;
    result.uwb_applied = stack.filter().counters().uwb_applied;
    result.uwb_refused = stack.filter().counters().uwb_refused;
    result.inputs_rejected = stack.inputs_rejected();
    result.stop_scores = stop_metrics.scores();
    result.timing = timing;
    result.directory = directory;
    result.sim_time_s = sim.now_s();
    result.events = files.num_events;
    detail::stamp_wall_time(result, wall_start);
    writer.finish(detail::recording_summary(scenario.name, scenario.description, simulation, sim));
    detail::write_mission_files(writer, files, intended_waypoints(stack),
                                summary_json(scenario, result));
    if (const perception::TextureMap* texture = stack.texture_map()) {
        texture->write(
            (std::filesystem::path(writer.staging_directory()) / io::recording_layout::kMissionDir /
             io::recording_layout::kMissionTextureDir)
                .string());
    }
    writer.write_timing(result.wall_time_s, result.real_time_factor);
    writer.commit();
    return result;
}

}  // namespace scantling::mission
