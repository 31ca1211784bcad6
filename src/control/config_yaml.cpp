#include <scantling/control/config_yaml.hpp>

#include <utility>
#include <vector>

namespace scantling::control {
namespace {

using io::ConfigNode;
using io::ConfigSchema;
using io::kNonNegative;
using io::kPositive;
using io::detail::join_key;

/// The command's name and velocity; time_s is read beside it (it is TimedCommand's).
const ConfigSchema<OperatorCommand>& operator_command_schema() {
    using C = OperatorCommandType;
    static const ConfigSchema<OperatorCommand> schema = [] {
        ConfigSchema<OperatorCommand> s;
        s.enum_field("command", &OperatorCommand::type,
                     {{"start", C::kStart},
                      {"pause", C::kPause},
                      {"resume", C::kResume},
                      {"take_over", C::kTakeOver},
                      {"hand_back", C::kHandBack},
                      {"go_home", C::kGoHome},
                      {"abort", C::kAbort}},
                     "the operator's command")
            .field("v_world_mps", &OperatorCommand::v_world_mps, "take_over: velocity, world, m/s")
            .field("yaw_rate_radps", &OperatorCommand::yaw_rate_radps,
                   "take_over: yaw rate about world z, rad/s");
        return s;
    }();
    return schema;
}

const ConfigNode& required(const ConfigNode& item, const std::string& key,
                           const std::string& path) {
    const ConfigNode* value = item.is_map() ? item.find(key) : nullptr;
    if (value == nullptr) io::detail::fail(item, join_key(path, key), "missing");
    return *value;
}

TimedCommand timed_command_from_yaml(const ConfigNode& item, const std::string& path) {
    TimedCommand timed;
    ConfigNode rest = item;
    if (rest.is_map()) std::erase_if(rest.map, [](const auto& e) { return e.first == "time_s"; });
    operator_command_schema().apply(rest, timed.command, path);
    timed.time_s = io::detail::parse_real(required(item, "time_s", path), join_key(path, "time_s"),
                                          kNonNegative);
    required(item, "command", path);
    for (const char* key : {"v_world_mps", "yaw_rate_radps"}) {
        const ConfigNode* value = item.find(key);
        if (value != nullptr && timed.command.type != OperatorCommandType::kTakeOver) {
            io::detail::fail(*value, join_key(path, key), "only take_over takes a velocity");
        }
    }
    return timed;
}

}  // namespace

const ConfigSchema<PidConfig>& pid_schema() {
    static const ConfigSchema<PidConfig> schema = [] {
        ConfigSchema<PidConfig> s;
        s.field("kp", &PidConfig::kp, "proportional gain", kNonNegative)
            .field("ki", &PidConfig::ki, "integral gain, 1/s", kNonNegative)
            .field("kd", &PidConfig::kd, "derivative gain (on the measurement), s", kNonNegative)
            .field("derivative_filter_s", &PidConfig::derivative_filter_s,
                   "tau_f of the derivative's low-pass, s (0: none)", kNonNegative)
            .field("output_min", &PidConfig::output_min, "lower output limit (<= 0)")
            .field("output_max", &PidConfig::output_max, "upper output limit (>= 0)");
        return s;
    }();
    return schema;
}

const ConfigSchema<PositionControllerConfig>& position_controller_schema() {
    static const ConfigSchema<PositionControllerConfig> schema = [] {
        using C = PositionControllerConfig;
        ConfigSchema<C> s;
        s.field("kp_per_s", &C::kp_per_s, "kp, 1/s", kNonNegative)
            .field("ki_per_s2", &C::ki_per_s2, "ki, 1/s^2", kNonNegative)
            .field("kd_s", &C::kd_s, "kd, s", kNonNegative)
            .field("derivative_filter_s", &C::derivative_filter_s,
                   "tau_f of the derivative's low-pass, s", kNonNegative)
            .field("max_speed_mps", &C::max_speed_mps, "|v_cmd| limit, m/s", kPositive)
            .field("yaw_gain_per_s", &C::yaw_gain_per_s, "k_psi, 1/s", kNonNegative)
            .field("max_yaw_rate_radps", &C::max_yaw_rate_radps, "yaw rate limit, rad/s",
                   kPositive);
        return s;
    }();
    return schema;
}

const ConfigSchema<DisturbanceObserverConfig>& disturbance_observer_schema() {
    static const ConfigSchema<DisturbanceObserverConfig> schema = [] {
        using C = DisturbanceObserverConfig;
        ConfigSchema<C> s;
        s.field("velocity_time_constant_s", &C::velocity_time_constant_s,
                "tau of the vehicle's velocity loop, s", kPositive)
            .field("drag_coefficient_per_s", &C::drag_coefficient_per_s,
                   "c of the vehicle's own linear drag, 1/s", kNonNegative)
            .field("max_accel_mps2", &C::max_accel_mps2,
                   "the velocity loop's acceleration authority, m/s^2", kPositive)
            .field("bandwidth_radps", &C::bandwidth_radps,
                   "observer poles, rad/s, >= (1/tau + c)/2", kPositive)
            .field("max_compensation_mps", &C::max_compensation_mps, "|tau d| limit, m/s",
                   kNonNegative)
            .field("max_gap_s", &C::max_gap_s, "longer: restart the velocity estimate, s",
                   kPositive);
        return s;
    }();
    return schema;
}

const ConfigSchema<VtpConfig>& vtp_schema() {
    static const ConfigSchema<VtpConfig> schema = [] {
        ConfigSchema<VtpConfig> s;
        s.field("max_vtp_distance_m", &VtpConfig::max_vtp_distance_m,
                "delta: largest distance to the VTP, m", kPositive)
            .field("max_path_separation_m", &VtpConfig::max_path_separation_m,
                   "lambda: largest allowed separation from the path, m", kPositive);
        return s;
    }();
    return schema;
}

const ConfigSchema<TrackingConfig>& tracking_schema() {
    static const ConfigSchema<TrackingConfig> schema = [] {
        ConfigSchema<TrackingConfig> s;
        s.field("use_vtp", &TrackingConfig::use_vtp, "target the VTP (else the waypoint)")
            .section("vtp", &TrackingConfig::vtp, vtp_schema(), "the VTP follower");
        return s;
    }();
    return schema;
}

const ConfigSchema<MissionManagerConfig>& mission_manager_schema() {
    static const ConfigSchema<MissionManagerConfig> schema = [] {
        using C = MissionManagerConfig;
        ConfigSchema<C> s;
        s.section("position_controller", &C::position_controller, position_controller_schema(),
                  "the three axis PIDs")
            .section("tracking", &C::tracking, tracking_schema(), "the trajectory follower")
            .field("estimate_timeout_s", &C::estimate_timeout_s,
                   "an invalid estimate this long enters the failsafe, s", kNonNegative)
            .field("home_height_offset_m", &C::home_height_offset_m,
                   "go home to this height above the take-off point, m", kNonNegative)
            .field("home_tolerance_m", &C::home_tolerance_m, "WP_tol of home, m", kPositive);
        return s;
    }();
    return schema;
}

OperatorScript operator_script_from_yaml(const ConfigNode& list_node, const std::string& prefix) {
    if (list_node.is_null()) return OperatorScript{};
    std::vector<TimedCommand> commands;
    for (const ConfigNode& item : io::detail::sequence_items(list_node, prefix, "a list of maps")) {
        commands.push_back(
            timed_command_from_yaml(item, io::detail::index_key(prefix, commands.size())));
    }
    return OperatorScript(std::move(commands));
}

}  // namespace scantling::control
