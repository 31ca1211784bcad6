// `scantling sim`: end to end, as a user runs it.
#include <fstream>

#include "cli_fixture.hpp"

namespace scantling::cli_test {
namespace {

class CliSim : public Cli {
  protected:
    std::string scenario(const std::string& text) const {
        std::ofstream(path("s.yaml")) << text;
        return path("s.yaml");
    }
};

TEST_F(CliSim, WritesARecordingAndPrintsASummary) {
    const CliRun r = run("sim " + quoted(scenario(kTinyScenario)) + " --out " +
                         quoted(path("rec")) + " --seed 3");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("recording: " + path("rec")), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("sweeps: 5\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("seed 3"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("simulating:"), std::string::npos) << r.err;
    for (const char* file : {"groundtruth.tum", "lidar/000004.bin", "lidar/times.txt",
                             "lidar/poses_gt.txt", "imu.csv", "world/mesh.ply", "summary.json"}) {
        EXPECT_TRUE(fs::exists(fs::path(path("rec")) / file)) << file;
    }
    // A second run into the same directory needs --force.
    const CliRun again = run("sim " + quoted(path("s.yaml")) + " --out " + quoted(path("rec")));
    expect_one_error_line(again, "--force");
    const CliRun forced = run("sim " + quoted(path("s.yaml")) + " --out " + quoted(path("rec")) +
                              " --force --no-progress");
    EXPECT_EQ(forced.exit_code, 0) << forced.err;
    EXPECT_EQ(forced.err, "");
}

TEST_F(CliSim, BadScenarioIsOneLineAndWritesNothing) {
    const CliRun r =
        run("sim " + quoted(scenario("world: {type: teapot}\n")) + " --out " + quoted(path("rec")));
    expect_one_error_line(r, "world.type");
    expect_files({"s.yaml"});
}

TEST_F(CliSim, MissingScenarioFileIsOneLine) {
    const CliRun r = run("sim " + quoted(path("none.yaml")) + " --out " + quoted(path("rec")));
    expect_one_error_line(r, "none.yaml");
    expect_files({});
}

}  // namespace
}  // namespace scantling::cli_test
