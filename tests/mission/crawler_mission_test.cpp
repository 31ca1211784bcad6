// The crawler's rectangle mission in closed loop (mission/crawler_mission.hpp): a small
// rectangle on the 5 × 2 m plate flown on the particle filter's estimate, the operator's
// commands, sensor faults and bad requests.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/mission_log.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/mission/crawler_mission.hpp>

namespace scantling::mission {
namespace {

namespace fs = std::filesystem;

// The plate lies in z = 0 (normal +z), centred on the origin; "up" on it is +y. Four UWB
// anchors on poles around it. The rectangle: 1.2 m along x by 0.6 m along y, ≤ 0.3 m steps.
const std::string kPlate = R"(
simulation:
  world: {type: plate, plate: {length_m: 5.0, width_m: 2.0}}
  vehicle: {type: crawler}
  sensors:
    - {type: imu, rate_hz: 100}
    - {type: wheel_odometry, rate_hz: 50}
    - type: uwb
      anchors:
        - {id: 1, position_world: [-3.0, -2.0, 1.5]}
        - {id: 2, position_world: [3.0, -2.0, 2.0]}
        - {id: 3, position_world: [3.0, 2.0, 1.5]}
        - {id: 4, position_world: [-3.0, 2.0, 2.0]}
  duration_s: 200
  dt_s: 0.01
  seed: 2
  export: {world: false}
start: {xyz: [-1.0, -0.5, 0.0], rpy_deg: [0.0, 0.0, 90.0]}
mission:
  type: surface_rectangle
  start_m: [-0.8, -0.4, 0.0]
  width_m: 1.2
  height_m: 0.6
  max_step_m: 0.3
  up: [0.0, 1.0, 0.0]
  swath_width_m: 0.4
)";

fs::path temp_dir(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) /
                         ("scantling_crawler_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    return dir;
}

struct CrawlerRun {
    CrawlerMissionResult result;
    io::MissionLog log;
};

CrawlerRun fly(const std::string& text, const std::string& name) {
    const CrawlerMissionScenario m = parse_crawler_mission_scenario(text, name + ".yaml");
    const fs::path dir = temp_dir(name);
    CrawlerRun run;
    run.result = run_crawler_mission(m, dir.string());
    run.log = *io::read_mission_log(dir.string());
    fs::remove_all(dir);
    return run;
}

std::size_t count_events(const CrawlerRun& r, const std::string& type,
                         const std::string& text = "") {
    std::size_t n = 0;
    for (const io::EventRecord& e : r.log.events) {
        n += e.type == type && e.json.find(text) != std::string::npos;
    }
    return n;
}

TEST(CrawlerMission, CoversAPlateRectangleOnItsOwnEstimate) {
    const CrawlerRun r = fly(kPlate, "plate");
    // ⌈1.2 / 0.3⌉ + 1 = 5 transects, 0.3 m apart: 10 waypoints.
    EXPECT_EQ(r.result.transects, 5u);
    EXPECT_DOUBLE_EQ(r.result.step_m, 0.3);
    EXPECT_TRUE(r.result.completed);
    EXPECT_EQ(r.result.waypoints_reached, 10u);
    EXPECT_EQ(count_events(r, "gyro_calibrated"), 1u);
    EXPECT_EQ(count_events(r, "stop_mapped"), 0u);  // no LiDAR, no stops
    EXPECT_EQ(r.result.stop_scores.stops, 0u);
    // Issue 15's targets: cross-track mean ≤ 0.03 m, coverage ≥ 99 %.
    EXPECT_LT(r.result.cross_track_mean_m, 0.03);
    EXPECT_GE(r.result.coverage, 0.99);
    EXPECT_LT(r.result.position_error_rms_m, 0.05);
    EXPECT_GT(r.result.uwb_applied, 1000u);
    std::printf(
        "plate rectangle: cross-track mean %.4f max %.4f m, coverage %.2f %%, "
        "estimate rms %.4f m, %.1f s\n",
        r.result.cross_track_mean_m, r.result.cross_track_max_m, 100.0 * r.result.coverage,
        r.result.position_error_rms_m, r.result.mission_time_s);
}

TEST(CrawlerMission, TheOperatorPausesResumesAndAborts) {
    const CrawlerRun r = fly(kPlate +
                                 "operator: [{time_s: 10.0, command: pause}, "
                                 "{time_s: 14.0, command: resume}, "
                                 "{time_s: 20.0, command: abort}, "
                                 "{time_s: 21.0, command: go_home}]\n",
                             "operator");
    EXPECT_EQ(count_events(r, "state_changed", R"("to":"paused")"), 1u);
    EXPECT_EQ(count_events(r, "state_changed", R"("from":"paused","to":"running")"), 1u);
    EXPECT_EQ(count_events(r, "state_changed", R"("to":"aborted")"), 1u);
    EXPECT_EQ(count_events(r, "command_refused", "go_home"), 1u);
    EXPECT_EQ(r.result.final_state, control::MissionState::kAborted);
    // Standing still while paused and once aborted: the commanded speed is zero.
    for (const io::CommandRecord& c : r.log.commands) {
        const bool still = (c.stamp_s > 10.0 && c.stamp_s < 14.0) || c.stamp_s > 20.0;
        if (still) {
            EXPECT_EQ(c.v_world_mps.norm(), 0.0) << c.stamp_s;
        }
    }
}

TEST(CrawlerMission, WheelFaultsStopTheCrawlerAndNansAreDropped) {
    const CrawlerRun r = fly(kPlate +
                                 "faults: [{sensor: wheel_odometry, kind: dropout, start_s: 8.0, "
                                 "duration_s: 1.0}, {sensor: uwb, kind: nan, start_s: 12.0, "
                                 "duration_s: 1.0}, {sensor: imu, kind: nan, start_s: 15.0, "
                                 "duration_s: 0.05}]\n",
                             "faults");
    EXPECT_EQ(count_events(r, "sensor_lost", "wheel_odometry"), 1u);
    EXPECT_EQ(count_events(r, "sensor_restored", "wheel_odometry"), 1u);
    EXPECT_EQ(count_events(r, "input_rejected", "uwb"), 1u);
    EXPECT_EQ(count_events(r, "input_rejected", "imu"), 1u);
    // No wheel sample from 8.0 s: lost 0.1 s after the last (7.98 s), standing still until
    // they are back at 9.0 s.
    for (const io::CommandRecord& c : r.log.commands) {
        if (c.stamp_s > 8.09 && c.stamp_s < 8.99) {
            EXPECT_EQ(c.v_world_mps.norm(), 0.0) << c.stamp_s;
        }
        ASSERT_TRUE(c.v_world_mps.allFinite() && std::isfinite(c.yaw_rate_radps));
    }
    EXPECT_TRUE(r.result.completed);
    EXPECT_LT(r.result.cross_track_mean_m, 0.03);
}

TEST(CrawlerMission, WithoutUwbItReportsAndDeadReckons) {
    // The UWB link down from 20 s to 45 s: reported once, restored once; the filter
    // dead-reckons on the gyro and the wheels and the rectangle is still driven on its line.
    const CrawlerRun r = fly(kPlate +
                                 "faults: [{sensor: uwb, kind: dropout, start_s: 20.0, "
                                 "duration_s: 25.0}]\n",
                             "no_uwb");
    EXPECT_EQ(count_events(r, "sensor_lost", "uwb"), 1u);
    EXPECT_EQ(count_events(r, "sensor_restored", "uwb"), 1u);
    EXPECT_EQ(count_events(r, "estimate_invalid"), 0u);
    EXPECT_TRUE(r.result.completed);
    EXPECT_LT(r.result.cross_track_mean_m, 0.03);
}

TEST(CrawlerMission, AnUncertainEstimateStopsTheCrawler) {
    // A limit under anything the filter reaches (UWB brings it to about 1 cm): it never moves,
    // and says why.
    std::string text = kPlate;
    text.replace(text.find("duration_s: 200"), std::string("duration_s: 200").size(),
                 "duration_s: 20");
    const CrawlerRun r = fly(text + "stack: {max_position_sigma_m: 0.002}\n", "uncertain");
    EXPECT_GE(count_events(r, "estimate_invalid"), 1u);
    EXPECT_FALSE(r.result.completed);
    for (const io::CommandRecord& c : r.log.commands) {
        ASSERT_EQ(c.v_world_mps.norm(), 0.0) << c.stamp_s;
    }
}

TEST(CrawlerMission, TheGyroCalibrationKeepsTheHeadingWithoutUwb) {
    // No UWB anchors: the filter dead-reckons on the gyro and the wheels. The simulated MEMS
    // gyro's turn-on bias (σ 0.5°/s) turns the heading unless it is taken standing still.
    std::string text = kPlate;
    const std::size_t uwb = text.find("    - type: uwb");
    text.erase(uwb, text.find("  duration_s") - uwb);
    const CrawlerRun calibrated = fly(text, "gyro_on");
    const CrawlerRun raw = fly(text + "stack: {gyro_calibration_s: 0}\n", "gyro_off");
    EXPECT_EQ(count_events(calibrated, "gyro_calibrated"), 1u);
    EXPECT_EQ(count_events(raw, "gyro_calibrated"), 0u);
    EXPECT_EQ(calibrated.result.uwb_applied, 0u);
    std::printf("no UWB: heading rms %.2f deg calibrated, %.2f deg raw; PF rms %.3f / %.3f m\n",
                calibrated.result.yaw_error_rms_rad * 180.0 / M_PI,
                raw.result.yaw_error_rms_rad * 180.0 / M_PI, calibrated.result.position_error_rms_m,
                raw.result.position_error_rms_m);
    EXPECT_LT(calibrated.result.yaw_error_rms_rad, 0.5 * raw.result.yaw_error_rms_rad);
    EXPECT_LT(calibrated.result.cross_track_mean_m, 0.03);
}

TEST(CrawlerMission, RefusesImpossibleRequests) {
    auto with = [](const std::string& from, const std::string& to) {
        std::string text = kPlate;
        text.replace(text.find(from), from.size(), to);
        return text;
    };
    // A start 0.3 m above the plate.
    const CrawlerMissionScenario off = parse_crawler_mission_scenario(
        with("start_m: [-0.8, -0.4, 0.0]", "start_m: [-0.8, -0.4, 0.3]"));
    try {
        run_crawler_mission(off, temp_dir("off").string());
        FAIL() << "a start off the surface was flown";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("start_world_m"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(temp_dir("off")));
    // Up along the plate's normal: no vertical on a floor.
    const CrawlerMissionScenario floor =
        parse_crawler_mission_scenario(with("up: [0.0, 1.0, 0.0]", "up: [0.0, 0.0, 1.0]"));
    EXPECT_THROW(run_crawler_mission(floor, temp_dir("floor").string()), InputError);
    EXPECT_THROW(
        parse_crawler_mission_scenario(with("vehicle: {type: crawler}", "vehicle: {type: mav}")),
        ConfigError);
    EXPECT_THROW(parse_crawler_mission_scenario(with("width_m: 1.2", "width_m: -1.2")), ParseError);
    EXPECT_THROW(parse_crawler_mission_scenario(with("swath_width_m: 0.4", "swath_widht_m: 0.4")),
                 ParseError);
    EXPECT_THROW(parse_crawler_mission_scenario(with("type: surface_rectangle", "type: sweep")),
                 ParseError);
}

TEST(CrawlerMission, TheShippedTankScenarioParses) {
    const CrawlerMissionScenario m =
        load_crawler_mission_scenario(std::string(SCANTLING_SOURCE_DIR) +
                                      "/scenarios/missions/crawler/storage_tank_rectangle.yaml");
    EXPECT_EQ(m.simulation.vehicle.type, sim::VehicleType::kCrawler);
    ASSERT_EQ(m.tasks.size(), 1u);
    EXPECT_EQ(m.tasks[0].type, planning::SurfaceTaskType::kRectangle);
    EXPECT_DOUBLE_EQ(m.tasks[0].rectangle.width_m, 6.0);
    EXPECT_EQ(m.stack.particle_filter.uwb_anchors_world_m.size(), 5u);
    EXPECT_TRUE(is_crawler_mission_file(std::string(SCANTLING_SOURCE_DIR) +
                                        "/scenarios/missions/crawler/storage_tank_rectangle.yaml"));
    EXPECT_FALSE(is_crawler_mission_file(std::string(SCANTLING_SOURCE_DIR) +
                                         "/scenarios/missions/hull_sweep_closed_loop.yaml"));
}

}  // namespace
}  // namespace scantling::mission
