// The crawler's stop-and-map in closed loop (mission/crawler_stack.hpp, perception/
// stop_and_map.hpp): a short rectangle on the plate with labelled obstacles beside it, the
// crawler carrying a Mid-70 rosette LiDAR.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include <scantling/io/mission_log.hpp>
#include <scantling/mission/crawler_mission.hpp>
#include <scantling/sim/surface_obstacles_truth.hpp>

namespace scantling::mission {
namespace {

namespace fs = std::filesystem;

// Two transects 0.4 m apart, 0.6 m long, up +y; a bracket 0.3 m beyond the first transect's top
// and a bolt beside its middle, both in the LiDAR's view from a stop.
const std::string kPlate = R"(
simulation:
  world:
    type: plate
    plate: {length_m: 5.0, width_m: 2.0}
    obstacles:
      - {kind: bracket, position_world: [0.0, 0.75, 0.0], size_m: [0.12, 0.06, 0.08]}
      - {kind: bolt, position_world: [-0.15, 0.1, 0.0], diameter_m: 0.03, height_m: 0.025}
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
    - type: rosette_lidar
      T_body_sensor: {xyz: [0.15, 0.0, 0.30], rpy_deg: [0.0, 40.0, 0.0]}
    - {type: camera, width: 160, height: 120, rate_hz: 1,
       T_body_sensor: {xyz: [0.15, 0.0, 0.30], rpy_deg: [-135.0, 0.0, -90.0]}}
  duration_s: 120
  dt_s: 0.01
  seed: 3
  export: {world: false}
start: {xyz: [0.0, -0.5, 0.0], rpy_deg: [0.0, 0.0, 90.0]}
mission:
  type: surface_rectangle
  start_m: [0.0, -0.3, 0.0]
  width_m: 0.4
  height_m: 0.6
  max_step_m: 0.4
  up: [0.0, 1.0, 0.0]
  swath_width_m: 0.4
texture_map: {cell_size_m: 0.01, min_x_m: -0.5, max_x_m: 0.9, min_y_m: -0.8, max_y_m: 1.2}
stack:
  stop_spacing_m: 0.5
  stop_and_map:
    obstacles: {column_median: true, rim_cells: 2, min_cluster_cells: 2}
)";

std::size_t files_in(const fs::path& dir) {
    if (!fs::exists(dir)) return 0;
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), {}));
}

TEST(CrawlerStopAndMap, StopsMapsAndFindsTheObstaclesBesideItsPath) {
    const CrawlerMissionScenario m = parse_crawler_mission_scenario(kPlate, "stop_and_map.yaml");
    const fs::path dir =
        fs::path(::testing::TempDir()) / ("scantling_stop_and_map_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const CrawlerMissionResult r = run_crawler_mission(m, dir.string());
    const io::MissionLog log = *io::read_mission_log(dir.string());
    const std::size_t rosette_files = files_in(dir / "rosette");
    std::ifstream metadata_file(dir / "mission" / "texture" / "metadata.json");
    ASSERT_TRUE(metadata_file.good()) << "no texture map written";
    const nlohmann::json texture = nlohmann::json::parse(metadata_file);
    const bool clean_png = fs::exists(dir / "mission" / "texture" / "clean.png");
    fs::remove_all(dir);

    ASSERT_TRUE(r.completed);
    const CrawlerStopScores& s = r.stop_scores;
    std::size_t mapped = 0;
    for (const io::EventRecord& e : log.events) mapped += e.type == "stop_mapped";
    EXPECT_EQ(mapped, s.stops);
    // Three waypoints before the last and a stop in each 0.6 m transect at 0.5 m.
    EXPECT_GE(s.stops, 4u);
    const auto& bracket = s.classes[static_cast<std::size_t>(sim::ObstacleKind::kBracket)];
    const auto& bolt = s.classes[static_cast<std::size_t>(sim::ObstacleKind::kBolt)];
    std::printf(
        "stops %zu: bracket %zu/%zu, bolt %zu/%zu, positive precision %zu/%zu, "
        "PF at stops %.4f m\n",
        s.stops, bracket.found, bracket.in_view, bolt.found, bolt.in_view, s.positive_right,
        s.positive_clusters, s.pf_error_rms_m);
    ASSERT_GT(bracket.in_view, 0u);
    EXPECT_EQ(bracket.found, bracket.in_view);
    ASSERT_GT(bolt.in_view, 0u);
    EXPECT_GE(bolt.found, 1u);
    EXPECT_GE(s.positive_right * 2, s.positive_clusters);  // at least half the clusters right
    EXPECT_LT(s.pf_error_rms_m, 0.03);
    // The recording keeps the stops' LiDAR frames only: ~25 a stop, not 10 a second.
    EXPECT_GT(rosette_files, 20u * s.stops);
    EXPECT_LT(rosette_files, 30u * s.stops + 5u);
    // The texture map: every image on the live layer, one clean layer per stop.
    EXPECT_TRUE(clean_png);
    EXPECT_EQ(texture["stops"].get<std::size_t>(), s.stops);
    EXPECT_GT(texture["images"].get<std::size_t>(), 10u);
    // At 1 cm over 1.4 × 2 m the camera saw most of the plate around the two transects.
    EXPECT_GT(texture["live"]["observed_cells"].get<std::size_t>(), 10000u);
}

}  // namespace
}  // namespace scantling::mission
