#include <scantling/control/operator_script.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include <scantling/core/error.hpp>

namespace scantling::control {
namespace {

void require_finite(const TimedCommand& timed, std::size_t index) {
    if (!std::isfinite(timed.time_s)) {
        throw InputError(
            fmt::format("operator_script[{}].time_s = {}, expected finite", index, timed.time_s));
    }
    const OperatorCommand& command = timed.command;
    if (!command.v_world_mps.allFinite() || !std::isfinite(command.yaw_rate_radps)) {
        throw InputError(
            fmt::format("operator_script[{}]: the take-over velocity ({}, {}, {}) "
                        "and yaw rate {} must be finite",
                        index, command.v_world_mps.x(), command.v_world_mps.y(),
                        command.v_world_mps.z(), command.yaw_rate_radps));
    }
}

}  // namespace

OperatorScript::OperatorScript(std::vector<TimedCommand> commands)
    : commands_(std::move(commands)) {
    for (std::size_t i = 0; i < commands_.size(); ++i) require_finite(commands_[i], i);
    std::stable_sort(
        commands_.begin(), commands_.end(),
        [](const TimedCommand& a, const TimedCommand& b) { return a.time_s < b.time_s; });
}

std::vector<OperatorCommand> OperatorScript::due(double t_s) {
    std::vector<OperatorCommand> due_now;
    while (!finished() && commands_[next_].time_s <= t_s)
        due_now.push_back(commands_[next_++].command);
    return due_now;
}

}  // namespace scantling::control
