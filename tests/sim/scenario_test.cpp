// Scenarios: parsing and validation, the runner's recording, determinism.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/scenario_runner.hpp>

#include "scenario_test_support.hpp"

namespace scantling::sim {
namespace {

namespace fs = std::filesystem;

/// A 1 s scenario with every sensor at low resolution: a few hundred ms to run.
const std::string kSmallScenario = R"(
name: small
world:
  type: cylinder
vehicle:
  type: scripted
  trajectory:
    type: helix
    helix: {radius_m: 3.0, z0_m: 1.0}
sensors:
  - type: spinning_lidar
    preset: os1_64
    columns: 512
    rate_hz: 10
    write_ply: true
    T_body_sensor: {xyz: [0.0, 0.0, 0.1], rpy_deg: [0.0, 0.0, 30.0]}
  - type: imu
  - type: vio
  - type: depth_camera
    preset: azure_nfov_binned
    rate_hz: 5
    T_body_sensor: {rpy_deg: [-90.0, 0.0, -90.0]}
  - type: camera
    width: 64
    rate_hz: 2
    T_body_sensor: {rpy_deg: [-90.0, 0.0, -90.0]}
duration_s: 1.0
seed: 11
export: {map_spacing_m: 0.2}
)";

/// Float32 storage of the .bin / .ply: points read back to within float rounding at ~5 m.
constexpr double kFloatTolerance_m = 1e-5;

fs::path temp_dir(const std::string& name) {
    return test::scenario_temp_dir("scenario_test", name);
}

using test::read_tree;

ScenarioRunResult run_small(const fs::path& dir, std::uint64_t seed, int num_threads = 0) {
    Scenario scenario = parse_scenario(kSmallScenario, "small.yaml");
    scenario.seed = seed;
    scenario.parallel.num_threads = num_threads;
    return run_scenario(scenario, dir.string());
}

void expect_parse_error(const std::string& yaml, const std::string& key, int line) {
    try {
        parse_scenario(yaml, "bad.yaml");
        ADD_FAILURE() << "no error for:\n" << yaml;
    } catch (const ParseError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("'" + key + "'"), std::string::npos) << what;
        EXPECT_NE(what.find("line " + std::to_string(line)), std::string::npos) << what;
    }
}

TEST(Scenario, ParsesEverySection) {
    const Scenario s = parse_scenario(kSmallScenario, "small.yaml");
    EXPECT_EQ(s.name, "small");
    EXPECT_EQ(s.world.type, WorldType::kCylinder);
    EXPECT_EQ(s.vehicle.trajectory.type, TrajectoryType::kHelix);
    EXPECT_DOUBLE_EQ(s.vehicle.trajectory.helix.radius_m, 3.0);
    ASSERT_EQ(s.sensors.size(), 5u);
    EXPECT_EQ(s.sensors[0].columns, 512);
    EXPECT_DOUBLE_EQ(s.sensors[0].T_body_sensor.rpy_deg.z(), 30.0);
    EXPECT_EQ(s.sensors[3].preset, SensorPreset::kAzureNfovBinned);
    EXPECT_EQ(s.seed, 11u);
}

TEST(Scenario, MalformedDocumentsNameTheKeyAndLine) {
    expect_parse_error("world: {type: cylinder}\nbogus: 1\n", "bogus", 2);
    expect_parse_error("duration_s: ten\n", "duration_s", 1);
    expect_parse_error("seed: 1\nduration_s: -1\n", "duration_s", 2);
    expect_parse_error("world:\n  type: teapot\n", "world.type", 2);
    expect_parse_error("world:\n  type: cylinder\n  cylinder: {radius_m: 0}\n",
                       "world.cylinder.radius_m", 3);
    expect_parse_error("world:\n  type: cylinder\n  plate: {length_m: 2}\n", "world.plate", 3);
    expect_parse_error("sensors:\n  - type: imu\n    columns: 4\n", "sensors[0].columns", 3);
    expect_parse_error("sensors:\n  - type: imu\n    preset: os1_64\n", "sensors[0].preset", 3);
}

TEST(Scenario, DuplicateSensorTypesAreRejected) {
    EXPECT_THROW(parse_scenario("sensors: [{type: imu}, {type: imu}]\n"), ConfigError);
}

TEST(Scenario, CameraLaserPointersAreReadAndCheckedNamingTheKey) {
    const Scenario s = parse_scenario(
        "sensors:\n  - type: camera\n    lasers:\n"
        "      - {origin_camera: [0, -0.1, 0], spot_radius_m: 0.003}\n"
        "      - {origin_camera: [0, 0.1, 0], direction_camera: [0, 0, 2], rgb: [0, 255, 0]}\n");
    const std::vector<LaserPointer>& lasers = s.sensors.at(0).lasers;
    ASSERT_EQ(lasers.size(), 2u);
    EXPECT_EQ(lasers[0].origin_camera, Eigen::Vector3d(0.0, -0.1, 0.0));
    EXPECT_EQ(lasers[0].direction_camera, Eigen::Vector3d::UnitZ());  // the default
    EXPECT_DOUBLE_EQ(lasers[0].spot_radius_m, 0.003);
    EXPECT_EQ(lasers[0].rgb, Eigen::Vector3d(255.0, 0.0, 0.0));  // red by default
    EXPECT_EQ(lasers[1].direction_camera, Eigen::Vector3d(0.0, 0.0, 2.0));
    EXPECT_EQ(lasers[1].rgb, Eigen::Vector3d(0.0, 255.0, 0.0));
    EXPECT_TRUE(parse_scenario("sensors: [{type: camera}]\n").sensors.at(0).lasers.empty());
    const std::string camera = "sensors:\n  - type: camera\n    lasers:\n";
    expect_parse_error(camera + "      - {origin: [0, 0, 0]}\n", "sensors[0].lasers[0].origin", 4);
    expect_parse_error(camera + "      - {rgb: [0, 300, 0]}\n", "sensors[0].lasers[0].rgb[1]", 4);
    expect_parse_error(camera + "      - {spot_radius_m: 0}\n",
                       "sensors[0].lasers[0].spot_radius_m", 4);
    expect_parse_error("sensors:\n  - type: imu\n    lasers: []\n", "sensors[0].lasers", 3);
    try {
        parse_scenario(camera + "      - {direction_camera: [0, 0, 0]}\n");
        ADD_FAILURE() << "a zero laser direction was accepted";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("sensors[0].lasers[0].direction_camera"),
                  std::string::npos)
            << e.what();
    }
}

TEST(Scenario, EveryShippedScenarioParses) {
    const fs::path dir = fs::path(SCANTLING_SOURCE_DIR) / "scenarios";
    int count = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() != ".yaml") continue;
        SCOPED_TRACE(entry.path().string());
        const Scenario s = load_scenario(entry.path().string());
        EXPECT_GT(scenario_duration_s(s), 0.0);
        ++count;
        // Worlds loaded from ../shared/data (not in the repository) are built only when present.
        const bool from_file =
            s.world.type == WorldType::kShipHullMesh || s.world.type == WorldType::kMesh;
        const fs::path mesh =
            fs::path(s.base_directory) /
            (s.world.type == WorldType::kMesh ? s.world.mesh.path : s.world.ship_hull_mesh.path);
        if (from_file && !fs::exists(mesh)) {
            std::cout << "[ SKIPPED  ] world of " << entry.path().filename()
                      << ": needs the shared data (" << mesh << ")\n";
            continue;
        }
        EXPECT_NO_THROW(build_world(s.world, s.base_directory));
    }
    EXPECT_GE(count, 14);
}

TEST(ScenarioRunner, WritesEveryStreamAndTheReaderReadsItBack) {
    const fs::path dir = temp_dir("roundtrip");
    const ScenarioRunResult result = run_small(dir, 11);
    EXPECT_EQ(result.counts.lidar_sweeps, 10);  // 10 Hz over [0, 1)
    EXPECT_EQ(result.counts.imu, 200);
    EXPECT_EQ(result.counts.vio, 30);
    EXPECT_EQ(result.counts.depth_frames, 5);
    EXPECT_EQ(result.counts.images, 2);
    EXPECT_EQ(result.counts.ground_truth, 201);  // ticks at 0, 5 ms, ..., 1 s
    for (const char* file :
         {"groundtruth.tum", "lidar/000009.bin", "lidar/000009.ply", "lidar/times.txt",
          "lidar/poses_gt.txt", "depth/000004.ply", "images/000001.png", "imu.csv", "vio.csv",
          "world/map.ply", "world/mesh.ply", "world/metadata.json", "summary.json"}) {
        EXPECT_TRUE(fs::exists(dir / file)) << file;
    }
    const io::Recording recording = io::open_recording(dir.string());
    ASSERT_EQ(recording.num_sweeps(), 10u);
    EXPECT_EQ(recording.ground_truth().size(), 201u);
    EXPECT_EQ(recording.imu().size(), 200u);
    EXPECT_EQ(recording.vio().size(), 30u);
    EXPECT_EQ(recording.num_depth_frames(), 5u);
    EXPECT_EQ(recording.num_images(), 2u);
    const PointCloud sweep = recording.read_sweep(3);
    EXPECT_DOUBLE_EQ(sweep.stamp_s, 0.3);
    EXPECT_TRUE(sweep.has_rings());
    EXPECT_TRUE(sweep.has_times());
    EXPECT_GT(sweep.size(), 1000u);
    // Sensor pose = body pose at the sweep start times the mount.
    const Scenario s = parse_scenario(kSmallScenario, "small.yaml");
    const Eigen::Isometry3d expected = make_trajectory(s.vehicle.trajectory)->at(0.3).T_world_body *
                                       s.sensors[0].T_body_sensor.to_isometry();
    EXPECT_TRUE(recording.sweep_pose_gt(3).isApprox(expected, 1e-9));
    EXPECT_TRUE(
        recording.lidar_T_body_sensor().isApprox(s.sensors[0].T_body_sensor.to_isometry(), 1e-12));
    // Every point lies on the cylinder (r = 1 m) or its caps, within noise: check the radius
    // of the side hits in the world frame.
    int side_hits = 0;
    for (const Eigen::Vector3d& p_sensor : sweep.points) {
        const Eigen::Vector3d p = recording.sweep_pose_gt(3) * p_sensor;
        if (p.z() < 0.1 || p.z() > 2.9) continue;
        EXPECT_NEAR(p.head<2>().norm(), 1.0, 0.1);
        ++side_hits;
    }
    EXPECT_GT(side_hits, 1000);
}

TEST(ScenarioRunner, SweepsReadBackAsWritten) {
    const fs::path dir = temp_dir("points");
    run_small(dir, 11);
    const io::Recording recording = io::open_recording(dir.string());
    const PointCloud from_ply = recording.read_sweep(0);
    fs::remove(dir / "lidar" / "000000.ply");  // falls back to the KITTI .bin
    const PointCloud from_bin = recording.read_sweep(0);
    ASSERT_EQ(from_ply.size(), from_bin.size());
    for (std::size_t i = 0; i < from_bin.size(); ++i) {
        EXPECT_LT((from_ply.points[i] - from_bin.points[i]).norm(), kFloatTolerance_m);
    }
}

TEST(ScenarioRunner, SameSeedGivesByteIdenticalRecordingsForAnyThreadCount) {
    const fs::path a = temp_dir("seed_a"), b = temp_dir("seed_b"), c = temp_dir("seed_c");
    run_small(a, 5);
    run_small(b, 5, 1);
    run_small(c, 6);
    const auto files_a = read_tree(a), files_b = read_tree(b), files_c = read_tree(c);
    EXPECT_GT(files_a.size(), 20u);
    EXPECT_TRUE(files_a == files_b);
    EXPECT_NE(files_a.at("lidar/000000.bin"), files_c.at("lidar/000000.bin"));
    EXPECT_NE(files_a.at("imu.csv"), files_c.at("imu.csv"));
}

TEST(ScenarioRunner, RefusesANonEmptyDirectoryAndOverwritesOnlyARecording) {
    const fs::path dir = temp_dir("nonempty");
    fs::create_directories(dir);
    std::ofstream(dir / "keep.txt") << "x";
    const Scenario s = parse_scenario(kSmallScenario, "small.yaml");
    EXPECT_THROW(run_scenario(s, dir.string()), FileError);
    EXPECT_FALSE(fs::exists(dir / "summary.json"));
    // --force never deletes a file that is not the recording's.
    EXPECT_THROW(
        run_scenario(s, dir.string(), ScenarioRunOptions{.progress = {}, .overwrite = true}),
        FileError);
    EXPECT_TRUE(fs::exists(dir / "keep.txt"));
    EXPECT_FALSE(fs::exists(dir / "summary.json"));
}

TEST(ScenarioRunner, MavTracksTheTrajectory) {
    Scenario s = parse_scenario(kSmallScenario, "small.yaml");
    s.vehicle.type = VehicleType::kMav;
    s.sensors.clear();
    s.duration_s = 5.0;
    const fs::path dir = temp_dir("mav");
    run_scenario(s, dir.string());
    const io::Recording recording = io::open_recording(dir.string());
    const auto trajectory = make_trajectory(s.vehicle.trajectory);
    // Tracking error of a first-order loop with feed-forward: well under a metre.
    constexpr double kTrackingTolerance_m = 0.5;
    for (const io::StampedPose& pose : recording.ground_truth()) {
        const Eigen::Vector3d reference = trajectory->at(pose.stamp_s).T_world_body.translation();
        EXPECT_LT((pose.T_world_body.translation() - reference).norm(), kTrackingTolerance_m);
    }
}

}  // namespace
}  // namespace scantling::sim
