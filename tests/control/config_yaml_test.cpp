// YAML bindings of the control configs: keys override the struct's defaults and nothing else,
// nested sections, and errors naming the file, line and key (unknown keys, ranges, validate()).
#include <gtest/gtest.h>

#include <string>

#include <scantling/control/config_yaml.hpp>
#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>

#include "../planning/expect_error.hpp"

namespace scantling::control {
namespace {

template <class T>
T parse(const io::ConfigSchema<T>& schema, const std::string& yaml, const std::string& prefix) {
    T config{};
    schema.apply(io::parse_yaml_string(yaml, "control.yaml"), config, prefix);
    return config;
}

TEST(ControlConfigYaml, MissionManagerKeysOverrideOnlyWhatTheyName) {
    const MissionManagerConfig config =
        parse(mission_manager_schema(),
              "position_controller: {kp_per_s: 1.5}\n"
              "tracking: {use_vtp: false, vtp: {max_vtp_distance_m: 3}}\n"
              "estimate_timeout_s: 1.0\n"
              "home_height_offset_m: 0.5\n",
              "mission_manager");
    const MissionManagerConfig defaults;
    EXPECT_EQ(config.position_controller.kp_per_s, 1.5);
    EXPECT_EQ(config.position_controller.ki_per_s2, defaults.position_controller.ki_per_s2);
    EXPECT_EQ(config.position_controller.max_speed_mps, defaults.position_controller.max_speed_mps);
    EXPECT_FALSE(config.tracking.use_vtp);
    EXPECT_EQ(config.tracking.vtp.max_vtp_distance_m, 3.0);
    EXPECT_EQ(config.tracking.vtp.max_path_separation_m,
              defaults.tracking.vtp.max_path_separation_m);
    EXPECT_EQ(config.estimate_timeout_s, 1.0);
    EXPECT_EQ(config.home_height_offset_m, 0.5);
    EXPECT_EQ(config.home_tolerance_m, defaults.home_tolerance_m);
}

TEST(ControlConfigYaml, AnEmptyDocumentGivesTheDefaults) {
    const PositionControllerConfig config = parse(position_controller_schema(), "", "pc");
    const PositionControllerConfig defaults;
    EXPECT_EQ(config.kp_per_s, defaults.kp_per_s);
    EXPECT_EQ(config.kd_s, defaults.kd_s);
    EXPECT_EQ(config.yaw_gain_per_s, defaults.yaw_gain_per_s);
    // describe() prints every key with its value.
    const std::string text = mission_manager_schema().describe();
    EXPECT_NE(text.find("max_vtp_distance_m: 2.0"), std::string::npos) << text;
    EXPECT_NE(text.find("estimate_timeout_s: 0.5"), std::string::npos) << text;
}

TEST(ControlConfigYaml, PidGainsAndLimits) {
    const PidConfig pid =
        parse(pid_schema(), "kp: 2\nki: 0.1\noutput_min: -1\noutput_max: 1\n", "pid");
    EXPECT_EQ(pid.kp, 2.0);
    EXPECT_EQ(pid.ki, 0.1);
    EXPECT_EQ(pid.output_min, -1.0);
    EXPECT_EQ(pid.output_max, 1.0);
    // 0 must lie within the limits (PidConfig::validate), reported with the file.
    SCANTLING_EXPECT_ERROR(parse(pid_schema(), "output_min: 0.5\n", "pid"), ConfigError,
                           "control.yaml: pid.output_min");
}

TEST(ControlConfigYaml, ErrorsNameTheFileLineAndKey) {
    SCANTLING_EXPECT_ERROR(
        parse(mission_manager_schema(), "tracking:\n  vtp:\n    delta: 2\n", "mission_manager"),
        ParseError,
        "control.yaml: line 3: key 'mission_manager.tracking.vtp.delta': "
        "unknown key");
    SCANTLING_EXPECT_ERROR(
        parse(mission_manager_schema(), "estimate_timeout_s: -0.1\n", "mission_manager"),
        ParseError, "line 1: key 'mission_manager.estimate_timeout_s' = -0.1, expected >= 0");
    SCANTLING_EXPECT_ERROR(parse(tracking_schema(), "use_vtp: maybe\n", "tracking"), ParseError,
                           "key 'tracking.use_vtp': expected true or false, got 'maybe'");
    SCANTLING_EXPECT_ERROR(parse(vtp_schema(), "max_path_separation_m: 0\n", "vtp"), ParseError,
                           "key 'vtp.max_path_separation_m' = 0, expected > 0");
}

}  // namespace
}  // namespace scantling::control
