#pragma once
/// @file
/// Sensor faults injected between the simulator and the stack (issue 13, item 8): the link to
/// a sensor drops out, or delivers NaNs, for a time window. A mission scenario lists them:
///
///   faults:
///     - {sensor: spinning_lidar, kind: dropout, start_s: 20, duration_s: 2}
///     - {sensor: imu, kind: nan, start_s: 30, duration_s: 0.1}
///
/// `sensor` is a simulated sensor type (every sensor of that type is affected). A faulty
/// reading is not written to the recording (a recording holds what reached the robot, and our
/// readers refuse NaNs); a NaN reading still reaches the stack, whose input screening must drop
/// it (drone_stack.hpp). The loop writes a fault_started and a fault_ended event per window.
/// Windows are half-open, [start_s, start_s + duration_s), in readings' stamps.

#include <string_view>
#include <vector>

#include <scantling/sim/scenario.hpp>
#include <scantling/sim/sensor_reading.hpp>

namespace scantling::mission {

enum class FaultKind { kDropout, kNan };
std::string_view to_string(FaultKind kind);

struct SensorFault {
    sim::SensorType sensor = sim::SensorType::kSpinningLidar;
    FaultKind kind = FaultKind::kDropout;
    double start_s = 0.0;
    double duration_s = 0.0;  ///< > 0

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "fault") const;
};

/// A started or ended fault window, for the event log.
struct FaultChange {
    std::size_t fault = 0;  ///< index into the scenario's faults
    bool started = true;    ///< false: ended
};

class FaultInjector {
  public:
    /// `sensor_types[i]`: the type of the simulator's sensor i (SensorReading::sensor_index).
    FaultInjector(std::vector<SensorFault> faults, std::vector<sim::SensorType> sensor_types);

    /// The fault affecting `reading`, or nullptr.
    const SensorFault* fault_of(const sim::SensorReading& reading) const;
    /// Windows that started or ended at or before `t_s` since the previous call, in order.
    std::vector<FaultChange> changes(double t_s);
    const std::vector<SensorFault>& faults() const { return faults_; }

  private:
    std::vector<SensorFault> faults_;
    std::vector<sim::SensorType> sensor_types_;
    std::vector<int> phase_;  ///< per fault: 0 not started, 1 active, 2 ended
};

/// The reading with every measured value replaced by NaN (stamps and ids kept).
sim::SensorReading poisoned(sim::SensorReading reading);

}  // namespace scantling::mission
