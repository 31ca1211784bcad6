#pragma once
/// @file
/// Runs a scenario and writes its recording (issue 3, items 3–5).
///
/// Clock: fixed steps of `dt_s` (SimClock); tick k is t = k · dt for k = 0 .. ⌊duration/dt⌋.
/// The vehicle is simulated first over all ticks (it does not depend on the sensors): a
/// scripted vehicle samples its trajectory, a MAV, ROV or legged base tracks it with a P
/// controller plus feed-forward (v_cmd = v_ref + k_p (p_ref − p), ψ̇_cmd = ψ̇_ref + k_ψ
/// wrap(ψ_ref − ψ)), a crawler pursues it on the world's surface (so the world is built first).
/// Ground truth is logged at every tick. Each sensor fires at its own rate on the integer
/// schedule of SimClock and is stamped with its nominal firing time; the pose at a firing
/// time between two ticks is interpolated (slerp, linear translation) from the ticks, and the
/// motion state for IMU/VIO is the one of the tick (dt ≤ 1 / rate keeps them exact); the VIO's
/// feature quality is cast from the tick pose (vio_features.hpp, no random draws). A
/// spinning-LiDAR sweep started at t covers [t, t + 1/rate); without motion distortion it is cast
/// from the pose at t; with it each column is cast from its own pose (scan_moving).
///
/// Determinism: the vehicle and every sensor draw from their own stream
/// Rng(seed).split(k) (k = 0 vehicle, 1 + i sensor i, 100 map sampling), so the same scenario
/// and seed give byte-identical recordings for any thread count; adding a sensor does not
/// change the others' noise.
/// Libraries never print: progress goes through a callback.

#include <functional>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/sim/recording_writer.hpp>
#include <scantling/sim/scenario.hpp>

namespace scantling::sim {

struct ScenarioProgress {
    double sim_time_s = 0.0;  ///< simulated time reached
    double duration_s = 0.0;  ///< total simulated time
    std::int64_t lidar_sweeps = 0;
};

struct ScenarioRunOptions {
    /// Called after the world is built, about once per simulated second, and at the end.
    std::function<void(const ScenarioProgress&)> progress;
    /// Replace an existing recording at the directory (see RecordingWriter).
    bool overwrite = false;
    /// Polled between ticks and before the recording is moved into place: when it returns
    /// true the run stops with ScenarioInterrupted (e.g. a flag set by a SIGINT handler).
    std::function<bool()> stop_requested = {};  // "= {}": may be left out of {.x = ...}
};

/// The run was stopped by ScenarioRunOptions::stop_requested; no recording was written.
class ScenarioInterrupted : public Error {
  public:
    using Error::Error;
};

struct ScenarioRunResult {
    std::string directory;
    RecordingCounts counts;
    double duration_s = 0.0;   ///< simulated
    double wall_time_s = 0.0;  ///< whole run, world build and export included
    std::size_t world_triangles = 0;
};

/// Simulated duration of a scenario: `duration_s`, or the trajectory's when it is 0.
double scenario_duration_s(const Scenario& scenario);

/// Builds the world, simulates and writes the recording to `directory`, all or nothing: the
/// files go to a temporary folder beside it that is renamed to `directory` at the end
/// (RecordingWriter). Throws ConfigError for an invalid scenario, FileError when the directory
/// is not empty (without overwrite), is not a recording (with overwrite) or a file cannot be
/// written (with the OS reason, e.g. "No space left on device"), ScenarioInterrupted when
/// stopped; in every case no partial recording is left and an existing one is untouched.
/// The temporary folder is created only after the world was built.
ScenarioRunResult run_scenario(const Scenario& scenario, const std::string& directory,
                               const ScenarioRunOptions& options = {});

}  // namespace scantling::sim
