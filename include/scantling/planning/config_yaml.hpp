#pragma once
/// @file
/// YAML bindings of the planning module (io::ConfigSchema): the mission configs and a tagged
/// mission request that becomes a WaypointPath. Every default stays in the structs' in-class
/// initialisers; every error names the file, the line and the key path.
///
/// A mission request is one map whose `type` picks the planner (SPEC §4's missions):
///   {type: sweep,    rectangle: {corner_world_m, normal_world, width_m, height_m}, config: {...}}
///   {type: vertical, rectangle: {...}, config: {standoff_m, leg_spacing_m, ...}}
///   {type: circular, circle: {centre_xy_world_m: [x, y], radius_m, heights_m: [...]},
///                    config: {points_per_turn, start_angle_rad, clockwise, waypoint_tolerance_m}}
///   {type: goto,     point: A, config: {waypoint_tolerance_m}}
///   {type: home,     config: {waypoint_tolerance_m}}
/// `config` is optional (the planner's defaults); keys not of the chosen type are errors. A bad
/// request is refused with the planner's own message, prefixed with the file: an empty
/// rectangle ("x.yaml: mission.rectangle.width_m = 0, expected finite > 0"), an unknown
/// recorded point ("x.yaml: line 3: key 'mission.point': recorded point 'B' is unknown
/// (recorded: A)"), go-home without a take-off point.
///
/// The schemas below cannot hold std::optional or 2-vectors: `leg_spacing_m` (vertical) and
/// `centre_xy_world_m` (circular) are read by mission_from_yaml only.
/// Thread-safety: the schemas are built once (function-local statics) and immutable.

#include <Eigen/Core>
#include <optional>
#include <string>

#include <scantling/io/config_node.hpp>
#include <scantling/io/config_schema.hpp>
#include <scantling/planning/circular_inspection.hpp>
#include <scantling/planning/nbv_planner.hpp>
#include <scantling/planning/recorded_points.hpp>
#include <scantling/planning/sweep_mission.hpp>
#include <scantling/planning/vertical_inspection.hpp>
#include <scantling/planning/wall_rectangle.hpp>
#include <scantling/planning/waypoints.hpp>

namespace scantling::planning {

const io::ConfigSchema<WallRectangle>& wall_rectangle_schema();
const io::ConfigSchema<SweepConfig>& sweep_config_schema();
/// Without leg_spacing_m (an optional; see the file comment).
const io::ConfigSchema<VerticalInspectionConfig>& vertical_inspection_config_schema();
const io::ConfigSchema<CircularInspectionConfig>& circular_inspection_config_schema();
const io::ConfigSchema<GoToConfig>& go_to_config_schema();
/// The exploration planner's settings (a mission's `stack.nbv:`), with its `camera:` and
/// `parallel:` sections; `sampling` is `uniform` or `frontier`. Defined in nbv_config_yaml.cpp.
const io::ConfigSchema<NbvPlannerConfig>& nbv_planner_config_schema();

/// What a request may refer to besides its own keys.
struct MissionContext {
    RecordedPoints recorded_points;                    ///< for type goto
    std::optional<Eigen::Vector3d> p_takeoff_world_m;  ///< for type home
};

/// The waypoints of the mission request `node` (a map; see the file comment), keys named
/// "<prefix>.<key>" in messages. Throws ParseError (unknown or missing key, bad value or type,
/// unknown recorded point, home without a take-off point) or ConfigError prefixed with the
/// file (a request the planner refuses).
WaypointPath mission_from_yaml(const io::ConfigNode& node, const MissionContext& context = {},
                               const std::string& prefix = "mission");

}  // namespace scantling::planning
