// The tagged mission request read from YAML: each type gives the planner's own waypoints; bad
// requests (empty rectangle, unknown recorded point, home without a take-off point, unknown
// keys or types) are refused naming the file, the line and the key.
#include <gtest/gtest.h>

#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/planning/config_yaml.hpp>

#include "expect_error.hpp"

namespace scantling::planning {
namespace {

WaypointPath mission(const std::string& yaml, const MissionContext& context = {}) {
    return mission_from_yaml(io::parse_yaml_string(yaml, "mission.yaml"), context);
}

void expect_same(const WaypointPath& a, const WaypointPath& b) {
    ASSERT_EQ(a.waypoints.size(), b.waypoints.size());
    for (std::size_t i = 0; i < a.waypoints.size(); ++i) {
        EXPECT_TRUE(a.waypoints[i].p_world_m.isApprox(b.waypoints[i].p_world_m, 1e-12)) << i;
        EXPECT_EQ(a.waypoints[i].yaw_rad, b.waypoints[i].yaw_rad) << i;
        EXPECT_EQ(a.waypoints[i].tolerance_m, b.waypoints[i].tolerance_m) << i;
    }
}

const WallRectangle kWall{Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d::UnitX(), 8.0, 5.0};
const std::string kWallYaml =
    "rectangle: {corner_world_m: [0, 0, 1], normal_world: [1, 0, 0], width_m: 8, height_m: 5}\n";

TEST(MissionYaml, SweepGivesThePlannersWaypoints) {
    expect_same(mission("type: sweep\n" + kWallYaml), plan_sweep(kWall));
    SweepConfig config;
    config.standoff_m = 2.0;
    config.line_spacing_m = 0.5;
    expect_same(
        mission("type: sweep\n" + kWallYaml + "config: {standoff_m: 2, line_spacing_m: 0.5}\n"),
        plan_sweep(kWall, config));
}

TEST(MissionYaml, VerticalReadsTheOptionalLegSpacing) {
    expect_same(mission("type: vertical\n" + kWallYaml), plan_vertical_inspection(kWall));
    VerticalInspectionConfig config;
    config.leg_spacing_m = 2.0;
    const WaypointPath path =
        mission("type: vertical\n" + kWallYaml + "config: {leg_spacing_m: 2, face_wall: true}\n");
    expect_same(path, plan_vertical_inspection(kWall, config));
    EXPECT_EQ(path.waypoints.size(), 10u);  // 5 legs
    SCANTLING_EXPECT_ERROR(mission("type: vertical\n" + kWallYaml + "config: {leg_spacing_m: 0}\n"),
                           ParseError,
                           "line 3: key 'mission.config.leg_spacing_m' = 0, expected > 0");
}

TEST(MissionYaml, CircularReadsTheCentreAndHeights) {
    const WaypointPath path = mission(
        "type: circular\n"
        "circle: {centre_xy_world_m: [2, 3], radius_m: 1.5, heights_m: [1, 2]}\n"
        "config: {points_per_turn: 8, clockwise: true}\n");
    CircleRequest request{Eigen::Vector2d(2.0, 3.0), 1.5, {1.0, 2.0}};
    CircularInspectionConfig config;
    config.points_per_turn = 8;
    config.clockwise = true;
    expect_same(path, plan_circular_inspection(request, config));
    SCANTLING_EXPECT_ERROR(
        mission("type: circular\ncircle: {centre_xy_world_m: [2, 3, 4], radius_m: 1, "
                "heights_m: [1]}\n"),
        ParseError, "line 2: key 'mission.circle.centre_xy_world_m': expected a sequence of 2");
    SCANTLING_EXPECT_ERROR(mission("type: circular\ncircle: {radius_m: 1}\n"), ConfigError,
                           "mission.yaml: mission.circle.heights_m");
}

TEST(MissionYaml, GoToAndHomeUseTheContext) {
    MissionContext context;
    context.recorded_points.record("manhole", {Eigen::Vector3d(1.0, 2.0, 3.0), 0.5});
    context.p_takeoff_world_m = Eigen::Vector3d(0.0, 0.0, 0.5);
    const WaypointPath go_to =
        mission("type: goto\npoint: manhole\nconfig: {waypoint_tolerance_m: 0.1}\n", context);
    ASSERT_EQ(go_to.waypoints.size(), 1u);
    EXPECT_EQ(go_to.waypoints[0].p_world_m, Eigen::Vector3d(1.0, 2.0, 3.0));
    EXPECT_EQ(go_to.waypoints[0].yaw_rad, 0.5);
    EXPECT_EQ(go_to.waypoints[0].tolerance_m, 0.1);
    const WaypointPath home = mission("type: home\n", context);
    ASSERT_EQ(home.waypoints.size(), 1u);
    EXPECT_EQ(home.waypoints[0].p_world_m, Eigen::Vector3d(0.0, 0.0, 0.5));
}

TEST(MissionYaml, BadRequestsAreRefusedNamingFileLineAndKey) {
    MissionContext context;
    context.recorded_points.record("A", {});
    SCANTLING_EXPECT_ERROR(mission("type: goto\npoint: B\n", context), ParseError,
                           "mission.yaml: line 2: key 'mission.point': recorded point 'B' is "
                           "unknown (recorded: A)");
    SCANTLING_EXPECT_ERROR(mission("type: goto\n", context), ParseError,
                           "key 'mission.point': missing");
    SCANTLING_EXPECT_ERROR(mission("type: home\n"), ParseError,
                           "line 1: key 'mission.type': home needs the take-off point");
    // An empty rectangle: absent (the planner's refusal, with the file) or zero (the line).
    SCANTLING_EXPECT_ERROR(mission("type: sweep\n"), ConfigError,
                           "mission.yaml: mission.rectangle.width_m = 0, expected finite > 0");
    SCANTLING_EXPECT_ERROR(mission("type: sweep\nrectangle: {width_m: 0, height_m: 1}\n"),
                           ParseError, "line 2: key 'mission.rectangle.width_m' = 0, expected > 0");
    SCANTLING_EXPECT_ERROR(mission("type: sweep\n" + kWallYaml + "radius_m: 2\n"), ParseError,
                           "line 3: key 'mission.radius_m': unknown key");
    SCANTLING_EXPECT_ERROR(mission("type: spiral\n"), ParseError,
                           "key 'mission.type': expected one of sweep, vertical, circular, goto, "
                           "home, got 'spiral'");
    SCANTLING_EXPECT_ERROR(mission(kWallYaml), ParseError, "key 'mission.type': missing");
    SCANTLING_EXPECT_ERROR(mission("[1, 2]"), ParseError, "key 'mission': expected a map");
}

TEST(PlanningConfigYaml, ConfigSchemasOverrideOnlyWhatTheyName) {
    SweepConfig sweep;
    sweep_config_schema().apply(io::parse_yaml_string("face_wall: false\n"), sweep, "sweep");
    EXPECT_FALSE(sweep.face_wall);
    EXPECT_EQ(sweep.standoff_m, SweepConfig{}.standoff_m);
    CircularInspectionConfig circular;
    SCANTLING_EXPECT_ERROR(circular_inspection_config_schema().apply(
                               io::parse_yaml_string("points_per_turn: 2\n"), circular, "c"),
                           ParseError, "key 'c.points_per_turn' = 2, expected >= 3");
}

}  // namespace
}  // namespace scantling::planning
