// Freshness of one input stream (stream_watchdog.hpp).
#include <scantling/safety/stream_watchdog.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <scantling/core/error.hpp>

namespace scantling::safety {

std::string_view to_string(StreamChange change) {
    return change == StreamChange::kLost ? "lost" : "restored";
}

StreamWatchdog::StreamWatchdog(std::string name, double max_age_s, double start_s)
    : name_(std::move(name)), max_age_s_(max_age_s), last_s_(start_s) {
    if (!std::isfinite(max_age_s) || max_age_s <= 0.0) {
        throw ConfigError(
            fmt::format("{}: max age = {}, expected finite > 0 (seconds)", name_, max_age_s));
    }
    if (!std::isfinite(start_s)) throw InputError(fmt::format("{}: start time not finite", name_));
}

void StreamWatchdog::feed(double stamp_s) {
    if (!std::isfinite(stamp_s)) return;
    // An out-of-order sample does not make the stream younger than its newest one.
    last_s_ = fed_ ? std::max(last_s_, stamp_s) : stamp_s;
    fed_ = true;
}

std::optional<StreamTransition> StreamWatchdog::check(double t_s) {
    const bool now_lost = age_s(t_s) > max_age_s_;
    if (now_lost == lost_) return std::nullopt;
    lost_ = now_lost;
    return StreamTransition{now_lost ? StreamChange::kLost : StreamChange::kRestored, age_s(t_s)};
}

}  // namespace scantling::safety
