// Scenarios with the ROV, crawler and legged vehicles and the sonar, rosette, stereo, ranging
// and odometry sensors: files, counts, read-back, surface contact, determinism.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/scenario_runner.hpp>

#include <scantling/core/surface_projector.hpp>
#include "scenario_test_support.hpp"

namespace scantling::sim {
namespace {

namespace fs = std::filesystem;

/// A 1 s crawler run on a plate with every new sensor at low resolution.
const std::string kCoverageScenario = R"(
world:
  type: plate
vehicle:
  type: crawler
  trajectory:
    type: waypoints
    waypoints:
      max_speed_mps: 0.2
      waypoints: [{position_m: [-1.0, 0.0, 0.0]}, {position_m: [1.0, 0.0, 0.0]}]
sensors:
  - {type: multibeam_sonar, num_beams: 32, num_bins: 48, rate_hz: 5,
     T_body_sensor: {xyz: [0.0, 0.0, 0.3], rpy_deg: [0.0, 20.0, 0.0]}}
  - {type: rosette_lidar, rate_hz: 10, T_body_sensor: {xyz: [0.0, 0.0, 0.2], rpy_deg: [0.0, 45.0, 0.0]}}
  - {type: stereo_points, width: 212, rate_hz: 5,
     T_body_sensor: {xyz: [0.0, 0.0, 0.3], rpy_deg: [180.0, 0.0, -90.0]}}
  - {type: range_finder, T_body_sensor: {xyz: [0.0, 0.0, 0.3], rpy_deg: [0.0, 90.0, 0.0]}}
  - type: uwb
    anchors: [{id: 7, position_world: [0.0, 3.0, 1.0]}, {id: 9, position_world: [3.0, 0.0, 1.0]}]
  - {type: pressure, surface_z_m: 2.0}
  - type: dvl
  - type: wheel_odometry
duration_s: 1.0
seed: 21
export: {world: false}
)";

/// Crawler contact: the dynamics settle on the analytic surface; the mesh differs from it by
/// the facet sagitta and weld beads (a few mm).
constexpr double kSurfaceContact_m = 0.01;

fs::path temp_dir(const std::string& name) {
    return test::scenario_temp_dir("coverage_test", name);
}

using test::read_tree;

ScenarioRunResult run_coverage(const fs::path& dir, std::uint64_t seed, int num_threads = 0) {
    Scenario scenario = parse_scenario(kCoverageScenario, "coverage.yaml");
    scenario.seed = seed;
    scenario.parallel.num_threads = num_threads;
    return run_scenario(scenario, dir.string());
}

TEST(ScenarioCoverage, EveryNewSensorWritesItsFilesWithTheRightCounts) {
    const fs::path dir = temp_dir("files");
    const RecordingCounts counts = run_coverage(dir, 21).counts;
    EXPECT_EQ(counts.sonar_pings, 5);
    EXPECT_EQ(counts.rosette_frames, 10);
    EXPECT_GT(counts.rosette_points, 1000);
    EXPECT_EQ(counts.stereo_frames, 5);
    EXPECT_EQ(counts.ranges, 50);
    EXPECT_EQ(counts.uwb_rounds, 10);
    EXPECT_EQ(counts.pressure, 20);
    EXPECT_EQ(counts.dvl, 10);
    EXPECT_EQ(counts.wheel_odometry, 50);
    for (const char* file :
         {"sonar/000004.png", "sonar/000004.bin", "sonar/meta.json", "sonar/times.txt",
          "sonar/poses_gt.txt", "rosette/000009.bin", "rosette/times.txt", "rosette/poses_gt.txt",
          "stereo/000004.ply", "stereo/poses_gt.txt", "range.csv", "uwb.csv", "pressure.csv",
          "dvl.csv", "wheel_odometry.csv"}) {
        EXPECT_TRUE(fs::exists(dir / file)) << file;
    }
    EXPECT_EQ(fs::file_size(dir / "sonar" / "000000.bin"), 32u * 48u * sizeof(float));
}

TEST(ScenarioCoverage, ReaderReadsTheNewStreamsBack) {
    const fs::path dir = temp_dir("reader");
    run_coverage(dir, 21);
    const io::Recording recording = io::open_recording(dir.string());
    EXPECT_EQ(recording.sonar_pings().size(), 5u);
    EXPECT_EQ(recording.read_sonar_intensity(2).size(), 32u * 48u);
    ASSERT_EQ(recording.rosette_frames().size(), 10u);
    EXPECT_GT(recording.read_rosette_frame(3).size(), 100u);
    EXPECT_DOUBLE_EQ(recording.read_rosette_frame(3).stamp_s, 0.3);
    EXPECT_EQ(recording.stereo_frames().size(), 5u);
    EXPECT_NO_THROW(recording.read_stereo_frame(4));
    EXPECT_EQ(recording.ranges().size(), 50u);
    ASSERT_EQ(recording.uwb().size(), 20u);  // two anchors per round
    EXPECT_EQ(recording.uwb()[0].anchor_id, 7);
    EXPECT_EQ(recording.uwb()[1].anchor_id, 9);
    ASSERT_EQ(recording.pressure().size(), 20u);
    // The crawler is on the plate (z = 0), 2 m below the surface; pressure noise 50 Pa is
    // 5 mm of water, so 5 cm is a generous bound.
    EXPECT_NEAR(recording.pressure()[3].depth_m, 2.0, 0.05);
    EXPECT_EQ(recording.dvl().size(), 10u);
    ASSERT_EQ(recording.wheel_odometry().size(), 50u);
    EXPECT_GT(recording.wheel_odometry().back().forward_speed_mps, 0.05);
    // The range finder looks down at the plate from 0.3 m.
    ASSERT_TRUE(recording.ranges()[10].valid);
    EXPECT_NEAR(recording.ranges()[10].range_m, 0.3, 0.1);
}

TEST(ScenarioCoverage, SameSeedGivesByteIdenticalNewStreams) {
    const fs::path a = temp_dir("seed_a"), b = temp_dir("seed_b"), c = temp_dir("seed_c");
    run_coverage(a, 5);
    run_coverage(b, 5, 1);
    run_coverage(c, 6);
    const auto files_a = read_tree(a), files_b = read_tree(b), files_c = read_tree(c);
    EXPECT_GT(files_a.size(), 35u);
    EXPECT_TRUE(files_a == files_b);
    EXPECT_NE(files_a.at("uwb.csv"), files_c.at("uwb.csv"));
    EXPECT_NE(files_a.at("rosette/000000.bin"), files_c.at("rosette/000000.bin"));
    EXPECT_NE(files_a.at("sonar/000000.bin"), files_c.at("sonar/000000.bin"));
}

TEST(ScenarioCoverage, CrawlerStaysOnTheStorageTankWall) {
    Scenario s = parse_scenario(R"(
world: {type: storage_tank}
vehicle:
  type: crawler
  trajectory:
    type: lawnmower
    lawnmower:
      T_world_wall: {xyz: [6.0, -1.0, 0.5], rpy_deg: [90.0, 0.0, 90.0]}
      width_m: 2.0
      height_m: 1.0
      standoff_m: 0.05
      slices: vertical
      face_wall: false
      max_speed_mps: 0.25
duration_s: 3.0
export: {world: false}
)");
    const fs::path dir = temp_dir("tank");
    run_scenario(s, dir.string());
    const io::Recording recording = io::open_recording(dir.string());
    const World world = build_world(s.world);
    const MeshSurface mesh(world.mesh);
    const Eigen::Vector3d start = recording.ground_truth().front().T_world_body.translation();
    const Eigen::Vector3d end = recording.ground_truth().back().T_world_body.translation();
    EXPECT_GT((end - start).norm(), 0.3);  // it drove (up to 0.25 m/s for 3 s)
    for (const io::StampedPose& pose : recording.ground_truth()) {
        const Eigen::Vector3d p = pose.T_world_body.translation();
        EXPECT_LT((mesh.project(p).point - p).norm(), kSurfaceContact_m) << pose.stamp_s;
    }
}

/// A 3 s straight leg at 0.3 m/s for the tracking vehicles.
Scenario tracking_scenario(VehicleType type) {
    Scenario s = parse_scenario(R"(
world: {type: plate}
vehicle:
  trajectory:
    type: waypoints
    waypoints:
      max_speed_mps: 0.3
      waypoints: [{position_m: [0.0, 0.0, 1.0]}, {position_m: [0.8, 0.4, 1.0]}]
duration_s: 3.0
export: {world: false}
)");
    s.vehicle.type = type;
    return s;
}

TEST(ScenarioCoverage, RovAndLeggedBaseTrackTheTrajectory) {
    // P loops (1.5 / s) with feed-forward behind a 0.3 m/s reference: the ROV's damping
    // (surge τ 1 s) and thrust lag leave ~0.19 m while it accelerates; the legged base less.
    constexpr double kTrackingTolerance_m = 0.25;
    for (const VehicleType type : {VehicleType::kRov, VehicleType::kLegged}) {
        const Scenario s = tracking_scenario(type);
        const fs::path dir = temp_dir("tracking");
        run_scenario(s, dir.string());
        const io::Recording recording = io::open_recording(dir.string());
        const auto trajectory = make_trajectory(s.vehicle.trajectory);
        for (const io::StampedPose& pose : recording.ground_truth()) {
            const Eigen::Vector3d ref = trajectory->at(pose.stamp_s).T_world_body.translation();
            const Eigen::Vector3d p = pose.T_world_body.translation();
            EXPECT_LT((p - ref).head<2>().norm(), kTrackingTolerance_m) << pose.stamp_s;
        }
    }
}

TEST(ScenarioCoverage, UwbWithoutAnchorsIsRejected) {
    EXPECT_THROW(parse_scenario("sensors: [{type: uwb}]\n"), ConfigError);
}

}  // namespace
}  // namespace scantling::sim
