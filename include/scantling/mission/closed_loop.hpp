#pragma once
/// @file
/// The closed loop (issue 13, item 1): the one place where the simulator and the robot's
/// stack meet. Each tick of the simulator's clock:
///   1. the simulator returns the ground truth and the readings due (sim/simulator.hpp);
///   2. the readings go to the recording and, as the io types a recording gives, to the stack
///      (drone_stack.hpp): motion and ranging samples first, then sweeps;
///   3. the operator script's commands due now and the stack's estimate give the command
///      (mission manager, VTP follower, PIDs, collision prevention), which the simulator holds
///      over the next tick.
/// The run ends when the mission has completed or aborted and `linger_s` has passed, or at
/// the scenario's `duration_s` (a "timeout" event).
///
/// The recording is a simulator recording (io/recording.hpp: ground truth and every sensor)
/// plus DIR/mission/ (io/mission_log.hpp: estimates at every tick, commands, events, the
/// intended path, summary.json with the figures below), written all or nothing like
/// run_scenario's. Deterministic: the same scenario and seed give the same recording for any
/// thread count (LiODOM runs on the loop's thread; the ray casting is thread-count
/// independent).

#include <functional>
#include <optional>
#include <string>

#include <scantling/mission/mission_scenario.hpp>

namespace scantling::mission {

struct MissionProgress {
    double sim_time_s = 0.0;
    double duration_s = 0.0;
    control::MissionState state = control::MissionState::kIdle;
};

struct MissionRunOptions {
    std::function<void(const MissionProgress&)> progress = {};  ///< about once per sim second
    bool overwrite = false;
    std::function<bool()> stop_requested = {};  ///< polled each tick (ScenarioInterrupted)
};

/// Wall time of the loop's stages over a run, s (issue 13, item 7).
struct LoopTiming {
    double simulate_s = 0.0;    ///< vehicle dynamics and the sensors (ray casting)
    double record_s = 0.0;      ///< the simulator's streams to the recording
    double odometry_s = 0.0;    ///< the stack's sweeps: LiODOM and the increment's EKF update
    double estimators_s = 0.0;  ///< IMU, range-finder, barometer and UWB updates of both EKFs
    double command_s = 0.0;     ///< mission manager, collision prevention, height keeping
    double log_s = 0.0;         ///< estimates, commands, events and metrics kept per tick
};

/// Figures of one run (also written to mission/summary.json).
struct MissionResult {
    std::string directory;
    control::MissionState final_state = control::MissionState::kIdle;
    bool completed = false;
    double mission_time_s = 0.0;  ///< from start to completion (or to the end of the run)
    double sim_time_s = 0.0;
    double wall_time_s = 0.0;
    double real_time_factor = 0.0;
    /// True distance of the vehicle to the intended path (the polyline from the start through
    /// the waypoints) while the mission was running, m.
    double path_deviation_mean_m = 0.0;
    double path_deviation_max_m = 0.0;
    /// Estimate (global EKF) against the ground truth at every tick, m and rad.
    double position_error_rms_m = 0.0;
    double position_error_max_m = 0.0;
    double final_position_error_m = 0.0;
    double yaw_error_rms_rad = 0.0;
    double path_length_m = 0.0;  ///< travelled (true)
    /// Average NEES of the position estimate (3 DoF; 3 when consistent).
    double position_nees_mean = 0.0;
    std::size_t waypoints_reached = 0;
    std::size_t waypoints = 0;
    std::size_t safety_interventions = 0;  ///< ticks where the safety layer changed the command
    double min_obstacle_distance_m = 0.0;  ///< nearest LiDAR return while flying, m
    std::size_t lidar_sweeps = 0;
    std::size_t events = 0;
    /// The estimators' counters: LiODOM increments, range-finder heights and UWB ranges
    /// fused or refused by their χ² gates.
    std::size_t increments_applied = 0;
    std::size_t increments_rejected = 0;
    std::size_t ranges_applied = 0;
    std::size_t ranges_rejected = 0;
    std::size_t uwb_applied = 0;
    std::size_t uwb_rejected = 0;
    std::size_t uwb_reacquisitions = 0;  ///< the global EKF re-opened after a run of refusals
    std::size_t inputs_rejected = 0;     ///< non-finite samples dropped by the stack's screening
    /// LiODOM's verdicts on the sweeps it was given: registered (ok + degenerate), of which
    /// degenerate, and not registered (no edges, too few correspondences: motion model).
    std::size_t odometry_registered = 0;
    std::size_t odometry_degenerate = 0;
    /// Outer iterations (correspondence searches) over the registered sweeps: LiODOM's cost.
    std::size_t odometry_iterations = 0;
    std::size_t odometry_unregistered = 0;
    LoopTiming timing;
    /// The camera coverage of the inspected rectangle, when the scenario asks (coverage_spec.hpp).
    std::optional<perception::CoverageResult> coverage;
};

/// Runs the mission and writes its recording to `directory` (see the file comment). Throws
/// ConfigError, FileError (as run_scenario), sim::ScenarioInterrupted when stopped.
MissionResult run_mission(const MissionScenario& scenario, const std::string& directory,
                          const MissionRunOptions& options = {});

}  // namespace scantling::mission
