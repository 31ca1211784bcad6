#pragma once
/// @file
/// The magnetic crawler's missions in closed loop (issue 15; SPEC §6): a mission
/// scenario whose vehicle is the simulated crawler on its surface and whose robot is the
/// CrawlerStack (crawler_stack.hpp). Each tick the simulator returns the readings due; they go
/// to the recording and, as io types, to the stack; the stack's wheel command moves the
/// crawler over the next tick. The recording is a simulator recording plus DIR/mission/ as the
/// other loops write it (io/mission_log.hpp), summary.json holding the figures below.
///
///   name: storage_tank_rectangle     # default: the file's stem
///   simulation: {world: {type: storage_tank}, vehicle: {type: crawler, crawler: {...}},
///                sensors: [imu, wheel_odometry, uwb], duration_s, seed}
///   start: {xyz: [x, y, z], rpy_deg: [...]}   # projected onto the surface
///   linger_s: 1.0
///   mission:
///     type: surface_rectangle
///     start_m: [x, y, z]            # the rectangle's lower-left corner, on the surface
///     width_m: 6.0                  # W, across (up × normal)
///     height_m: 2.0                 # H, up
///     max_step_m: 0.4               # transect spacing limit; the step is adjusted to W/(n−1)
///     up: [0, 0, 1]                 # the world's up (a horizontal plate needs another)
///     swath_width_m: 0.5            # what one transect inspects, for the coverage figure
///   # or a task list (planning/surface_tasks.hpp), each task taking its own keys only:
///   mission:
///     type: surface_tasks
///     swath_width_m: 0.5
///     tasks:
///       - {type: go_to, goal_m: [x, y, z]}               # the geodesic on a mesh
///       - {type: rectangle, start_m, width_m, height_m, max_step_m, up}
///       - {type: vertical_transect, length_m: 1.0, reverse: false, up: [0, 0, 1]}
///       - {type: horizontal_transect, length_m: 1.0, reverse: false, up: [0, 0, 1]}
///       - {type: drive_between_stiffeners, length_m: 1.5}   # also drive_on_stiffener,
///                                                          # drive_on_stiffener_side
///   stack: {particle_filter: {...}, follower: {...}, walk: {...}, corridor: {...}, ...}
///   operator: [{time_s, command: pause | resume | abort}]
///   faults: [{sensor: uwb, kind: dropout, start_s, duration_s}]
///
/// The robot's calibration comes from the simulated sensors (the UWB anchors and tag lever
/// arm); its map is the world's surface (the plate's plane, the tank's cylinder, the mesh).
///
/// Figures, on the truth: the cross-track error is the distance from the true position to the
/// intended path of the inspection legs (the transects and drives, not the drives to their
/// start: planning::TaskLeg::inspection), per tick while the mission runs on those legs; the
/// coverage is the share of the rectangles (cells of 2 cm laid on the surface) within half a
/// swath of the true path while on them (0 without a rectangle task); the localisation error
/// is the PF pose against the truth at every tick.
/// Errors name the file, line and key (ParseError) or the field (ConfigError, InputError).

#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <scantling/control/operator_script.hpp>
#include <scantling/mission/closed_loop.hpp>
#include <scantling/mission/crawler_stack.hpp>
#include <scantling/mission/fault_injection.hpp>
#include <scantling/planning/surface_tasks.hpp>
#include <scantling/sim/scenario.hpp>

namespace scantling::mission {

struct CrawlerMissionScenario {
    std::string name;
    std::string description;
    sim::Scenario simulation{};
    sim::PoseSpec start{};
    double linger_s = 1.0;  ///< simulated after the mission completes or aborts, s, >= 0
    std::vector<planning::SurfaceTask> tasks;  ///< at least one
    double swath_width_m = 0.5;                ///< > 0, for the coverage figure only
    CrawlerStackConfig stack{};
    std::vector<control::TimedCommand> operator_script;
    std::vector<SensorFault> faults;

    Eigen::Isometry3d T_world_body_start() const { return start.to_isometry(); }
    /// Throws ConfigError naming the field.
    void validate() const;
};

/// True when the document's `mission.type` is `surface_rectangle` or `surface_tasks` (the
/// crawler's missions).
bool is_crawler_mission_file(const std::string& path);
CrawlerMissionScenario load_crawler_mission_scenario(
    const std::string& path, const std::vector<std::string>& overrides = {});
CrawlerMissionScenario parse_crawler_mission_scenario(const std::string& yaml_text,
                                                      const std::string& name = "<mission>");

/// Obstacles of one class at the stops (src/mission/detail/crawler_stop_metrics.hpp).
struct CrawlerClassScore {
    std::size_t in_view = 0;
    std::size_t found = 0;
};

/// The stop-and-map's figures on the truth, summed over the stops: obstacle recall per class,
/// precision per sign, and the stops' map (ICP-corrected) and PF poses against the true pose.
struct CrawlerStopScores {
    std::size_t stops = 0;
    std::size_t stops_icp_applied = 0;
    double map_error_rms_m = 0.0;
    double map_error_max_m = 0.0;
    double pf_error_rms_m = 0.0;
    double pf_error_max_m = 0.0;
    std::array<CrawlerClassScore, 5> classes{};  ///< indexed by sim::ObstacleKind
    std::size_t positive_clusters = 0, positive_right = 0;
    std::size_t negative_clusters = 0, negative_right = 0;
};

/// Figures of one crawler run (also in mission/summary.json).
struct CrawlerMissionResult {
    std::string directory;
    control::MissionState final_state = control::MissionState::kIdle;
    bool completed = false;
    double mission_time_s = 0.0;  ///< start to completion (or to the end of the run)
    double sim_time_s = 0.0;
    double wall_time_s = 0.0;
    double real_time_factor = 0.0;
    std::size_t transects = 0;  ///< the first rectangle task's
    double step_m = 0.0;
    std::size_t waypoints_reached = 0;
    std::size_t tasks = 0;
    std::size_t tasks_done = 0;
    std::size_t tasks_failed = 0;
    double cross_track_mean_m = 0.0;  ///< see the file comment
    double cross_track_max_m = 0.0;
    std::size_t cross_track_samples = 0;
    double coverage = 0.0;  ///< share of the rectangle, [0, 1]
    double position_error_rms_m = 0.0;
    double position_error_max_m = 0.0;
    double yaw_error_rms_rad = 0.0;
    double path_length_m = 0.0;  ///< travelled (true)
    std::size_t uwb_applied = 0;
    std::size_t uwb_refused = 0;
    std::size_t inputs_rejected = 0;
    std::size_t events = 0;
    CrawlerStopScores stop_scores;  ///< all zero without a LiDAR
    LoopTiming timing;
};

/// Runs the crawler mission and writes its recording to `directory` (all or nothing).
CrawlerMissionResult run_crawler_mission(const CrawlerMissionScenario& scenario,
                                         const std::string& directory,
                                         const MissionRunOptions& options = {});

}  // namespace scantling::mission
