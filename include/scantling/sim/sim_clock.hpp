#pragma once
/// @file
/// The simulator's fixed-step clock and the per-sensor firing schedules (SPEC §10: "fixed-step
/// clock; each sensor fires at its own rate").
///
/// Time is kept in integers: the step dt and each schedule's phase in whole nanoseconds, each
/// rate in whole micro-hertz (the given values are rounded to these units). Tick k is the time
/// t_k = start + k dt; schedule i nominally fires at phase + n / rate (n = 0, 1, ...) after
/// the start, and fires *at tick k* for every nominal time in (t_{k−1}, t_k] (tick 0: every
/// nominal time <= t_0). Counts come from integer floor divisions, so there is no drift:
/// over [0, T) a rate f fires exactly ⌈(T − phase) f⌉ times whatever dt is (e.g. 300 times
/// for 30 Hz over 10 s, with dt = 1 ms or 5 ms). A rate above 1 / dt fires several times in
/// one tick (`fire_count`).
///
/// Thread-safety: a SimClock is mutable; queries are const. Determinism: integer arithmetic.

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace scantling::sim {

/// When a sensor fires: at phase_s + n / rate_hz after the clock start.
struct RateSchedule {
    double rate_hz = 10.0;  ///< > 0, at most 1e6 (rounded to 1 µHz)
    double phase_s = 0.0;   ///< >= 0, at most 1e6 s (rounded to 1 ns)

    /// Throws ConfigError naming the field ("rate_schedule.rate_hz = 0, expected ...").
    void validate(std::string_view prefix = "rate_schedule") const;
};

class SimClock {
  public:
    /// `dt_s` in [1e-9, 1e3] s (rounded to whole nanoseconds); ConfigError ("sim_clock.dt_s")
    /// otherwise, or when start_s is not finite.
    explicit SimClock(double dt_s, double start_s = 0.0);

    /// Registers a schedule and returns its index (0, 1, ...). Throws ConfigError naming
    /// "sim_clock.schedules[i].<field>".
    std::size_t add(const RateSchedule& schedule);

    /// Moves to the next tick.
    void advance() { ++tick_; }

    std::int64_t tick() const { return tick_; }
    /// start + tick · dt, computed from the tick count (no accumulated rounding).
    double now_s() const;
    double dt_s() const;
    std::size_t num_schedules() const { return schedules_.size(); }

    /// Firings of schedule `i` at the current tick (0 when not due). InputError for a bad i.
    std::int64_t fire_count(std::size_t i) const;
    bool due(std::size_t i) const { return fire_count(i) > 0; }
    /// Indices of the schedules due at the current tick, ascending.
    std::vector<std::size_t> due_now() const;
    /// Firings of schedule `i` from the start up to and including the current tick.
    std::int64_t total_fired(std::size_t i) const;
    /// Nominal time (start + phase + n / rate, seconds) of the latest firing of schedule `i` up
    /// to the current tick; a sensor stamps its measurement with it. InputError when it has
    /// not fired yet.
    double last_fire_time_s(std::size_t i) const;

  private:
    struct Schedule {
        std::int64_t rate_uhz = 0;
        std::int64_t phase_ns = 0;
    };

    const Schedule& schedule(std::size_t i) const;
    std::int64_t fired_up_to(const Schedule& s, std::int64_t tick) const;

    std::int64_t dt_ns_ = 0;
    double start_s_ = 0.0;
    std::int64_t tick_ = 0;
    std::vector<Schedule> schedules_;
};

}  // namespace scantling::sim
