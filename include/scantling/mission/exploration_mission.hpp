#pragma once
/// @file
/// Exploration of an unknown tank in closed loop (issue 16 item 3; SPEC §8, thesis art. G): a
/// mission scenario whose vehicle is the simulated MAV and whose robot is the
/// ExplorationStack (exploration_stack.hpp), and the loop that runs it. Each tick the
/// simulator returns the readings due; IMU, VIO and barometer go to the stack first, then the
/// depth frames and the camera's defect sightings; the stack's command (a world velocity and a
/// yaw rate) moves the vehicle over the next tick.
///
///   name: ballast_large_explore        # default: the file's stem
///   simulation: {world: {type: ballast_tank_large}, vehicle: {type: mav},
///                sensors: [imu, vio, barometer, depth_camera, camera], duration_s, seed}
///   start: {xyz: [x, y, z], rpy_deg: [0, 0, yaw]}
///   linger_s: 1.0
///   mission:
///     type: explore
///     bounds: {min: [x, y, z], max: [x, y, z]}   # the exploration volume (the planner's
///                                                 # samples and the figures), world, m
///     record_depth_every: 25     # the recording keeps one depth frame in this many (the map
///                                # is built from all of them); 0: none
///     volume_every_s: 10         # the explored-volume curve's period, s
///   stack: {max_speed_mps, max_yaw_rate_radps, map: {resolution_m, ...}, nbv: {...}, ...}
///   operator: [{time_s, command: pause | resume | abort | take_over | hand_back}]
///   faults: [{sensor: vio, kind: dropout, start_s, duration_s}]
///
/// The robot's calibration comes from the simulated sensors: the IMU, depth-camera and camera
/// mounts and the camera's intrinsics; the planner's camera view is the depth camera's field
/// of view with the map's maximum range, and its bounds are the mission's.
///
/// The figures (mission/summary.json, mission/exploration.csv): the explored volume (the
/// octree's known leaves inside the bounds) against time; the share of the reachable free
/// volume mapped, where the reachable free volume is the ground truth: the voxels of the map's
/// resolution inside the bounds that no surface of the world crosses (rays cast through every
/// voxel centre along the three axes), 6-connected to the start; planning time per
/// iteration; path length; detections (defect sightings) per camera image.
/// Errors name the file, line and key (ParseError) or the field (ConfigError); a start inside
/// the world's surfaces (no reachable free space as large as the vehicle box) is an InputError
/// naming `start`, raised before anything is written.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include <scantling/control/operator_script.hpp>
#include <scantling/mission/closed_loop.hpp>
#include <scantling/mission/exploration_stack.hpp>
#include <scantling/mission/fault_injection.hpp>
#include <scantling/sim/scenario.hpp>

namespace scantling::mission {

struct ExplorationMissionScenario {
    std::string name;
    std::string description;
    sim::Scenario simulation{};
    sim::PoseSpec start{};
    double linger_s = 1.0;  ///< simulated after the mission completes or aborts, s, >= 0
    Eigen::AlignedBox3d bounds_world{};  ///< the exploration volume
    int record_depth_every = 25;         ///< >= 0; 0 records no depth frame
    double volume_every_s = 10.0;        ///< > 0
    ExplorationStackConfig stack{};
    std::vector<control::TimedCommand> operator_script;
    std::vector<SensorFault> faults;

    Eigen::Isometry3d T_world_body_start() const { return start.to_isometry(); }
    /// Throws ConfigError naming the field.
    void validate() const;
};

/// One point of the explored-volume curve.
struct ExploredSample {
    double t_s = 0.0;
    double explored_m3 = 0.0;      ///< known voxels inside the bounds
    double reachable_share = 0.0;  ///< of the reachable free volume, known
    double path_length_m = 0.0;    ///< travelled so far (true)
};

struct ExplorationMissionResult {
    std::string directory;
    control::MissionState final_state = control::MissionState::kIdle;
    bool completed = false;           ///< the planner found no gain left
    double exploration_time_s = 0.0;  ///< from the start to the end of exploring
    double sim_time_s = 0.0;
    double wall_time_s = 0.0;
    double real_time_factor = 0.0;
    double path_length_m = 0.0;      ///< travelled (true)
    double reachable_free_m3 = 0.0;  ///< ground truth
    double explored_m3 = 0.0;        ///< known inside the bounds, at the end
    double reachable_share = 0.0;    ///< of the reachable free volume, known at the end
    std::size_t plans = 0;
    std::size_t plans_failed = 0;
    double plan_time_mean_s = 0.0;
    double plan_time_max_s = 0.0;
    std::size_t images = 0;
    std::size_t detections = 0;  ///< defect sightings over all images
    double detections_per_image = 0.0;
    std::size_t defects_mapped = 0;
    std::size_t defects_in_world = 0;
    double position_error_rms_m = 0.0;
    double position_error_final_m = 0.0;
    double min_wall_distance_m = 0.0;  ///< nearest surface to the true position while flying
    std::size_t inputs_rejected = 0;
    std::size_t events = 0;
    std::vector<ExploredSample> curve;
    LoopTiming timing;
};

ExplorationMissionResult run_exploration_mission(const ExplorationMissionScenario& scenario,
                                                 const std::string& directory,
                                                 const MissionRunOptions& options = {});

/// True when the file's `mission.type` is explore.
bool is_exploration_mission_file(const std::string& path);
/// Reads an exploration mission file with `--set` overrides. FileError, ParseError,
/// ConfigError.
ExplorationMissionScenario load_exploration_mission_scenario(
    const std::string& path, const std::vector<std::string>& overrides = {});
ExplorationMissionScenario parse_exploration_mission_scenario(
    const std::string& yaml_text, const std::string& name = "<mission>");

}  // namespace scantling::mission
