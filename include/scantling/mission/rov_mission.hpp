#pragma once
/// @file
/// The ROV hull survey in closed loop (issue 14; SPEC §5): a mission scenario whose vehicle is
/// the simulated ROV and whose robot is the RovStack (rov_stack.hpp), and the loop that runs
/// it. Each tick the simulator returns the readings due; they go to the recording and, as io
/// types, to the stack (IMU, DVL, pressure first, then sonar pings and camera images); the
/// stack's command (a water-relative world velocity and a yaw rate) moves the vehicle over the
/// next tick. The recording is a simulator recording plus DIR/mission/ as the drone's loop
/// writes it (closed_loop.hpp, io/mission_log.hpp), with the sonar inspection map's voxels
/// (mission/sonar_map.csv) and summary.json holding the survey's figures below.
///
///   name: hull_survey_horizontal     # default: the file's stem
///   simulation: {world: {type: ship_hull, ...}, vehicle: {type: rov, rov: {current: ...}},
///                sensors: [multibeam_sonar, camera, imu, pressure, dvl], duration_s, ...}
///   start: {xyz: [x, y, z], rpy_deg: [0, 0, yaw]}
///   linger_s: 1.0
///   mission:
///     type: hull_survey
///     hull: {xyz: [...], rpy_deg: [0, 0, yaw]}   # T_world_hull: the plan's hull frame
///     plan: {length_m, draught_m, stand_off_m, orientation, overlap, ...}
///                                     # planning/hull_survey_plan.hpp's keys: the section
///     margin_m: 0.1                   # the plan flown reaches this far beyond the section
///   stack: {guidance: {...}, adapter: {...}, hull_line: {...}, contact: {...},
///           coverage: {...}, max_reinspection_rounds, ...}
///   operator: [{time_s, command: pause | resume | abort}]
///   faults: [{sensor: dvl, kind: dropout, start_s, duration_s}]
///   coverage: {camera: {...}, mount: {...}, max_mm_per_px, ...}   # the figure (true poses);
///                                     # default rectangle: the surveyed section
///
/// The robot's calibration comes from the simulated sensors: the IMU, DVL, sonar and camera
/// mounts, the camera's intrinsics and lasers, the water surface of the pressure sensor. The
/// plan's stand-off and speed set the adapter's stand-off, the re-inspection's stand-off and
/// footprint and the stack's survey speed.
///
/// Stand-off and heading are measured on the truth: per tick, a ray from the true camera
/// centre along the vehicle's heading (horizontal) to the world; the stand-off is the
/// perpendicular distance to the surface hit (range · |cos| of the ray to the hit's normal),
/// the heading error the horizontal angle between the heading and the surface's inward normal.
/// Ticks while the mission runs and the ray hits the hull within 3 m count; a ray that meets
/// an appendage (anode, grating, bilge keel) is not a sample: the stand-off is the plating's.
/// Errors name the file, line and key (ParseError) or the field (ConfigError).

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <scantling/control/operator_script.hpp>
#include <scantling/mission/closed_loop.hpp>
#include <scantling/mission/coverage_spec.hpp>
#include <scantling/mission/fault_injection.hpp>
#include <scantling/mission/rov_stack.hpp>
#include <scantling/planning/hull_survey_plan.hpp>
#include <scantling/sim/scenario.hpp>

namespace scantling::mission {

struct RovMissionScenario {
    std::string name;
    std::string description;
    sim::Scenario simulation{};
    sim::PoseSpec start{};
    double linger_s = 1.0;  ///< simulated after the mission completes or aborts, s, >= 0
    sim::PoseSpec hull{};   ///< T_world_hull (hull_survey_plan.hpp's hull frame), z up
    planning::HullSurveyPlanConfig plan{};  ///< the section: its length and draught
    /// The plan flown reaches this far beyond the section on every side (its ends, the keel
    /// side and, above the water line, the surface side), m, >= 0: the footprints end exactly
    /// at the section's edges otherwise, and centimetres of stand-off or depth error open a
    /// gap along them.
    double margin_m = 0.1;
    RovStackConfig stack{};
    std::vector<control::TimedCommand> operator_script;
    std::vector<SensorFault> faults;
    std::optional<CoverageSpec> coverage;  ///< the true camera-coverage figure

    Eigen::Isometry3d T_world_body_start() const { return start.to_isometry(); }
    /// The plan flown: the section grown by margin_m on every side, and where its hull frame
    /// lies (the section's shifted by (−margin, 0, +margin)).
    planning::HullSurveyPlanConfig flown_plan() const;
    Eigen::Isometry3d T_world_flown_hull() const;
    /// The surveyed section as a wall rectangle: lower-left corner (hull x = 0, at the keel
    /// depth), normal from the hull into the water (hull −y), width the length, height the
    /// draught.
    planning::WallRectangle section() const;
    /// Throws ConfigError naming the field.
    void validate() const;
};

/// True when the document's `mission.type` is `hull_survey` (the ROV's mission), false for the
/// drone's missions. FileError / ParseError as the readers.
bool is_rov_mission_file(const std::string& path);

/// Reads an ROV mission scenario (see the file comment) with `--set` overrides applied first.
RovMissionScenario load_rov_mission_scenario(const std::string& path,
                                             const std::vector<std::string>& overrides = {});
RovMissionScenario parse_rov_mission_scenario(const std::string& yaml_text,
                                              const std::string& name = "<mission>");

/// Figures of one ROV run (also in mission/summary.json).
struct RovMissionResult {
    std::string directory;
    control::MissionState final_state = control::MissionState::kIdle;
    bool completed = false;
    double mission_time_s = 0.0;  ///< start to completion (or to the end of the run)
    double sim_time_s = 0.0;
    double wall_time_s = 0.0;
    double real_time_factor = 0.0;
    std::size_t waypoints_survey = 0;  ///< the initial plan's
    /// True stand-off error |d − d_wanted| (see the file comment), m, and heading error, rad.
    double stand_off_error_mean_m = 0.0;
    double stand_off_error_max_m = 0.0;
    double heading_error_mean_rad = 0.0;
    double heading_error_max_rad = 0.0;
    std::size_t stand_off_samples = 0;
    /// The estimate against the truth at every tick, m and rad.
    double position_error_rms_m = 0.0;
    double position_error_max_m = 0.0;
    double yaw_error_rms_rad = 0.0;
    double path_length_m = 0.0;  ///< travelled (true)
    std::size_t guidance_paused_ticks = 0;
    std::size_t backing_off_ticks = 0;
    std::size_t contacts = 0;
    std::size_t pings = 0;
    std::size_t hull_lines = 0;
    std::size_t laser_measurements = 0;
    std::size_t images = 0;
    double laser_distance_error_mean_m = 0.0;  ///< |laser distance − true optical-axis range|
    std::size_t dvl_invalid = 0;
    std::size_t inputs_rejected = 0;
    std::size_t events = 0;
    /// The coverage the robot believes (its estimated views), before and after re-inspection.
    double believed_coverage_survey = 0.0;
    double believed_coverage_final = 0.0;
    std::size_t holes_found = 0;
    std::size_t reinspection_rounds = 0;
    std::size_t sonar_voxels = 0;  ///< existing voxels of the sonar inspection map
    double sonar_voxel_uncertainty_mean_m = 0.0;
    /// The section's share covered by the sonar map's voxels (mapping::coverage_of), a figure
    /// only: the re-inspection follows the camera's believed coverage, since a horizontal
    /// slice's 20° fan covers a band a third of the camera footprint's height.
    double sonar_coverage = 0.0;
    /// The true camera coverage (coverage: figure), after the survey and at the end.
    std::optional<perception::CoverageResult> coverage_survey;
    std::optional<perception::CoverageResult> coverage;
    LoopTiming timing;
};

/// Runs the ROV mission and writes its recording to `directory` (all or nothing). Throws
/// ConfigError, FileError, sim::ScenarioInterrupted when stopped.
RovMissionResult run_rov_mission(const RovMissionScenario& scenario, const std::string& directory,
                                 const MissionRunOptions& options = {});

}  // namespace scantling::mission
