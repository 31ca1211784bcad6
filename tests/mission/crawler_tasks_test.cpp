// The crawler's task missions in closed loop (mission/crawler_stack.hpp,
// planning/surface_tasks.hpp): a go-to, transects, and the three stiffener drives whose
// corridor comes from the LiDAR, scored on the simulator's truth; and the task list's refusals.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/mission_log.hpp>
#include <scantling/io/tum.hpp>
#include <scantling/mission/crawler_mission.hpp>

namespace scantling::mission {
namespace {

namespace fs = std::filesystem;

const std::string kPlateTasks = R"(
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
  duration_s: 120
  dt_s: 0.01
  seed: 4
  export: {world: false}
start: {xyz: [-1.0, -0.5, 0.0], rpy_deg: [0.0, 0.0, 0.0]}
mission:
  type: surface_tasks
  swath_width_m: 0.3
  tasks:
    - {type: go_to, goal_m: [-0.5, -0.3, 0.0]}
    - {type: vertical_transect, length_m: 0.6, up: [0.0, 1.0, 0.0]}
    - {type: horizontal_transect, length_m: 0.5, up: [0.0, 1.0, 0.0]}
)";

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() /
                         ("scantling-crawler-tasks-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    return dir;
}

std::size_t count_events(const io::MissionLog& log, const std::string& type) {
    return static_cast<std::size_t>(std::count_if(log.events.begin(), log.events.end(),
                                                  [&](const auto& e) { return e.type == type; }));
}

TEST(CrawlerTasks, GoToThenTransectsEndWhereTheyShould) {
    const CrawlerMissionScenario m = parse_crawler_mission_scenario(kPlateTasks, "tasks");
    ASSERT_EQ(m.tasks.size(), 3u);
    const fs::path dir = fresh_dir("plate");
    const CrawlerMissionResult r = run_crawler_mission(m, dir.string());
    EXPECT_TRUE(r.completed);
    EXPECT_EQ(r.tasks_done, 3u);
    EXPECT_EQ(r.tasks_failed, 0u);
    // Up +y from the goal 0.6 m, then across (up × normal = y × z = +x) 0.5 m.
    const std::vector<io::StampedPose> truth = io::read_tum((dir / "groundtruth.tum").string());
    const Eigen::Vector3d end = truth.back().T_world_body.translation();
    EXPECT_LT((end - Eigen::Vector3d(0.0, 0.3, 0.0)).norm(), 0.05) << end.transpose();
    // The transects are scored, the go-to is not: a few centimetres off at most.
    EXPECT_GT(r.cross_track_samples, 0u);
    EXPECT_LT(r.cross_track_mean_m, 0.03);
    const io::MissionLog log = *io::read_mission_log(dir.string());
    EXPECT_EQ(count_events(log, "task_started"), 3u);
    EXPECT_EQ(count_events(log, "task_done"), 3u);
    fs::remove_all(dir);
}

TEST(CrawlerTasks, OnTheMoebiusStripGoesToItsGoalsOnTheGeodesic) {
    // GoToMesh twice (the second across the twist) around two transects, on the strip's mesh.
    const CrawlerMissionScenario m = load_crawler_mission_scenario(
        std::string(SCANTLING_SOURCE_DIR) + "/scenarios/missions/crawler/moebius_tasks.yaml");
    const fs::path dir = fresh_dir("moebius");
    const CrawlerMissionResult r = run_crawler_mission(m, dir.string());
    EXPECT_TRUE(r.completed);
    EXPECT_EQ(r.tasks_done, 4u);
    const io::MissionLog log = *io::read_mission_log(dir.string());
    const std::vector<io::StampedPose> truth = io::read_tum((dir / "groundtruth.tum").string());
    fs::remove_all(dir);
    // Every leg's end: the snapped goals and the transects' ends; the last is the second goal.
    ASSERT_EQ(log.intended_path.size(), 4u);
    const Eigen::Vector3d goal = log.intended_path.back().position_world_m;
    EXPECT_LT((goal - Eigen::Vector3d(-2.0, -0.3, 0.2)).norm(), 0.05);
    const double miss_m = (truth.back().T_world_body.translation() - goal).norm();
    std::printf("moebius tasks: goal missed by %.4f m, transects' cross-track %.4f m\n", miss_m,
                r.cross_track_mean_m);
    EXPECT_LT(miss_m, 0.03);
    EXPECT_LT(r.cross_track_mean_m, 0.03);
}

/// The true lateral offset of the crawler from a line along x, while it drives along the middle
/// of a stiffener drive (x from -1.4 to 0.6: past the join onto the corridor, before its end).
struct Lateral {
    double mean_m = 0.0;
    double max_m = 0.0;
    std::size_t samples = 0;
};

Lateral lateral_error(const fs::path& dir, int axis, double centre_m) {
    Lateral l;
    for (const io::StampedPose& p : io::read_tum((dir / "groundtruth.tum").string())) {
        const Eigen::Vector3d t = p.T_world_body.translation();
        if (t.x() < -1.4 || t.x() > 0.6) continue;
        const double e = std::abs(t[axis] - centre_m);
        l.mean_m += e;
        l.max_m = std::max(l.max_m, e);
        ++l.samples;
    }
    if (l.samples > 0) l.mean_m /= static_cast<double>(l.samples);
    return l;
}

struct StiffenerRun {
    CrawlerMissionResult result;
    Lateral lateral;
    io::MissionLog log;
};

StiffenerRun run_stiffener(const std::string& file, int axis, double centre_m) {
    const CrawlerMissionScenario m = load_crawler_mission_scenario(
        std::string(SCANTLING_SOURCE_DIR) + "/scenarios/missions/crawler/" + file);
    const fs::path dir = fresh_dir(fs::path(file).stem().string());
    StiffenerRun run;
    run.result = run_crawler_mission(m, dir.string());
    run.lateral = lateral_error(dir, axis, centre_m);
    run.log = *io::read_mission_log(dir.string());
    std::printf("%s: lateral mean %.4f max %.4f m over %zu ticks, cross-track %.4f m\n",
                file.c_str(), run.lateral.mean_m, run.lateral.max_m, run.lateral.samples,
                run.result.cross_track_mean_m);
    fs::remove_all(dir);
    return run;
}

TEST(CrawlerTasks, DrivesBetweenTwoStiffenersOnTheFramesCentreLine) {
    // Webs at y = ±0.333 m: the frame's centre line is y = 0.
    const StiffenerRun run = run_stiffener("plate_5x2_between_stiffeners.yaml", 1, 0.0);
    EXPECT_TRUE(run.result.completed);
    EXPECT_EQ(count_events(run.log, "corridor_found"), 1u);
    ASSERT_GT(run.lateral.samples, 1000u);
    EXPECT_LT(run.lateral.mean_m, 0.02);
    EXPECT_LT(run.lateral.max_m, 0.05);
    // Re-measured at every stop on the way (0.5 m apart).
    EXPECT_GE(count_events(run.log, "corridor_remeasured"), 4u);
}

TEST(CrawlerTasks, DrivesOnAStiffenersTopFaceWithoutFallingOff) {
    // The flange's top: z = 0.3, y from -0.006 to 0.196 (centre 0.095).
    const StiffenerRun run = run_stiffener("stiffener_top.yaml", 1, 0.095);
    EXPECT_TRUE(run.result.completed);
    ASSERT_GT(run.lateral.samples, 1000u);
    EXPECT_LT(run.lateral.mean_m, 0.02);
    EXPECT_LT(run.lateral.max_m, 0.05);
}

TEST(CrawlerTasks, DrivesOnAStiffenersSideAlongItsMiddle) {
    // The web's side: y = -0.006, z from 0 to 0.4 (centre 0.2).
    const StiffenerRun run = run_stiffener("stiffener_side.yaml", 2, 0.2);
    EXPECT_TRUE(run.result.completed);
    ASSERT_GT(run.lateral.samples, 1000u);
    EXPECT_LT(run.lateral.mean_m, 0.03);
    EXPECT_LT(run.lateral.max_m, 0.06);
}

std::string with(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
}

TEST(CrawlerTasks, BadTaskListsAreClearErrors) {
    const auto message = [](const std::string& text) -> std::string {
        try {
            const CrawlerMissionScenario m = parse_crawler_mission_scenario(text, "bad");
            run_crawler_mission(m, fresh_dir("bad").string());
        } catch (const Error& e) {
            return e.what();
        }
        return "no error";
    };
    const auto expect_in = [&](const std::string& text, const std::string& needle) {
        const std::string got = message(text);
        EXPECT_NE(got.find(needle), std::string::npos) << got;
    };
    expect_in(with(kPlateTasks, "type: vertical_transect", "type: vertical_transct"),
              "mission.tasks[1].type");
    expect_in(with(kPlateTasks, "length_m: 0.6, up", "width_m: 0.6, up"),
              "'mission.tasks[1].width_m': not a key of a vertical_transect task (it takes: "
              "length_m, reverse, up)");
    expect_in(with(kPlateTasks, "swath_width_m: 0.3", "swath_width_m: 0.3\n  width_m: 2.0"),
              "'mission.width_m': not a key of a surface_tasks mission");
    expect_in(with(kPlateTasks, "type: surface_tasks", "type: surface_taks"), "mission.type");
    // The transect runs off the plate (y = 1 m): refused before the crawler moves.
    expect_in(with(kPlateTasks, "length_m: 0.6", "length_m: 2.0"),
              "mission.tasks[1] (vertical_transect)");
    // A stiffener drive needs the LiDAR.
    expect_in(with(kPlateTasks, "type: horizontal_transect, length_m: 0.5, up: [0.0, 1.0, 0.0]",
                   "type: drive_on_stiffener, length_m: 0.5"),
              "mission.tasks[2] (drive_on_stiffener): the stiffener's geometry comes from the "
              "LiDAR, and none is mounted");
    expect_in(with(kPlateTasks, "goal_m: [-0.5, -0.3, 0.0]", "goal_m: [-0.5, -0.3, 0.4]"),
              "mission.tasks[0] (go_to).goal_m");
}

TEST(CrawlerTasks, NoCorridorFailsTheTaskPausesAndAResumeSkipsIt) {
    // Between-stiffeners on a bare plate: the stop's cloud has no walls, the task fails, the
    // crawler pauses; the operator's resume goes on to the transect after it.
    std::string text =
        with(kPlateTasks, "    - {type: imu, rate_hz: 100}",
             "    - {type: imu, rate_hz: 100}\n    - type: rosette_lidar\n"
             "      T_body_sensor: {xyz: [0.15, 0.0, 0.30], rpy_deg: [0.0, 40.0, 0.0]}");
    text = with(text, "type: horizontal_transect, length_m: 0.5, up: [0.0, 1.0, 0.0]",
                "type: drive_between_stiffeners, length_m: 1.0}\n"
                "    - {type: horizontal_transect, length_m: 0.5, up: [0.0, 1.0, 0.0]");
    text +=
        "stack: {obstacle_slow_distance_m: 0.0, stop_spacing_m: 0.0}\n"
        "operator:\n  - {time_s: 40.0, command: resume}\n";
    const CrawlerMissionScenario m = parse_crawler_mission_scenario(text, "no_corridor");
    const fs::path dir = fresh_dir("no-corridor");
    const CrawlerMissionResult r = run_crawler_mission(m, dir.string());
    EXPECT_TRUE(r.completed);
    EXPECT_EQ(r.tasks_failed, 1u);
    EXPECT_EQ(r.tasks_done, 3u);
    const io::MissionLog log = *io::read_mission_log(dir.string());
    const auto failed = std::find_if(log.events.begin(), log.events.end(),
                                     [](const auto& e) { return e.type == "task_failed"; });
    ASSERT_NE(failed, log.events.end());
    EXPECT_NE(failed->json.find("no corridor in the stop's cloud"), std::string::npos)
        << failed->json;
    EXPECT_LT(failed->t_s, 40.0);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace scantling::mission
