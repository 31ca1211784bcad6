#pragma once
/// @file
/// Freshness of one input stream (issue 13, item 8): a sensor that stops (a LiDAR silent for
/// 2 s, an IMU gap, a cable pulled) must become a reported event and a safe reaction, not a
/// stale value silently reused. The watchdog says when the stream was lost and restored; the
/// caller decides the reaction (the drone stack hovers, drone_stack.hpp).
///
/// A stream is lost when no sample has arrived for more than `max_age_s`, counted from the
/// watchdog's start when none ever came (a sensor that never starts is lost too), and restored
/// by the next sample. `check` reports each change once, at the first check that sees it.
///
/// Units: seconds, one clock for samples and checks. Not thread-safe; O(1).

#include <optional>
#include <string>
#include <string_view>

namespace scantling::safety {

enum class StreamChange { kLost, kRestored };
std::string_view to_string(StreamChange change);

struct StreamTransition {
    StreamChange change = StreamChange::kLost;
    double age_s = 0.0;  ///< time since the last sample (or the start) when it was seen
};

class StreamWatchdog {
  public:
    /// `max_age_s`: finite > 0 (ConfigError naming `name`); `start_s` finite.
    StreamWatchdog(std::string name, double max_age_s, double start_s);

    /// A sample stamped `stamp_s` arrived (non-finite stamps are ignored: not a sample).
    void feed(double stamp_s);
    /// The change since the previous check, if any.
    std::optional<StreamTransition> check(double t_s);
    /// True while the last check found the stream lost.
    bool lost() const { return lost_; }
    /// Time since the last sample (or the start) at `t_s`.
    double age_s(double t_s) const { return t_s - last_s_; }
    const std::string& name() const { return name_; }
    bool ever_fed() const { return fed_; }

  private:
    std::string name_;
    double max_age_s_;
    double last_s_;
    bool fed_ = false;
    bool lost_ = false;
};

}  // namespace scantling::safety
