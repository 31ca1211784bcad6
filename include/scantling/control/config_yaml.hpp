#pragma once
/// @file
/// YAML bindings of the control module (io::ConfigSchema): the PID, the position controller,
/// the VTP follower and tracking, the mission manager, and the operator script. Each key is
/// registered once; its default stays in the struct's in-class initialiser. Errors name the
/// file, the line and the key path; unknown keys are errors.
///
/// An operator script is a YAML list of maps, one per command:
///   - {time_s: 12.0, command: pause}
///   - {time_s: 20.0, command: take_over, v_world_mps: [0.5, 0, 0], yaw_rate_radps: 0.1}
/// `time_s` (≥ 0) and `command` (start, pause, resume, take_over, hand_back, go_home, abort)
/// are required; the velocity keys only go with take_over (omitted: zero, a hover under the
/// operator's control), e.g. "x.yaml: line 7: key 'operator[2].command': expected one of
/// start, pause, ..., got 'jump'".
///
/// Thread-safety: the schemas are built once (function-local statics) and immutable.

#include <string>

#include <scantling/control/disturbance_observer.hpp>
#include <scantling/control/mission_manager.hpp>
#include <scantling/control/operator_script.hpp>
#include <scantling/control/pid.hpp>
#include <scantling/control/position_controller.hpp>
#include <scantling/control/vtp_follower.hpp>
#include <scantling/control/waypoint_sequencer.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/io/config_schema.hpp>

namespace scantling::control {

const io::ConfigSchema<PidConfig>& pid_schema();
const io::ConfigSchema<PositionControllerConfig>& position_controller_schema();
const io::ConfigSchema<VtpConfig>& vtp_schema();
const io::ConfigSchema<TrackingConfig>& tracking_schema();
const io::ConfigSchema<MissionManagerConfig>& mission_manager_schema();
const io::ConfigSchema<DisturbanceObserverConfig>& disturbance_observer_schema();

/// The script in `list_node` (a sequence; null: no commands), keys named "<prefix>[i].<key>".
/// Throws ParseError naming file, line and key.
OperatorScript operator_script_from_yaml(const io::ConfigNode& list_node,
                                         const std::string& prefix = "operator");

}  // namespace scantling::control
