// What the scenario runner records besides the raw sensor data: the VIO's feature quality
// (from the scene and the lighting), the defects in view in each camera image and the depth
// camera's mount.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/scenario_runner.hpp>

namespace scantling::sim {
namespace {

namespace fs = std::filesystem;

/// 1 s over the default 5 × 2 m plate (4 defects) at height `HEIGHT`, with a down-looking
/// camera and VIO (`rpy_deg [180, 0, -90]`: optical z along −body z).
const std::string kPlateScenario = R"(
world:
  type: plate
vehicle:
  type: scripted
  trajectory:
    type: waypoints
    waypoints:
      max_speed_mps: 1.0
      max_accel_mps2: 2.0
      waypoints:
        - {position_m: [-0.25, 0.0, HEIGHT]}
        - {position_m: [0.25, 0.0, HEIGHT]}
sensors:
  - type: camera
    width: 64
    rate_hz: 4
    T_body_sensor: {rpy_deg: [180.0, 0.0, -90.0]}
  - type: vio
    ambient_light: LIGHT
    T_body_sensor: {rpy_deg: [180.0, 0.0, -90.0]}
duration_s: 1.0
seed: 3
export: {map_spacing_m: 0.1}
)";

Scenario plate_scenario(const std::string& height_m, const std::string& light) {
    std::string yaml = kPlateScenario;
    for (std::size_t at = yaml.find("HEIGHT"); at != std::string::npos; at = yaml.find("HEIGHT"))
        yaml.replace(at, 6, height_m);
    yaml.replace(yaml.find("LIGHT"), 5, light);
    return parse_scenario(yaml, "plate.yaml");
}

/// 1 s through the mock-up with a depth camera mounted off-centre and turned on every axis (so
/// that a transposed or inverted mount cannot pass).
const std::string kDepthScenario = R"(
world:
  type: ballast_tank_mockup
vehicle:
  type: scripted
  trajectory:
    type: waypoints
    waypoints:
      yaw_mode: face_travel
      max_speed_mps: 0.3
      waypoints:
        - {position_m: [0.6, 2.1, 0.9]}
        - {position_m: [1.6, 1.5, 1.1]}
sensors:
  - type: depth_camera
    preset: l515
    width: 320
    rate_hz: 10
    T_body_sensor: {xyz: [0.05, 0.02, -0.03], rpy_deg: [-100.0, 5.0, -80.0]}
duration_s: 1.0
seed: 3
export: {world: false}
)";

// Poses are written as shortest round-trip doubles (KITTI) and quaternions (TUM): composing
// them agrees to rounding; 1e-9 leaves room and still catches any wrong frame.
constexpr double kPoseTolerance = 1e-9;

double max_difference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

io::Recording run(const Scenario& scenario, const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) /
                         ("scantling_scenario_outputs_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    run_scenario(scenario, dir.string());
    return io::open_recording(dir.string());
}

/// Ids of the defects in world/metadata.json, and of those among them on the plate's top face
/// (normal +z); the others are on its underside.
struct DefectIds {
    std::set<int> all;
    std::set<int> top;
};

DefectIds metadata_defect_ids(const io::Recording& recording) {
    std::ifstream in(recording.world_metadata_path());
    const nlohmann::json metadata = nlohmann::json::parse(in);
    DefectIds ids;
    for (const auto& defect : metadata.at("defects")) {
        const int id = defect.at("id").get<int>();
        ids.all.insert(id);
        if (defect.at("normal").at(2).get<double>() > 0.5) ids.top.insert(id);
    }
    return ids;
}

TEST(ScenarioOutputs, VioOverALitTexturedPlateHasFullFeatureQuality) {
    const io::Recording recording = run(plate_scenario("0.5", "1.0"), "vio_lit");
    ASSERT_EQ(recording.vio().size(), 30u);
    for (const io::VioRecord& sample : recording.vio()) {
        ASSERT_TRUE(sample.feature_quality.has_value());
        EXPECT_DOUBLE_EQ(*sample.feature_quality, 1.0);
    }
}

TEST(ScenarioOutputs, VioInTheDarkLosesTracking) {
    const io::Recording recording = run(plate_scenario("0.5", "0.0"), "vio_dark");
    ASSERT_EQ(recording.vio().size(), 30u);
    for (const io::VioRecord& sample : recording.vio()) {
        EXPECT_DOUBLE_EQ(sample.feature_quality.value_or(-1.0), 0.0);
        EXPECT_FALSE(sample.valid);
    }
}

TEST(ScenarioOutputs, AmbientLightOutsideTheUnitIntervalIsRejectedWithItsKey) {
    EXPECT_THROW(plate_scenario("0.5", "1.5"), ParseError);
    Scenario scenario = plate_scenario("0.5", "1.0");
    scenario.sensors[1].ambient_light = -0.1;
    EXPECT_THROW(scenario.validate(), ConfigError);
    EXPECT_THROW(parse_scenario("sensors:\n  - type: imu\n    ambient_light: 0.5\n"), ParseError);
}

TEST(ScenarioOutputs, ImagesListTheDefectsInViewAndNotThoseOnTheFarSide) {
    // From 5 m the camera (66° × 49.5°) sees the whole 5 × 2 m plate from above: every defect
    // on the top face is in view, none on the underside (seed 3 puts one there).
    const io::Recording recording = run(plate_scenario("5.0", "1.0"), "defects");
    const DefectIds ids = metadata_defect_ids(recording);
    ASSERT_EQ(ids.all.size(), 4u);
    ASSERT_FALSE(ids.top.empty());
    ASSERT_LT(ids.top.size(), ids.all.size());
    ASSERT_EQ(recording.num_images(), 4u);
    ASSERT_EQ(recording.image_visible_defects().size(), recording.num_images());
    for (const std::vector<int>& in_view : recording.image_visible_defects()) {
        EXPECT_EQ(std::set<int>(in_view.begin(), in_view.end()), ids.top);
        EXPECT_TRUE(std::is_sorted(in_view.begin(), in_view.end()));
    }
}

TEST(ScenarioOutputs, RecordingsWithoutTheDefectFileStillOpen) {
    const fs::path dir = fs::path(::testing::TempDir()) /
                         ("scantling_scenario_outputs_compat_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    run_scenario(plate_scenario("0.5", "1.0"), dir.string());
    const fs::path csv = dir / "images" / "visible_defects.csv";
    ASSERT_TRUE(fs::exists(csv));
    std::ofstream(csv, std::ios::app) << "4,1,0\n";  // one row more than there are images
    EXPECT_THROW(io::open_recording(dir.string()), ParseError);
    fs::remove(csv);
    const io::Recording recording = io::open_recording(dir.string());
    EXPECT_EQ(recording.num_images(), 4u);
    EXPECT_TRUE(recording.image_visible_defects().empty());
}

TEST(ScenarioOutputs, SightingsCarryTheCameraModelAndMustMatchTheirImages) {
    const Scenario scenario = plate_scenario("5.0", "1.0");
    const fs::path dir = fs::path(::testing::TempDir()) /
                         ("scantling_scenario_outputs_sightings_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    run_scenario(scenario, dir.string());
    const io::Recording recording = io::open_recording(dir.string());
    ASSERT_TRUE(recording.image_intrinsics().has_value());
    ASSERT_TRUE(recording.image_T_body_sensor().has_value());
    EXPECT_EQ(recording.image_intrinsics()->width, 64);  // the scenario's camera
    // One sighting per id in view, with its image's index and stamp, inside the image.
    std::size_t in_view = 0;
    for (const std::vector<int>& ids : recording.image_visible_defects()) in_view += ids.size();
    ASSERT_EQ(recording.defect_sightings().size(), in_view);
    for (const io::DefectSighting& s : recording.defect_sightings()) {
        EXPECT_EQ(s.stamp_s, recording.images().stamps_s[s.image]);
        EXPECT_TRUE(recording.image_intrinsics()->contains(s.pixel));
        EXPECT_GT(s.radius_px, 0.0);
    }
    // A sighting of an image that does not exist is refused, naming the file.
    std::ofstream(dir / "images" / "defect_sightings.csv", std::ios::app) << "99,9.9,0,1,1,1\n";
    try {
        io::open_recording(dir.string());
        ADD_FAILURE() << "no error";
    } catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find("defect_sightings.csv"), std::string::npos);
    }
    fs::remove_all(dir);
}

TEST(ScenarioOutputs, DepthFramesComeWithTheCameraMount) {
    const Scenario scenario = parse_scenario(kDepthScenario, "depth.yaml");
    const io::Recording recording = run(scenario, "depth_mount");
    ASSERT_EQ(recording.num_depth_frames(), 10u);
    ASSERT_TRUE(recording.depth_T_body_sensor().has_value());
    const Eigen::Isometry3d& T_body_sensor = *recording.depth_T_body_sensor();
    EXPECT_LT(max_difference(T_body_sensor, scenario.sensors[0].T_body_sensor.to_isometry()),
              kPoseTolerance);
    // T_world_body at a frame's stamp (ground truth) times the mount is the frame's pose.
    for (const std::size_t i : {std::size_t{3}, std::size_t{9}}) {
        const double stamp_s = recording.depth_frames().stamps_s[i];
        const auto& truth = recording.ground_truth();
        const auto at = std::find_if(truth.begin(), truth.end(), [&](const io::StampedPose& p) {
            return std::abs(p.stamp_s - stamp_s) < 1e-9;
        });
        ASSERT_NE(at, truth.end()) << "no ground truth at " << stamp_s;
        EXPECT_LT(
            max_difference(at->T_world_body * T_body_sensor, recording.depth_frames().poses_gt[i]),
            kPoseTolerance)
            << "frame " << i;
    }
}

TEST(ScenarioOutputs, RecordingsWithoutTheDepthMountStillOpen) {
    const fs::path dir = fs::path(::testing::TempDir()) /
                         ("scantling_scenario_outputs_no_mount_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    run_scenario(parse_scenario(kDepthScenario, "depth.yaml"), dir.string());
    ASSERT_TRUE(fs::remove(dir / "depth" / "T_body_sensor.txt"));  // as older recordings
    const io::Recording recording = io::open_recording(dir.string());
    EXPECT_EQ(recording.num_depth_frames(), 10u);
    EXPECT_FALSE(recording.depth_T_body_sensor().has_value());
    fs::remove_all(dir);
}

}  // namespace
}  // namespace scantling::sim
