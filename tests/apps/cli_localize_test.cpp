// `scantling localize`: end to end on a short simulated flight in the mock-up, plus bad input.
#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace scantling::cli_test {
namespace {

// 5 s through the first compartment of the mock-up with an L515-class camera, IMU and VIO.
const char* const kFlight = R"(world: {type: ballast_tank_mockup}
vehicle:
  type: scripted
  trajectory:
    type: waypoints
    waypoints:
      yaw_mode: face_travel
      max_speed_mps: 0.3
      waypoints:
        - {position_m: [0.6, 2.1, 0.9]}
        - {position_m: [2.0, 2.1, 0.9]}
sensors:
  - {type: depth_camera, preset: l515, width: 320, rate_hz: 10,
     T_body_sensor: {xyz: [0.05, 0.0, 0.0], rpy_deg: [-90.0, 0.0, -90.0]}}
  - {type: imu}
  - {type: vio}
duration_s: 5.0
seed: 3
export: {map_spacing_m: 0.02}
)";

class CliLocalize : public Cli {
  protected:
    void SetUp() override {
        Cli::SetUp();
        std::ofstream(path("s.yaml")) << kFlight;
        const CliRun sim = run("sim " + quoted(path("s.yaml")) + " --out " + quoted(path("rec")) +
                               " --no-progress");
        ASSERT_EQ(sim.exit_code, 0) << sim.err;
    }
};

TEST_F(CliLocalize, LocalisesAKnownAndAnUnknownStartAndWritesAllOutputs) {
    for (const std::string start : {"known", "unknown"}) {
        const std::string out = path("loc_" + start);
        const CliRun r = run("localize " + quoted(path("rec")) + " --out " + quoted(out) +
                             " --start " + start + " --filter ukf");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_NE(r.err.find("localize: ["), std::string::npos) << r.err;  // the progress bar
        EXPECT_NE(r.out.find("fused position error"), std::string::npos) << r.out;
        const auto summary = nlohmann::json::parse(read_text(fs::path(out) / "summary.json"));
        EXPECT_LT(summary["fused_error_m"]["mean"].get<double>(), 0.03) << start;
        EXPECT_GT(summary["fused_error_m"]["count"].get<int>(), 100) << start;
        EXPECT_EQ(summary["settings"]["filter"], "ukf");
        const std::string events = read_text(fs::path(out) / "events.csv");
        EXPECT_EQ(events.rfind("stamp_s,kind,index,outcome", 0), 0u);
        EXPECT_GE(std::count(events.begin(), events.end(), '\n'), 50);
        EXPECT_TRUE(fs::exists(fs::path(out) / "trajectory.tum"));
    }
    // The map descriptors were cached beside the map by the first run; the cache does not stop
    // the recording from being replaced.
    EXPECT_TRUE(fs::exists(path("rec") + "/world/map.ply.fpfh"));
    const CliRun again = run("sim " + quoted(path("s.yaml")) + " --out " + quoted(path("rec")) +
                             " --force --no-progress");
    EXPECT_EQ(again.exit_code, 0) << again.err;
}

TEST_F(CliLocalize, BadInputIsOneLineAndWritesNothing) {
    const std::string rec = quoted(path("rec"));
    expect_one_error_line(run("localize " + rec + " --out " + quoted(path("o")) + " --filter kf"),
                          "--filter");
    expect_one_error_line(run("localize " + rec + " --out " + quoted(path("o")) + " --start maybe"),
                          "--start");
    expect_one_error_line(run("localize " + rec + " --out " + quoted(path("o")) + " --vio speed"),
                          "--vio");
    expect_one_error_line(run("localize " + rec + " --out " + quoted(path("rec/out"))), "rec/out");
    std::ofstream(path("bad.json")) << "{\"name\": \"x\", \"compartments\": [{\"id\": 0}]}";
    expect_one_error_line(run("localize " + rec + " --out " + quoted(path("o")) + " --metadata " +
                              quoted(path("bad.json"))),
                          "bad.json");
    std::ofstream(path("c.yaml")) << "gates:\n  overlap:\n    min_overlap: 2\n";
    expect_one_error_line(run("localize " + rec + " --out " + quoted(path("o")) + " --config " +
                              quoted(path("c.yaml"))),
                          "min_overlap");
    // A recording without depth frames.
    fs::remove_all(path("rec/depth"));
    expect_one_error_line(run("localize " + rec + " --out " + quoted(path("o"))),
                          "no depth frames");
    expect_files({"bad.json", "c.yaml", "rec", "s.yaml"});
}

TEST_F(CliLocalize, RefusesToReplaceAFolderItDidNotWrite) {
    fs::create_directories(path("o"));
    std::ofstream(path("o/notes.txt")) << "mine";
    expect_one_error_line(run("localize " + quoted(path("rec")) + " --out " + quoted(path("o")) +
                              " --max-frames 3 --no-progress"),
                          "notes.txt");
    EXPECT_EQ(read_text(path("o/notes.txt")), "mine");
}

TEST_F(CliLocalize, PrintConfigListsEveryKey) {
    const CliRun r = run("localize " + quoted(path("rec")) + " --print-config");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* key : {"filter:", "kind: ekf", "mahalanobis_threshold",
                            "registration_period_s", "correlative:", "global_every_frame"}) {
        EXPECT_NE(r.out.find(key), std::string::npos) << key;
    }
}

// 6 s in the first compartment looking 30° up at the deck, where the world's defect 1 (a
// crack at (2.33, 2.58, 1.75)) is: the ToF and the RGB camera share the view.
const char* const kDeckSurvey = R"(world: {type: ballast_tank_mockup}
vehicle:
  type: scripted
  trajectory:
    type: waypoints
    waypoints:
      yaw_mode: face_travel
      max_speed_mps: 0.3
      waypoints:
        - {position_m: [0.6, 2.1, 0.9]}
        - {position_m: [1.6, 2.1, 0.9]}
sensors:
  - {type: depth_camera, preset: l515, width: 320, rate_hz: 10,
     T_body_sensor: {xyz: [0.05, 0.0, 0.0], rpy_deg: [-60.0, 0.0, -90.0]}}
  - {type: camera, width: 320, rate_hz: 5,
     T_body_sensor: {xyz: [0.05, 0.0, 0.03], rpy_deg: [-60.0, 0.0, -90.0]}}
  - {type: imu}
  - {type: vio}
duration_s: 6.0
seed: 3
export: {map_spacing_m: 0.02}
)";

TEST_F(Cli, LocalizeMapsTheDefectsTheCameraSees) {
    std::ofstream(path("deck.yaml")) << kDeckSurvey;
    const CliRun sim = run("sim " + quoted(path("deck.yaml")) + " --out " + quoted(path("rec")) +
                           " --no-progress");
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    const CliRun r =
        run("localize " + quoted(path("rec")) + " --out " + quoted(path("o")) + " --no-progress");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("right frame 1/1, right longitudinal 1/1"), std::string::npos) << r.out;
    const auto json = nlohmann::json::parse(read_text(path("o/defects.json")));
    ASSERT_EQ(json["defects"].size(), 1u) << json.dump(2);
    const auto& d = json["defects"][0];
    EXPECT_EQ(d["id"], 1);
    EXPECT_GT(d["views"].get<int>(), 5);
    EXPECT_LT(d["truth"]["error_m"].get<double>(), 0.05);
    EXPECT_EQ(d["location"]["compartment_name"], "compartment_1");
    EXPECT_EQ(d["location"]["frame"], 1);
    EXPECT_NEAR(d["location"]["height_above_floor_m"].get<double>(), 1.75, 0.05);
    // The covariance must cover the error (3 σ).
    EXPECT_LT(d["truth"]["error_m"].get<double>(), 3.0 * d["largest_sigma_m"].get<double>());
    const std::string csv = read_text(path("o/defects.csv"));
    EXPECT_EQ(csv.rfind("id,x,y,z,largest_sigma_m,views,compartment", 0), 0u);
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 2);
    EXPECT_TRUE(fs::exists(path("o/defects/1/crop.png")));
    EXPECT_TRUE(fs::exists(path("o/defects/1/cloud.ply")));
    // A corrupt image costs its crop, not the survey; the same folder is replaced by a second
    // run (it holds only localize's outputs).
    const int best_image = d["best_view"]["image"].get<int>();
    std::ofstream(path("rec/images/" + fmt::format("{:06d}.png", best_image))) << "not a png";
    const CliRun again =
        run("localize " + quoted(path("rec")) + " --out " + quoted(path("o")) + " --no-progress");
    ASSERT_EQ(again.exit_code, 0) << again.err;
    const auto again_json = nlohmann::json::parse(read_text(path("o/defects.json")));
    EXPECT_TRUE(again_json["defects"][0]["crop"].is_null());
    EXPECT_NE(again_json["defects"][0]["crop_error"].get<std::string>().find("PNG"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(path("o/defects/1/crop.png")));
}

}  // namespace
}  // namespace scantling::cli_test
