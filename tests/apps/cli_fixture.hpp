#pragma once
// Shared by the CLI tests: runs the `scantling` binary as a user would (through the shell,
// stdout and stderr captured to files) in a fresh directory per test.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <scantling/core/point_cloud.hpp>

namespace scantling::cli_test {

namespace fs = std::filesystem;

/// Half a second of a small LiDAR and an IMU in the cylinder: the quickest full recording.
inline constexpr const char* kTinyScenario = R"(world: {type: cylinder}
vehicle:
  type: scripted
  trajectory: {type: helix, helix: {radius_m: 3.0, z0_m: 1.0}}
sensors:
  - {type: spinning_lidar, columns: 512, rate_hz: 10}
  - {type: imu}
duration_s: 0.5
export: {map_spacing_m: 0.2}
)";

struct CliRun {
    int exit_code = -1;
    std::string out;
    std::string err;
};

inline std::string read_text(const fs::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

inline std::string quoted(const std::string& text) { return "'" + text + "'"; }

/// A 10 × 5 × 2 grid with spacing 0.1 m, normals and intensities.
inline scantling::PointCloud make_grid() {
    scantling::PointCloud cloud;
    for (int i = 0; i < 10; ++i) {
        for (int j = 0; j < 5; ++j) {
            for (int k = 0; k < 2; ++k) {
                cloud.points.emplace_back(0.1 * i, 0.1 * j, 0.1 * k);
                cloud.normals.emplace_back(0.0, 0.0, 1.0);
                cloud.intensities.push_back(static_cast<float>(i + j + k));
            }
        }
    }
    return cloud;
}

class Cli : public testing::Test {
  protected:
    void SetUp() override {
        const auto* info = testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::path(testing::TempDir()) / ("scantling_cli_test_" + std::to_string(::getpid())) /
               info->name();
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_.parent_path()); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    CliRun run(const std::string& args) const {
        const fs::path out = dir_.parent_path() / "stdout.txt";
        const fs::path err = dir_.parent_path() / "stderr.txt";
        const std::string command = quoted(SCANTLING_CLI) + " " + args + " > " +
                                    quoted(out.string()) + " 2> " + quoted(err.string());
        const int status = std::system(command.c_str());
        CliRun result;
        result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        result.out = read_text(out);
        result.err = read_text(err);
        return result;
    }

    /// The contract for every failure: exit 2, one "scantling: error:" line naming `subject`.
    void expect_one_error_line(const CliRun& result, const std::string& subject) const {
        EXPECT_EQ(result.exit_code, 2);
        EXPECT_EQ(result.err.rfind("scantling: error: ", 0), 0u) << result.err;
        EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
        EXPECT_NE(result.err.find(subject), std::string::npos) << result.err;
        EXPECT_EQ(result.out, "");
    }

    /// Only `expected` files in the test directory: no output and no temporary left behind.
    void expect_files(std::vector<std::string> expected) const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir_)) {
            names.push_back(entry.path().filename().string());
        }
        std::sort(names.begin(), names.end());
        std::sort(expected.begin(), expected.end());
        EXPECT_EQ(names, expected);
    }

    fs::path dir_;
};

}  // namespace scantling::cli_test
