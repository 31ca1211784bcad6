// `scantling odometry`: end to end on a short simulated flight, plus bad input.
#include <fstream>
#include <regex>

#include <scantling/io/cloud_io.hpp>

#include "cli_fixture.hpp"

namespace scantling::cli_test {
namespace {

// 4 s in the ballast-tank mock-up: stiffeners, web frame and hopper give plenty of edges.
const char* const kMockupFlight = R"(world: {type: ballast_tank_mockup}
vehicle:
  type: scripted
  trajectory:
    type: waypoints
    waypoints:
      yaw_mode: face_travel
      max_speed_mps: 0.5
      waypoints:
        - {position_m: [0.8, 1.4, 0.9]}
        - {position_m: [2.2, 1.5, 1.0]}
sensors:
  - {type: spinning_lidar, preset: os1_64, columns: 1024, rate_hz: 10}
duration_s: 4.0
export: {world: false}
)";

double value_of(const std::string& out, const std::string& key) {
    const std::regex re(key + R"(: ([-0-9.eE+]+))");
    std::smatch m;
    if (!std::regex_search(out, m, re)) return -1.0;
    return std::stod(m[1]);
}

class CliOdometry : public Cli {
  protected:
    void SetUp() override {
        Cli::SetUp();
        std::ofstream(path("s.yaml")) << kMockupFlight;
    }
};

TEST_F(CliOdometry, RunsOnARecordingAndReportsDrift) {
    const CliRun sim =
        run("sim " + quoted(path("s.yaml")) + " --out " + quoted(path("rec")) + " --no-progress");
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    const CliRun r = run("odometry " + quoted(path("rec")) + " --out " + quoted(path("traj.txt")) +
                         " --preset confined");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("odometry: ["), std::string::npos) << r.err;  // the progress bar
    EXPECT_NE(r.out.find("sweeps: 40"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("status_ok:"), std::string::npos) << r.out;
    const double ate_percent = value_of(r.out, "ate_percent_of_path");
    ASSERT_GE(ate_percent, 0.0) << r.out;
    EXPECT_LT(ate_percent, 1.0) << r.out;
    const std::string trajectory = read_text(path("traj.txt"));
    EXPECT_EQ(std::count(trajectory.begin(), trajectory.end(), '\n'), 40);
    EXPECT_TRUE(fs::exists(path("traj_frames.csv")));
    EXPECT_TRUE(fs::exists(path("traj_gt.txt")));
    // TUM output by extension, and identical poses whatever the thread count.
    const CliRun tum =
        run("odometry " + quoted(path("rec")) + " --out " + quoted(path("traj.tum")) +
            " --preset confined --threads 1 --no-progress");
    ASSERT_EQ(tum.exit_code, 0) << tum.err;
    EXPECT_EQ(tum.err, "");
    EXPECT_DOUBLE_EQ(value_of(tum.out, "ate_rmse_m"), value_of(r.out, "ate_rmse_m"));
}

TEST_F(CliOdometry, UnreadableSweepIsAWarningAndTheRunGoesOn) {
    fs::create_directories(path("scans"));
    const CliRun sim =
        run("sim " + quoted(path("s.yaml")) + " --out " + quoted(path("rec")) + " --no-progress");
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    for (int i = 0; i < 12; ++i) {
        char name[32];
        std::snprintf(name, sizeof(name), "%06d", i);
        const std::string dst = path("scans/") + name + ".bin";
        if (i == 6) {
            std::ofstream(dst) << "not a point cloud";  // 17 bytes: not a multiple of 16
        } else {
            fs::copy_file(path("rec/lidar/") + name + ".bin", dst);
        }
    }
    const CliRun r = run("odometry " + quoted(path("scans")) + " --out " + quoted(path("t.txt")) +
                         " --preset confined --no-progress");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: sweep 6"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("000006.bin"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("status_unreadable: 1"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("source: " + path("scans") + " (folder)"), std::string::npos) << r.out;
}

TEST_F(CliOdometry, BadArgumentsAreOneLineAndWriteNothing) {
    expect_one_error_line(
        run("odometry " + quoted(path("none")) + " --out " + quoted(path("t.txt"))), "none");
    fs::create_directories(path("empty"));
    expect_one_error_line(
        run("odometry " + quoted(path("empty")) + " --out " + quoted(path("t.txt"))),
        "no .pcd, .ply or .bin");
    expect_one_error_line(run("odometry " + quoted(path("empty")) + " --out " +
                              quoted(path("t.txt")) + " --preset lidar9000"),
                          "lidar9000");
    expect_one_error_line(run("odometry " + quoted(path("empty")) + " --out " +
                              quoted(path("t.txt")) + " --format csv"),
                          "--format");
    EXPECT_FALSE(fs::exists(path("t.txt")));
}

TEST_F(CliOdometry, PrintConfigShowsThePreset) {
    const CliRun r = run("odometry x --print-config --preset confined");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("max_range_m: 20"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace scantling::cli_test
