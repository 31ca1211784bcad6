// The exploration in closed loop (issue 16 items 3 and 6): a drone with a depth camera
// explores a small closed room with a partition until its next-best-view planner finds no gain
// left, maps the reachable free volume and never touches a wall; bad input (a map resolution
// of 0, no depth camera, a start outside the bounds, unknown keys) is refused naming the field,
// a start inside a wall is refused before anything is written, and a depth camera that never
// delivers makes the vehicle hover and then abort without a single plan.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/core/triangle_mesh.hpp>
#include <scantling/io/mesh_io.hpp>
#include <scantling/mission/exploration_mission.hpp>

namespace scantling::mission {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) /
                         ("scantling_explore_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    return dir;
}

/// An axis-aligned box's six faces (both sides: the room is seen from inside, the partition
/// from both).
void add_box(TriangleMesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    const int base = static_cast<int>(mesh.vertices.size());
    for (int k = 0; k < 8; ++k) {
        mesh.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(),
                                   k & 4 ? hi.z() : lo.z());
    }
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
        mesh.triangles.emplace_back(base + f[0], base + f[1], base + f[2]);
        mesh.triangles.emplace_back(base + f[0], base + f[2], base + f[3]);
    }
}

/// A 4 × 2 × 2 m closed room with a partition at x = 2 m from the floor to 0.9 m, leaving a
/// 1.1 m gap under the ceiling: the second half is seen only after flying up and over. (With a
/// 0.8 m gap the 0.3 m tall vehicle box, its voxels and 0.1 m of drift left no edge over it.)
std::string write_room(const fs::path& dir) {
    TriangleMesh mesh;
    add_box(mesh, {-0.05, -0.05, -0.05}, {4.05, 2.05, 0.0});  // floor
    add_box(mesh, {-0.05, -0.05, 2.0}, {4.05, 2.05, 2.05});   // ceiling
    add_box(mesh, {-0.05, -0.05, 0.0}, {0.0, 2.05, 2.0});     // x = 0 wall
    add_box(mesh, {4.0, -0.05, 0.0}, {4.05, 2.05, 2.0});      // x = 4 wall
    add_box(mesh, {0.0, -0.05, 0.0}, {4.0, 0.0, 2.0});        // y = 0 wall
    add_box(mesh, {0.0, 2.0, 0.0}, {4.0, 2.05, 2.0});         // y = 2 wall
    add_box(mesh, {1.98, 0.0, 0.0}, {2.02, 2.0, 0.9});        // partition
    fs::create_directories(dir);
    const std::string path = (dir / "room.ply").string();
    io::write_mesh(path, mesh);
    return path;
}

std::string room_scenario(const std::string& mesh_path) {
    return R"(
simulation:
  world: {type: mesh, mesh: {path: ")" +
           mesh_path + R"("}}
  vehicle: {type: mav}
  sensors:
    - {type: imu}
    - {type: vio, preset: t265}
    - {type: barometer}
    - type: depth_camera
      preset: l515
      width: 320
      rate_hz: 5
      T_body_sensor: {xyz: [0.1, 0.0, 0.0], rpy_deg: [-90.0, 0.0, -90.0]}
  duration_s: 600
  seed: 4
  export: {world: false}
start: {xyz: [1.0, 1.0, 0.2], rpy_deg: [0.0, 0.0, 0.0]}
mission:
  type: explore
  bounds: {min: [0.0, 0.0, 0.0], max: [4.0, 2.0, 2.0]}
  record_depth_every: 0
stack:
  takeoff_height_m: 0.8
  max_speed_mps: 0.5
  map: {resolution_m: 0.1, max_range_m: 5.0}
  nbv: {max_nodes: 30}
)";
}

std::string with(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

struct Explored {
    ExplorationMissionResult result;
    std::string events;
    std::string curve;
    bool map_written = false;
};

Explored explore(const std::string& text, const std::string& name) {
    const ExplorationMissionScenario m = parse_exploration_mission_scenario(text, name + ".yaml");
    const fs::path dir = temp_dir(name);
    Explored run;
    run.result = run_exploration_mission(m, dir.string());
    run.events = read_text(dir / "mission" / "events.jsonl");
    run.curve = read_text(dir / "mission" / "exploration.csv");
    run.map_written = fs::file_size(dir / "mission" / "map.bt") > 0;
    fs::remove_all(dir);
    return run;
}

std::string config_error(const std::string& text) {
    try {
        parse_exploration_mission_scenario(text, "bad.yaml");
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "accepted";
    return "";
}

class ExplorationMission : public ::testing::Test {
  protected:
    static void SetUpTestSuite() { room_path_ = write_room(temp_dir("room_mesh")); }
    static void TearDownTestSuite() { fs::remove_all(temp_dir("room_mesh")); }
    static std::string room_path_;
};
std::string ExplorationMission::room_path_;

TEST_F(ExplorationMission, MapsTheRoomAndTheSpaceBehindThePartitionUntilNoGainIsLeft) {
    const Explored run = explore(room_scenario(room_path_), "room");
    const ExplorationMissionResult& r = run.result;
    EXPECT_TRUE(r.completed) << run.events;
    EXPECT_EQ(r.final_state, control::MissionState::kCompleted);
    // The room's 16 m³ less the partition and the voxel layers the plates cross.
    EXPECT_GT(r.reachable_free_m3, 12.0);
    EXPECT_LT(r.reachable_free_m3, 16.0);
    EXPECT_GE(r.reachable_share, 0.95) << run.curve;
    EXPECT_GE(r.plans, 5u);
    EXPECT_GT(r.path_length_m, 4.0);  // over the partition and into the far half
    // The vehicle box's half width is 0.3 m: no wall came nearer than the box's edge.
    EXPECT_GT(r.min_wall_distance_m, 0.25);
    EXPECT_LT(r.position_error_rms_m, 0.2);
    EXPECT_NE(run.events.find("nbv_planned"), std::string::npos);
    EXPECT_NE(run.events.find("no gain left"), std::string::npos);
    EXPECT_TRUE(run.map_written);
    // The curve grows: the explored volume at the end exceeds the first sample's.
    ASSERT_GE(r.curve.size(), 3u);
    EXPECT_GT(r.curve.back().explored_m3, r.curve.front().explored_m3 + 5.0);
    EXPECT_GT(r.curve.back().reachable_share, r.curve[1].reachable_share);
}

TEST_F(ExplorationMission, BadInputIsRefusedNamingTheField) {
    const std::string good = room_scenario(room_path_);
    const auto expect_refused = [&](const std::string& from, const std::string& to,
                                    const std::string& named) {
        const std::string message = config_error(with(good, from, to));
        EXPECT_NE(message.find(named), std::string::npos) << message;
    };
    expect_refused("resolution_m: 0.1", "resolution_m: 0", "stack.map.resolution_m");
    expect_refused("resolution_m: 0.1", "resolution_m: -0.1", "stack.map.resolution_m");
    expect_refused("    - type: depth_camera\n      preset: l515\n      width: 320\n",
                   "    - type: range_finder\n", "needs a depth_camera");
    expect_refused("xyz: [1.0, 1.0, 0.2]", "xyz: [9.0, 1.0, 0.2]", "outside mission.bounds");
    expect_refused("max: [4.0, 2.0, 2.0]", "max: [0.0, 2.0, 2.0]", "mission.bounds");
    expect_refused("max: [4.0, 2.0, 2.0]", "max: [100000.0, 2.0, 2.0]", "voxels");
    expect_refused("nbv: {max_nodes: 30}", "nbv: {max_nodes: 30, wings: 2}", "wings");
    expect_refused("nbv: {max_nodes: 30}", "nbv: {max_nodes: 1}", "max_nodes");
}

TEST_F(ExplorationMission, ADepthCameraThatNeverDeliversEndsTheRunSafely) {
    std::string text = room_scenario(room_path_);
    text += "faults:\n  - {sensor: depth_camera, kind: dropout, start_s: 0.0, duration_s: 1000}\n";
    text = with(text, "duration_s: 600", "duration_s: 120");
    const Explored run = explore(text, "no_depth");
    EXPECT_FALSE(run.result.completed);
    EXPECT_EQ(run.result.final_state, control::MissionState::kAborted);
    EXPECT_NE(run.events.find(R"("type":"sensor_lost","sensor":"depth_camera")"), std::string::npos)
        << run.events;
    EXPECT_NE(run.events.find("the depth camera is silent"), std::string::npos) << run.events;
    EXPECT_EQ(run.events.find("nbv_planned"), std::string::npos) << run.events;
    EXPECT_EQ(run.result.plans, 0u);
    EXPECT_LT(run.result.path_length_m, 1.5);  // the take-off and the turn, nothing else
}

TEST_F(ExplorationMission, AStartInsideTheWallIsRefusedBeforeAnythingIsWritten) {
    // The vehicle starts inside the partition.
    const std::string text =
        with(room_scenario(room_path_), "xyz: [1.0, 1.0, 0.2]", "xyz: [2.0, 1.0, 0.2]");
    const ExplorationMissionScenario m = parse_exploration_mission_scenario(text, "in_wall.yaml");
    const fs::path dir = temp_dir("in_wall");
    std::string message;
    try {
        run_exploration_mission(m, dir.string());
        ADD_FAILURE() << "flown";
    } catch (const InputError& e) {
        message = e.what();
    }
    EXPECT_NE(message.find("start: the vehicle at (2.000, 1.000, 0.200) m lies inside"),
              std::string::npos)
        << message;
    EXPECT_FALSE(fs::exists(dir));
}

TEST(ExplorationStack, TheOperatorStartsPausesTakesOverAndAbortsIt) {
    using control::MissionState;
    using control::OperatorCommand;
    using control::OperatorCommandType;
    ExplorationStack stack({}, Eigen::Isometry3d::Identity());
    const auto send = [&](double t_s, OperatorCommandType type,
                          const Eigen::Vector3d& v = Eigen::Vector3d::Zero()) {
        const std::vector<OperatorCommand> commands{{.type = type, .v_world_mps = v}};
        return stack.command(t_s, commands);
    };
    EXPECT_EQ(stack.command(0.0, {}).state, MissionState::kIdle);
    ExplorationCommand c = send(0.01, OperatorCommandType::kStart);
    EXPECT_EQ(c.state, MissionState::kRunning);
    EXPECT_GT(c.v_world_mps.z(), 0.0);  // taking off
    EXPECT_EQ(stack.phase(), ExplorationPhase::kTakeOff);
    c = send(0.02, OperatorCommandType::kPause);
    EXPECT_EQ(c.state, MissionState::kPaused);
    EXPECT_NE(c.events.front().json.find(R"("to":"paused")"), std::string::npos);
    c = send(0.03, OperatorCommandType::kTakeOver, Eigen::Vector3d(0.2, 0.0, 0.0));
    EXPECT_EQ(c.state, MissionState::kOperator);
    EXPECT_NEAR(c.v_world_mps.x(), 0.2, 1e-12);  // no depth frame: nothing to avoid
    c = send(0.04, OperatorCommandType::kHandBack);
    EXPECT_EQ(c.state, MissionState::kRunning);
    c = send(0.05, OperatorCommandType::kAbort);
    EXPECT_EQ(c.state, MissionState::kAborted);
    EXPECT_EQ(send(0.06, OperatorCommandType::kResume).state, MissionState::kAborted);
}

TEST(ExplorationStack, RejectsNonFiniteSamplesWithOneEventPerEpisode) {
    ExplorationStack stack({}, Eigen::Isometry3d::Identity());
    io::ImuRecord bad;
    bad.stamp_s = 0.01;
    bad.specific_force_mps2 = Eigen::Vector3d(std::nan(""), 0.0, 9.81);
    stack.add_imu(bad);
    bad.stamp_s = 0.02;
    stack.add_imu(bad);
    stack.add_barometer({.stamp_s = std::nan(""), .altitude_m = 1.0});
    const ExplorationCommand c = stack.command(0.03, {});
    EXPECT_EQ(stack.inputs_rejected(), 3u);
    ASSERT_EQ(c.events.size(), 2u);  // imu once, barometer once
    EXPECT_EQ(c.events[0].type, "input_rejected");
    EXPECT_NE(c.events[0].json.find("imu"), std::string::npos);
    EXPECT_THROW(ExplorationStack({}, Eigen::Isometry3d(Eigen::Translation3d(std::nan(""), 0, 0))),
                 InputError);
    ExplorationStackConfig bad_config;
    bad_config.max_speed_mps = 0.0;
    EXPECT_THROW(ExplorationStack(bad_config, Eigen::Isometry3d::Identity()), ConfigError);
}

}  // namespace
}  // namespace scantling::mission
