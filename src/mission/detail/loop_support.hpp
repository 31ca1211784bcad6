#pragma once
// What the vehicles' closed loops share (closed_loop.cpp, rov_loop.cpp, crawler_loop.cpp,
// exploration_loop.cpp): the stage clock, the mission files besides the simulator's streams,
// the logging of operator commands and injected faults, the world's export and the wall time.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <scantling/control/mission_manager.hpp>
#include <scantling/control/operator_script.hpp>
#include <scantling/io/mission_log.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/localization/local_ekf.hpp>
#include <scantling/mission/closed_loop.hpp>
#include <scantling/mission/fault_injection.hpp>
#include <scantling/planning/waypoints.hpp>
#include <scantling/sim/recording_writer.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/simulator.hpp>

namespace scantling::mission::detail {

/// Accumulates the wall time of the scope into `total_s`.
class StageClock {
  public:
    explicit StageClock(double& total_s) : total_s_(total_s) {}
    ~StageClock() {
        total_s_ +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    StageClock(const StageClock&) = delete;
    StageClock& operator=(const StageClock&) = delete;

  private:
    double& total_s_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// Everything the loop writes besides the simulator's streams.
struct MissionFiles {
    std::vector<io::EstimateRecord> estimates;
    std::vector<io::CommandRecord> commands;
    std::string events;
    std::size_t num_events = 0;
    bool limited = false;  ///< the safety layer's state at the previous tick

    void add_event(double t_s, const std::string& type, const std::string& json) {
        events += io::event_line(t_s, type, json);
        ++num_events;
    }
};

void write_text(const std::string& path, const std::string& text);

/// One reading on its way to the stack: inside a dropout window of `faults` nothing; inside a
/// NaN window the reading poisoned (fault_injection.hpp), not recorded; otherwise recorded
/// (its time into `record_s`, unless `record` is false) and then given to `feed`. True when it
/// was recorded.
template <class Feed>
bool deliver(const sim::SensorReading& reading, const FaultInjector& faults,
             sim::RecordingWriter& writer, double& record_s, Feed&& feed, bool record = true) {
    if (const SensorFault* fault = faults.fault_of(reading)) {
        if (fault->kind == FaultKind::kNan) feed(poisoned(reading));
        return false;
    }
    if (record) {
        StageClock clock(record_s);
        writer.add(reading);
    }
    feed(reading);
    return record;
}

/// A simulated IMU sample and UWB round as the io records a recording gives.
io::ImuRecord imu_record(const sim::ImuSample& sample);
std::vector<io::UwbRecord> uwb_records(const sim::UwbMeasurement& round);

/// One tick's line of mission/estimates.csv: the stack's world estimate and its 1σ.
io::EstimateRecord estimate_record(const localization::DroneState& estimate, double t_s,
                                   bool valid);

/// sim::ScenarioInterrupted (nothing written) when the caller asked the run to stop.
void throw_if_stop_requested(const MissionRunOptions& options, const sim::Simulator& sim,
                             const std::string& directory);

/// The operator script's commands due now, after the start that begins every run at tick 0.
std::vector<control::OperatorCommand> operator_commands_due(control::OperatorScript& script,
                                                            const sim::Simulator& sim);

void log_operator(MissionFiles& files, std::span<const control::OperatorCommand> commands,
                  double t_s);
void log_faults(MissionFiles& files, FaultInjector& faults, double t_s);

std::vector<sim::SensorType> sensor_types(const sim::Scenario& simulation);

/// The mission is over (completed or aborted): the loop lingers, then stops.
inline bool mission_ended(control::MissionState state) {
    return state == control::MissionState::kCompleted || state == control::MissionState::kAborted;
}

/// DIR/world/ (the world's map, mesh and metadata) when the scenario exports it.
void write_world_if_exported(sim::RecordingWriter& writer, const sim::Scenario& simulation,
                             const sim::Simulator& sim);

/// The result's wall time since `wall_start` and its real-time factor over `sim_time_s`.
template <class Result>
void stamp_wall_time(Result& result, std::chrono::steady_clock::time_point wall_start) {
    result.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    result.real_time_factor = result.sim_time_s / std::max(result.wall_time_s, 1e-9);
}

/// summary.json's scenario block of the recording.
sim::RecordingSummary recording_summary(const std::string& name, const std::string& description,
                                        const sim::Scenario& simulation, const sim::Simulator& sim);

/// DIR/mission/: estimates (CSV and TUM), commands, events, the intended path and `summary`
/// (summary.json), in the writer's staging directory.
void write_mission_files(const sim::RecordingWriter& writer, const MissionFiles& files,
                         const planning::WaypointPath& path, const std::string& summary);

}  // namespace scantling::mission::detail
