#pragma once
/// @file
/// A timed list of operator commands (SPEC §4 supervised autonomy): what an operator does
/// during a simulated or replayed mission ("pause at 12 s, take over at 20 s with 0.5 m/s
/// along x, hand back at 25 s"), fed to the MissionManager tick by tick. Read from YAML by
/// control/config_yaml.hpp's operator_script_from_yaml.
///
/// Times are seconds on the mission manager's clock. Commands at the same time keep their
/// order. Thread-safety: mutable (the position of the next command); one owner.
/// Cost: O(n log n) to build, O(commands due) per call.

#include <cstddef>
#include <vector>

#include <scantling/control/mission_manager.hpp>

namespace scantling::control {

struct TimedCommand {
    double time_s = 0.0;      ///< when it is due, s, finite
    OperatorCommand command;  ///< the velocity only for take_over
};

class OperatorScript {
  public:
    /// Sorts by time (stably). Throws InputError naming the first non-finite time or take-over
    /// velocity ("operator_script[2].time_s = nan, expected finite").
    explicit OperatorScript(std::vector<TimedCommand> commands = {});

    /// The commands with time_s ≤ `t_s` not returned before, in time order (each once).
    std::vector<OperatorCommand> due(double t_s);

    bool finished() const { return next_ == commands_.size(); }
    const std::vector<TimedCommand>& commands() const { return commands_; }  ///< sorted

  private:
    std::vector<TimedCommand> commands_;
    std::size_t next_ = 0;
};

}  // namespace scantling::control
