// The closed loop (mission/): the scenario file, the recording's mission files, and a short
// closed-loop flight whose own estimate drives it to a recorded point in the dry dock.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/mission_log.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/mission/closed_loop.hpp>
#include <scantling/mission/mission_scenario.hpp>

#include "mission_test_support.hpp"

namespace scantling::mission {
namespace {

using test::kGoTo;
using test::temp_dir;
namespace fs = std::filesystem;

TEST(MissionScenario, ReadsTheDefaultJobAndCalibratesTheStack) {
    const MissionScenario m = load_mission_scenario(
        std::string(SCANTLING_SOURCE_DIR) + "/scenarios/missions/hull_sweep_closed_loop.yaml");
    EXPECT_EQ(m.name, "hull_sweep_closed_loop");
    EXPECT_EQ(m.path.waypoints.size(), 8u);  // 4 lines over 3 m, both ends
    EXPECT_NEAR(m.stack.T_body_lidar.translation().z(), 0.1, 1e-12);
    EXPECT_EQ(m.stack.global_ekf.uwb_anchors_world_m.size(), 5u);
    EXPECT_TRUE(m.stack.lidar_expected);
    // Without a LiDAR its silence is no fault: the stack neither pauses nor blocks for it.
    std::string no_lidar = kGoTo;
    const std::string lidar_line =
        "    - {type: spinning_lidar, columns: 512, T_body_sensor: {xyz: [0.0, 0.0, 0.1]}}\n";
    no_lidar.erase(no_lidar.find(lidar_line), lidar_line.size());
    EXPECT_FALSE(parse_mission_scenario(no_lidar).stack.lidar_expected);
    EXPECT_NEAR(m.stack.local_ekf.floor_height_m, -3.5, 1e-12);  // floor −1.5, start z 2
    // The ranger's beam (sim: +x) becomes the EKF's ray (+z): pointing down.
    const Eigen::Vector3d ray = m.stack.local_ekf.T_body_sensor.linear() * Eigen::Vector3d::UnitZ();
    EXPECT_NEAR(ray.z(), -1.0, 1e-9);
}

TEST(MissionScenario, OverridesKeysFromTheCommandLine) {
    const std::string path =
        std::string(SCANTLING_SOURCE_DIR) + "/scenarios/missions/hull_sweep_closed_loop.yaml";
    const MissionScenario m =
        load_mission_scenario(path, {"stack.manager.tracking.use_vtp=false",
                                     "simulation.duration_s=30", "stack.collision={d_min_m: 1.2}"});
    EXPECT_FALSE(m.stack.manager.tracking.use_vtp);
    EXPECT_EQ(m.simulation.duration_s, 30.0);
    EXPECT_EQ(m.stack.collision.d_min_m, 1.2);
    EXPECT_TRUE(load_mission_scenario(path).stack.manager.tracking.use_vtp);
    EXPECT_THROW(load_mission_scenario(path, {"stack.manager.tracking.use_vtp"}), ConfigError);
    EXPECT_THROW(load_mission_scenario(path, {"stack..x=1"}), ConfigError);
    EXPECT_THROW(load_mission_scenario(path, {"description.x=1"}), ConfigError);  // a scalar
    try {
        load_mission_scenario(path, {"stack.manager.tracking.use_vtq=false"});
        FAIL() << "a misspelt key was accepted";
    } catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find("use_vtq"), std::string::npos) << e.what();
    }
}

TEST(MissionScenario, RefusesUnknownKeysAndMissingParts) {
    EXPECT_THROW(parse_mission_scenario(kGoTo + "stack: {odometry_sigma: 1}\n"), ParseError);
    try {
        parse_mission_scenario(kGoTo + "speed: 3\n", "m.yaml");
        FAIL() << "an unknown key was accepted";
    } catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find("speed"), std::string::npos) << e.what();
    }
    EXPECT_THROW(parse_mission_scenario("start: {xyz: [0, 0, 1]}\nmission: {type: home}\n"),
                 ParseError);  // no simulation
    std::string unknown_point = kGoTo;
    unknown_point.replace(unknown_point.find("point: A"), 8, "point: B");
    EXPECT_THROW(parse_mission_scenario(unknown_point), ParseError);
}

TEST(MissionLog, RoundTrips) {
    const fs::path dir = temp_dir("log");
    fs::create_directories(dir / "mission");
    io::EstimateRecord e;
    e.stamp_s = 0.5;
    e.T_world_body.translation() = Eigen::Vector3d(1.0, 2.0, 3.0);
    e.T_world_body.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    e.position_sigma_m = Eigen::Vector3d(0.1, 0.2, 0.3);
    const io::CommandRecord c{0.5, Eigen::Vector3d(0.1, 0.0, 0.0), 0.2,
                              Eigen::Vector3d(0.3, 0.0, 0.0), true};
    const auto write = [&dir](const char* name, const std::string& text) {
        std::ofstream(dir / "mission" / name) << text;
    };
    write(io::recording_layout::kMissionEstimates, io::estimates_csv(std::vector{e}));
    write(io::recording_layout::kMissionCommands, io::commands_csv(std::vector{c}));
    write(io::recording_layout::kMissionEvents,
          io::event_line(0.5, "operator", R"({"command":"pause"})"));
    write(io::recording_layout::kMissionPath,
          io::intended_path_csv(std::vector{io::PathPointRecord{Eigen::Vector3d(4, 5, 6), 0.2}}));
    const auto log = io::read_mission_log(dir.string());
    ASSERT_TRUE(log.has_value());
    ASSERT_EQ(log->estimates.size(), 1u);
    EXPECT_TRUE(log->estimates[0].T_world_body.isApprox(e.T_world_body, 1e-12));
    EXPECT_EQ(log->commands[0].v_requested_world_mps, c.v_requested_world_mps);
    EXPECT_TRUE(log->commands[0].limited);
    ASSERT_EQ(log->events.size(), 1u);
    EXPECT_EQ(log->events[0].type, "operator");
    EXPECT_EQ(log->intended_path[0].position_world_m, Eigen::Vector3d(4, 5, 6));
    write(io::recording_layout::kMissionEvents, "{\"t_s\": \"soon\"}\n");
    EXPECT_THROW(io::read_mission_log(dir.string()), ParseError);
    fs::remove_all(dir);
}

TEST(ClosedLoop, FliesToARecordedPointOnItsOwnEstimate) {
    const MissionScenario m = parse_mission_scenario(kGoTo, "goto.yaml");
    const fs::path dir = temp_dir("goto");
    const MissionResult r = run_mission(m, dir.string());
    EXPECT_TRUE(r.completed);
    EXPECT_EQ(r.waypoints_reached, 1u);
    EXPECT_LT(r.position_error_rms_m, 0.25);  // measured 0.18 m (issue 13 target 0.10: not met)
    EXPECT_LT(r.path_deviation_max_m, 0.3);
    // Completed at A, then held: the vehicle ends within WP_tol of A (truth), aborted by the
    // operator at 11 s.
    EXPECT_EQ(r.final_state, control::MissionState::kAborted);
    const io::Recording recording = io::open_recording(dir.string());
    const Eigen::Vector3d p_end = recording.ground_truth().back().T_world_body.translation();
    EXPECT_LT((p_end - Eigen::Vector3d(18.0, 10.6, 2.5)).norm(), 0.3);
    const auto log = io::read_mission_log(dir.string());
    ASSERT_TRUE(log.has_value());
    EXPECT_EQ(log->estimates.size(), recording.ground_truth().size());
    for (const io::CommandRecord& c : log->commands) ASSERT_TRUE(c.v_world_mps.allFinite());
    bool aborted = false;
    for (const io::EventRecord& e : log->events)
        aborted |= e.json.find("\"abort\"") != std::string::npos;
    EXPECT_TRUE(aborted);
    fs::remove_all(dir);
}

// The go-to in a steady 5 m/s wind blowing onto the hull, from rest: without the wind
// compensation the position PIDs' integral learns the wind from the position error it lets
// grow (it takes seconds); with it the vehicle flies the line from the first second.
TEST(ClosedLoop, WindCompensationHoldsTheLineInASteadyWind) {
    auto fly = [](bool compensation) {
        MissionScenario m = parse_mission_scenario(kGoTo, "goto_wind.yaml");
        m.simulation.vehicle.mav.wind.mean = Eigen::Vector3d(0.0, -5.0, 0.0);
        m.stack.wind_compensation = compensation;
        const fs::path dir = temp_dir(compensation ? "wind_on" : "wind_off");
        const MissionResult r = run_mission(m, dir.string());
        fs::remove_all(dir);
        return r;
    };
    const MissionResult on = fly(true);
    const MissionResult off = fly(false);
    EXPECT_TRUE(on.completed);
    EXPECT_TRUE(off.completed);
    std::printf("steady wind: deviation max %.3f m with compensation, %.3f m without\n",
                on.path_deviation_max_m, off.path_deviation_max_m);
    // Measured 0.140 m with, 0.273 m without (the estimate itself is 0.18 m RMS here).
    EXPECT_LT(on.path_deviation_max_m, 0.2);
    EXPECT_GT(off.path_deviation_max_m, 1.5 * on.path_deviation_max_m);
}

// The whole default job with the fast registration documented for sites with UWB (0.5 mm /
// 0.05 mrad convergence, 1 cm refit distance), on a seed where, along the top line, the hull
// leaves LiODOM four unobserved directions for ten seconds and nothing aids the local EKF's
// velocity there (it reached 7 m/s). LiODOM predicted with the local filter's motion slid its
// map along the hull until no cell was in reach, and never registered again (589 sweeps,
// mission not completed); predicted with the global estimate's motion, it registers every
// sweep.
TEST(ClosedLoop, TheDefaultSweepKeepsLiodomRegisteredWhereTheLocalFilterWanders) {
    MissionScenario m = load_mission_scenario(std::string(SCANTLING_SOURCE_DIR) +
                                              "/scenarios/missions/hull_sweep_closed_loop.yaml");
    m.simulation.seed = 5;
    m.stack.odometry.registration.convergence_translation_m = 5e-4;
    m.stack.odometry.registration.convergence_rotation_rad = 5e-5;
    m.stack.odometry.registration.refit_distance_m = 0.01;
    m.simulation.export_world.world = false;
    m.coverage.reset();
    const fs::path dir = temp_dir("sweep_seed5");
    const MissionResult r = run_mission(m, dir.string());
    EXPECT_TRUE(r.completed);
    EXPECT_EQ(r.waypoints_reached, 8u);
    EXPECT_EQ(r.odometry_unregistered, 0u);
    EXPECT_LT(r.position_error_rms_m, 0.10);   // measured 0.063 m (issue 13 target 0.10)
    EXPECT_LT(r.path_deviation_mean_m, 0.13);  // measured 0.109 m
    EXPECT_LT(r.odometry_iterations, 3 * r.odometry_registered);  // the fast setting held
    fs::remove_all(dir);
}

}  // namespace
}  // namespace scantling::mission
