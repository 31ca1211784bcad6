// The ROV hull survey in closed loop (mission/rov_mission.hpp, mission/rov_stack.hpp): a short
// section of the parametric hull at a quay, surveyed on the robot's own estimate, judged on the
// truth.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/mission/rov_mission.hpp>

#include "../planning/expect_error.hpp"
#include "mission_test_support.hpp"

namespace scantling::mission {
namespace {

/// A 6 x 2 m section midship, flown 0.1 m beyond it on every side (3 horizontal slices at 1.0 m:
/// ~15 m of path, ~70 s), in a current of 0.1 m/s along the hull and 0.05 m/s onto it. `extra` is
/// appended to the document.
std::string section_yaml(const std::string& extra = "") {
    return R"(
simulation:
  world: {type: ship_hull, ship_hull: {surroundings: {environment: quay, draught_m: 6.9}}}
  vehicle:
    type: rov
    rov: {current: {mean: [0.1, 0.05, 0.0], sigma: [0.02, 0.02, 0.0]}}
  sensors:
    - {type: multibeam_sonar, num_beams: 128, num_bins: 256, max_range_m: 5.0, rate_hz: 5,
       T_body_sensor: {xyz: [0.3, 0.0, 0.0], rpy_deg: [0.0, 10.0, 0.0]}}
    - type: camera
      preset: rov
      width: 160
      rate_hz: 2
      T_body_sensor: {xyz: [0.35, 0.0, 0.0], rpy_deg: [-90.0, 0.0, -90.0]}
      lasers:
        - {origin_camera: [0.0, -0.1, 0.0], direction_camera: [0.0, 0.0, 1.0]}
        - {origin_camera: [0.0, 0.1, 0.0], direction_camera: [0.0, 0.0, 1.0]}
    - {type: imu, preset: industrial_mems, rate_hz: 200}
    - {type: pressure, surface_z_m: 6.9}
    - {type: dvl}
  duration_s: 150
  dt_s: 0.005
  seed: 2
  export: {world: false}
start: {xyz: [12.5, -9.6, 6.4], rpy_deg: [0.0, 0.0, 90.0]}
mission:
  type: hull_survey
  hull: {xyz: [12.0, -8.1, 6.9], rpy_deg: [0.0, 0.0, 0.0]}
  plan: {length_m: 6.0, draught_m: 2.0, stand_off_m: 1.0, orientation: horizontal}
coverage:
  camera: {width_px: 1920, height_px: 1080, hfov_deg: 77.0, vfov_deg: 48.0}
  rate_hz: 2
  cell_size_m: 0.05
  max_range_m: 3.0
  max_mm_per_px: 2.0
)" + extra;
}

RovMissionResult run(const std::string& yaml, const std::string& name) {
    const RovMissionScenario scenario = parse_rov_mission_scenario(yaml, name);
    return run_rov_mission(scenario, test::temp_dir(name).string());
}

std::string events_of(const RovMissionResult& r) {
    std::ifstream in(std::filesystem::path(r.directory) / "mission" / "events.jsonl");
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(RovHullSurvey, TheClosedLoopHoldsTheStandOffAndCoversTheSection) {
    const RovMissionResult r = run(section_yaml(), "rov_section");
    EXPECT_TRUE(r.completed);
    EXPECT_EQ(r.waypoints_survey, 6u);
    EXPECT_LT(r.stand_off_error_mean_m, 0.10);  // issue 14's target
    EXPECT_LT(r.stand_off_error_max_m, 0.30);
    EXPECT_LT(r.heading_error_mean_rad, 3.0 * M_PI / 180.0);
    ASSERT_TRUE(r.coverage.has_value());
    EXPECT_GE(r.coverage->covered_fraction, 0.98);  // issue 14's target
    EXPECT_LT(r.position_error_rms_m, 0.10);
    EXPECT_GT(r.hull_lines, 0.9 * r.pings);
    EXPECT_GT(r.sonar_voxels, 50u);
    EXPECT_GT(r.laser_measurements, 0.8 * r.images);
    EXPECT_LT(r.laser_distance_error_mean_m, 0.03);
    EXPECT_TRUE(
        std::filesystem::exists(std::filesystem::path(r.directory) / "mission" / "sonar_map.csv"));
}

// Camera images lost for 16 s in the middle of the first slice leave a hole in the coverage
// the robot believes (the next slice's overlap covers part of it); it goes back once the slices
// are done and closes it.
TEST(RovHullSurvey, AHoleInTheBelievedCoverageIsReinspectedInTheSameMission) {
    const RovMissionResult r = run(
        section_yaml("faults: [{sensor: camera, kind: dropout, start_s: 8.0, duration_s: 16.0}]\n"),
        "rov_hole");
    EXPECT_TRUE(r.completed);
    EXPECT_EQ(r.reinspection_rounds, 1u);
    EXPECT_GE(r.holes_found, 1u);
    EXPECT_LT(r.believed_coverage_survey, 0.97);
    EXPECT_GT(r.believed_coverage_final, 0.98);
    ASSERT_TRUE(r.coverage.has_value());
    EXPECT_GE(r.coverage->covered_fraction, 0.98);
    EXPECT_NE(events_of(r).find("reinspection_started"), std::string::npos);
}

TEST(RovHullSurvey, ADvlDropoutHoldsTheSurveyAndIsReported) {
    const RovMissionResult r = run(
        section_yaml("faults: [{sensor: dvl, kind: dropout, start_s: 20.0, duration_s: 6.0}]\n"),
        "rov_dvl");
    EXPECT_TRUE(r.completed);
    const std::string events = events_of(r);
    EXPECT_NE(events.find(R"("sensor":"dvl","silent_s")"), std::string::npos);
    EXPECT_NE(events.find("sensor_restored"), std::string::npos);
    EXPECT_LT(r.stand_off_error_mean_m, 0.10);
}

TEST(RovHullSurvey, SonarPingsOfNaNsAreDroppedAndReported) {
    const RovMissionResult r =
        run(section_yaml("faults: [{sensor: multibeam_sonar, kind: nan, start_s: 10.0, duration_s: "
                         "2.0}]\n"),
            "rov_sonar_nan");
    EXPECT_TRUE(r.completed);
    EXPECT_GE(r.inputs_rejected, 9u);  // 10 pings at 5 Hz, minus the window's edges
    EXPECT_NE(events_of(r).find(R"("sensor":"sonar")"), std::string::npos);
}

// A bump from below, out of the camera's and the sonar's view (a bilge keel under the vehicle):
// 6 m/s² upwards for 50 ms, a 0.3 m/s kick. The IMU sees it, the vehicle backs off upwards for
// 2 s, away from the obstacle, reports it, and then resumes the survey.
TEST(RovHullSurvey, AnOutOfViewContactMakesTheVehicleBackOffAndReportIt) {
    std::string yaml = section_yaml();
    const std::string current = "rov: {current: {mean: [0.1, 0.05, 0.0], sigma: [0.02, 0.02, 0.0]}";
    yaml.replace(yaml.find(current), current.size(),
                 current +
                     ", pushes: [{start_s: 30.0, duration_s: 0.05, "
                     "acceleration_world_mps2: [0.0, 0.0, 6.0]}]");
    const RovMissionResult r = run(yaml, "rov_contact");
    EXPECT_TRUE(r.completed);
    EXPECT_EQ(r.contacts, 1u);
    EXPECT_NEAR(static_cast<double>(r.backing_off_ticks), 2.0 / 0.005, 2.0);
    const std::string events = events_of(r);
    const std::size_t at = events.find(R"("type":"contact")");
    ASSERT_NE(at, std::string::npos);
    // The impulse (and the back-off) points up, away from the obstacle below.
    const std::size_t open = events.find('[', events.find("impulse_direction_world", at));
    const std::size_t second_comma = events.find(',', events.find(',', open) + 1);
    EXPECT_GT(std::stod(events.substr(second_comma + 1)), 0.99) << events.substr(open, 40);
    EXPECT_LT(r.stand_off_error_mean_m, 0.10);
}

TEST(RovHullSurvey, TheShippedSurveysParseAndAreToldFromTheDronesMissions) {
    const std::string dir = std::string(SCANTLING_SOURCE_DIR) + "/scenarios/missions/";
    for (const char* name : {"hull_survey_horizontal", "hull_survey_vertical"}) {
        const std::string path = dir + "rov/" + name + ".yaml";
        EXPECT_TRUE(is_rov_mission_file(path)) << path;
        const RovMissionScenario m = load_rov_mission_scenario(path);
        EXPECT_EQ(m.name, name);
        EXPECT_DOUBLE_EQ(m.plan.length_m, 30.0);
        EXPECT_DOUBLE_EQ(m.flown_plan().length_m, 30.2);  // the margin on both ends
        EXPECT_TRUE(m.coverage.has_value());
        EXPECT_DOUBLE_EQ(m.stack.surface_z_world_m, 6.9);  // from the pressure sensor
    }
    EXPECT_TRUE(is_rov_mission_file(dir + "rov/dtc_hull_survey.yaml"));
    EXPECT_FALSE(is_rov_mission_file(dir + "hull_sweep_closed_loop.yaml"));
}

TEST(RovHullSurvey, AnImpossiblePlanIsRefusedNamingTheField) {
    auto with = [](const std::string& from, const std::string& to) {
        std::string yaml = section_yaml();
        yaml.replace(yaml.find(from), from.size(), to);
        return yaml;
    };
    SCANTLING_EXPECT_ERROR(parse_rov_mission_scenario(with("draught_m: 2.0", "draught_m: 0.0")),
                           ParseError, "mission.plan.draught_m");
    SCANTLING_EXPECT_ERROR(
        parse_rov_mission_scenario(with("orientation: horizontal", "overlap: 1.0")), ParseError,
        "mission.plan.overlap");
    SCANTLING_EXPECT_ERROR(parse_rov_mission_scenario(with("type: hull_survey", "type: sweep")),
                           ParseError, "expected hull_survey");
    SCANTLING_EXPECT_ERROR(
        parse_rov_mission_scenario(with(
            "type: rov\n    rov: {current: {mean: [0.1, 0.05, 0.0], sigma: [0.02, 0.02, 0.0]}}",
            "type: mav")),
        ConfigError, "needs the rov vehicle");
    SCANTLING_EXPECT_ERROR(parse_rov_mission_scenario(section_yaml("stack: {survey_speed: 1}\n")),
                           ParseError, "survey_speed");
}

}  // namespace
}  // namespace scantling::mission
