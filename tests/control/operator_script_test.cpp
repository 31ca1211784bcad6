// The operator script: commands sorted by time and handed out once each when due; read from a
// YAML list with errors naming the file, line and key; and driving the mission manager.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <scantling/control/config_yaml.hpp>
#include <scantling/control/mission_manager.hpp>
#include <scantling/control/operator_script.hpp>
#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/planning/recorded_points.hpp>
#include <scantling/planning/waypoints.hpp>

#include "../planning/expect_error.hpp"
#include "velocity_plant.hpp"

namespace scantling::control {
namespace {

using Type = OperatorCommandType;

std::vector<Type> types(const std::vector<OperatorCommand>& commands) {
    std::vector<Type> out;
    for (const OperatorCommand& c : commands) out.push_back(c.type);
    return out;
}

OperatorScript script_from(const std::string& yaml) {
    return operator_script_from_yaml(io::parse_yaml_string(yaml, "ops.yaml"));
}

TEST(OperatorScript, HandsOutEachCommandOnceWhenDueInTimeOrder) {
    OperatorScript script({{5.0, {Type::kResume}},
                           {1.0, {Type::kStart}},
                           {3.0, {Type::kPause}},
                           {3.0, {Type::kTakeOver, Eigen::Vector3d(0.5, 0.0, 0.0), 0.1}},
                           {3.0, {Type::kHandBack}}});
    EXPECT_TRUE(script.due(0.5).empty());
    EXPECT_EQ(types(script.due(1.0)), (std::vector<Type>{Type::kStart}));  // due at its time
    EXPECT_TRUE(script.due(1.0).empty());                                  // once only
    const std::vector<OperatorCommand> at3 = script.due(4.0);
    EXPECT_EQ(types(at3), (std::vector<Type>{Type::kPause, Type::kTakeOver, Type::kHandBack}));
    EXPECT_EQ(at3[1].v_world_mps, Eigen::Vector3d(0.5, 0.0, 0.0));  // same time: given order
    EXPECT_FALSE(script.finished());
    EXPECT_EQ(types(script.due(100.0)), (std::vector<Type>{Type::kResume}));
    EXPECT_TRUE(script.finished());
}

TEST(OperatorScript, NonFiniteTimesAndVelocitiesAreRefused) {
    SCANTLING_EXPECT_ERROR(OperatorScript({{1.0, {}}, {std::nan(""), {}}}), InputError,
                           "operator_script[1].time_s = nan, expected finite");
    SCANTLING_EXPECT_ERROR(
        OperatorScript({{1.0, {Type::kTakeOver, Eigen::Vector3d(INFINITY, 0.0, 0.0), 0.0}}}),
        InputError, "operator_script[0]: the take-over velocity (inf, 0, 0)");
}

TEST(OperatorScriptYaml, ReadsTimesCommandsAndTakeOverVelocities) {
    OperatorScript script = script_from(
        "- {time_s: 4.0, command: take_over, v_world_mps: [0.5, 0, -0.1], yaw_rate_radps: 0.2}\n"
        "- {time_s: 0.5, command: start}\n"
        "- {time_s: 6, command: hand_back}\n");
    ASSERT_EQ(script.commands().size(), 3u);
    EXPECT_EQ(script.commands()[0].command.type, Type::kStart);
    const TimedCommand& take_over = script.commands()[1];
    EXPECT_EQ(take_over.time_s, 4.0);
    EXPECT_EQ(take_over.command.v_world_mps, Eigen::Vector3d(0.5, 0.0, -0.1));
    EXPECT_EQ(take_over.command.yaw_rate_radps, 0.2);
    EXPECT_EQ(script.commands()[2].command.v_world_mps, Eigen::Vector3d::Zero());  // default
    EXPECT_TRUE(operator_script_from_yaml(io::parse_yaml_string("")).finished());
}

TEST(OperatorScriptYaml, ErrorsNameTheFileLineAndKey) {
    SCANTLING_EXPECT_ERROR(
        script_from("- {time_s: 1, command: start}\n- {time_s: 2, command: pause}\n"
                    "- {time_s: 3, command: jump}\n"),
        ParseError,
        "ops.yaml: line 3: key 'operator[2].command': expected one of start, pause, resume, "
        "take_over, hand_back, go_home, abort, got 'jump'");
    SCANTLING_EXPECT_ERROR(script_from("- {time_s: 1, command: pause, speed: 2}\n"), ParseError,
                           "key 'operator[0].speed': unknown key");
    SCANTLING_EXPECT_ERROR(script_from("- {command: pause}\n"), ParseError,
                           "key 'operator[0].time_s': missing");
    SCANTLING_EXPECT_ERROR(script_from("- {time_s: 1}\n"), ParseError,
                           "key 'operator[0].command': missing");
    SCANTLING_EXPECT_ERROR(script_from("- {time_s: -1, command: abort}\n"), ParseError,
                           "key 'operator[0].time_s' = -1, expected >= 0");
    SCANTLING_EXPECT_ERROR(script_from("- {time_s: 1, command: pause, v_world_mps: [1, 0, 0]}\n"),
                           ParseError, "key 'operator[0].v_world_mps': only take_over takes");
    SCANTLING_EXPECT_ERROR(script_from("time_s: 1\n"), ParseError,
                           "key 'operator': expected a list of maps, got a map");
}

TEST(OperatorScript, DrivesAMissionThroughPauseResumeAndGoHome) {
    OperatorScript script = script_from(
        "- {time_s: 0.1, command: start}\n- {time_s: 3, command: pause}\n"
        "- {time_s: 5, command: resume}\n- {time_s: 8, command: go_home}\n");
    const Eigen::Vector3d home(0.0, 0.0, 1.0);
    MissionManager manager(
        planning::WaypointPath{{{Eigen::Vector3d(6.0, 0.0, 1.0), std::nullopt, 0.2}}});
    test::Plant3d plant{home, Eigen::Vector3d::Zero()};
    std::vector<MissionState> states;
    for (double t_s = 0.0; t_s < 20.0; t_s += 0.05) {
        const MissionTick tick =
            manager.update({plant.p, 0.0, plant.v, true}, t_s, script.due(t_s));
        for (const MissionEvent& e : tick.events) {
            if (e.type == MissionEventType::kStateChanged) states.push_back(e.to);
        }
        plant.step(tick.v_cmd_world_mps, 0.05, Eigen::Vector3d::Zero());
    }
    using S = MissionState;
    EXPECT_EQ(states,
              (std::vector<S>{S::kRunning, S::kPaused, S::kRunning, S::kGoingHome, S::kCompleted}));
    EXPECT_LT((plant.p - home).norm(), 0.05);
}

}  // namespace
}  // namespace scantling::control
