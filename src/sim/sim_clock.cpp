#include <scantling/core/error.hpp>
#include <scantling/sim/sim_clock.hpp>

#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <cmath>

namespace scantling::sim {
namespace {

__extension__ typedef __int128 Int128;  // products of ns and µHz exceed 64 bits

constexpr std::int64_t kNsPerS = 1'000'000'000;
constexpr std::int64_t kUhzPerHz = 1'000'000;
constexpr Int128 kNsUhzPerCycle = static_cast<Int128>(kNsPerS) * kUhzPerHz;

}  // namespace

void RateSchedule::validate(std::string_view prefix) const {
    detail::require(std::isfinite(rate_hz) && rate_hz >= 1e-6 && rate_hz <= 1e6, prefix, "rate_hz",
                    rate_hz, "in [1e-6, 1e6] Hz");
    detail::require(std::isfinite(phase_s) && phase_s >= 0.0 && phase_s <= 1e6, prefix, "phase_s",
                    phase_s, "in [0, 1e6] s");
}

SimClock::SimClock(double dt_s, double start_s) : start_s_(start_s) {
    detail::require(std::isfinite(dt_s) && dt_s >= 1e-9 && dt_s <= 1e3, "sim_clock", "dt_s", dt_s,
                    "in [1e-9, 1e3] s");
    detail::require(std::isfinite(start_s), "sim_clock", "start_s", start_s, "finite");
    dt_ns_ = std::llround(dt_s * kNsPerS);
}

std::size_t SimClock::add(const RateSchedule& schedule) {
    schedule.validate(fmt::format("sim_clock.schedules[{}]", schedules_.size()));
    schedules_.push_back(
        {std::llround(schedule.rate_hz * kUhzPerHz), std::llround(schedule.phase_s * kNsPerS)});
    return schedules_.size() - 1;
}

double SimClock::now_s() const {
    return start_s_ + static_cast<double>(tick_ * dt_ns_) / static_cast<double>(kNsPerS);
}

double SimClock::dt_s() const { return static_cast<double>(dt_ns_) / kNsPerS; }

const SimClock::Schedule& SimClock::schedule(std::size_t i) const {
    if (i >= schedules_.size()) {
        throw InputError(
            fmt::format("SimClock: schedule {} of {} does not exist", i, schedules_.size()));
    }
    return schedules_[i];
}

std::int64_t SimClock::fired_up_to(const Schedule& s, std::int64_t tick) const {
    if (tick < 0) return 0;
    const Int128 elapsed_ns = static_cast<Int128>(tick) * dt_ns_ - s.phase_ns;
    if (elapsed_ns < 0) return 0;
    // Firing n happens at phase + n / rate: n <= elapsed · rate.
    return static_cast<std::int64_t>(elapsed_ns * s.rate_uhz / kNsUhzPerCycle) + 1;
}

std::int64_t SimClock::fire_count(std::size_t i) const {
    const Schedule& s = schedule(i);
    return fired_up_to(s, tick_) - fired_up_to(s, tick_ - 1);
}

std::vector<std::size_t> SimClock::due_now() const {
    std::vector<std::size_t> due;
    for (std::size_t i = 0; i < schedules_.size(); ++i) {
        if (fire_count(i) > 0) due.push_back(i);
    }
    return due;
}

std::int64_t SimClock::total_fired(std::size_t i) const { return fired_up_to(schedule(i), tick_); }

double SimClock::last_fire_time_s(std::size_t i) const {
    const Schedule& s = schedule(i);
    const std::int64_t fired = fired_up_to(s, tick_);
    if (fired == 0) {
        throw InputError(fmt::format("SimClock: schedule {} has not fired yet", i));
    }
    const double n = static_cast<double>(fired - 1);
    return start_s_ + static_cast<double>(s.phase_ns) / kNsPerS +
           n * static_cast<double>(kUhzPerHz) / static_cast<double>(s.rate_uhz);
}

}  // namespace scantling::sim
