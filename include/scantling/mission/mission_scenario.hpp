#pragma once
/// @file
/// A closed-loop mission scenario (issue 13, item 1): the simulated world, vehicle, sensors
/// and disturbances (`simulation:`, a whole simulator scenario, sim/scenario.hpp), where the
/// robot starts, the robot's stack configuration (`stack:`), the mission (`mission:`, tagged by
/// type: sweep, vertical, circular, goto, home; planning/config_yaml.hpp) and an optional
/// operator script (`operator:`, timed pause / resume / take_over / hand_back / go_home /
/// abort; control/config_yaml.hpp).
///
///   name: hull_sweep            # default: the file's stem
///   simulation: {world: ..., vehicle: {type: mav, mav: {wind: ...}}, sensors: [...], ...}
///   start: {xyz: [x, y, z], rpy_deg: [r, p, y]}
///   floor_height_m: 0.0          # world z of the floor under the range finder
///   linger_s: 1.0                # simulated time kept after the mission ends
///   stack: {odometry_sigma_m, collision_prevention, collision: {...}, height: {...},
///           manager: {...}, ...}
///   mission: {type: sweep, ...}
///   operator: [{time_s: 10, command: pause}, ...]
///   faults: [{sensor: spinning_lidar, kind: dropout, start_s: 20, duration_s: 2}, ...]
///                                (fault_injection.hpp)
///   coverage: {camera: {...}, mount: {...}, ...}   camera coverage of the inspected
///                                rectangle, a figure of the run (coverage_spec.hpp)
///
/// The robot's calibration comes from the simulated sensors: the LiDAR, IMU and range-finder
/// mounts and the UWB anchors' positions (a surveyed installation) are copied into the stack's
/// configuration. `simulation.duration_s` is the time limit of the run.
/// Errors name the file, line and key (ParseError) or the field (ConfigError), as everywhere.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include <scantling/control/operator_script.hpp>
#include <scantling/mission/coverage_spec.hpp>
#include <scantling/mission/drone_stack.hpp>
#include <scantling/mission/fault_injection.hpp>
#include <scantling/planning/waypoints.hpp>
#include <scantling/sim/scenario.hpp>

namespace scantling::mission {

struct MissionScenario {
    std::string name;
    std::string description;
    sim::Scenario simulation{};
    sim::PoseSpec start{};
    double floor_height_m = 0.0;  ///< world z of the floor the range finder sees
    double linger_s = 1.0;        ///< simulated after the mission completes or aborts, s, >= 0
    DroneStackConfig stack{};
    planning::WaypointPath path;
    std::vector<control::TimedCommand> operator_script;
    std::vector<SensorFault> faults;       ///< injected between the simulator and the stack
    std::optional<CoverageSpec> coverage;  ///< the camera-coverage figure (coverage_spec.hpp)

    Eigen::Isometry3d T_world_body_start() const { return start.to_isometry(); }
    /// Throws ConfigError naming the field (the simulation, the stack, the path).
    void validate() const;
};

/// Reads a mission scenario file (see the file comment), with `overrides` ("KEY=VALUE", KEY a
/// dotted path of map keys such as stack.manager.tracking.use_vtp, VALUE in YAML) applied to
/// the document first: what `scantling mission --set` passes. FileError, ParseError,
/// ConfigError (a malformed override names it).
MissionScenario load_mission_scenario(const std::string& path,
                                      const std::vector<std::string>& overrides = {});
/// The same for YAML text; `name` stands for the file in messages.
MissionScenario parse_mission_scenario(const std::string& yaml_text,
                                       const std::string& name = "<mission>");

}  // namespace scantling::mission
