// A recording is written whole or not at all (issue 10, item 4): the scenario runner stages it
// in a temporary folder beside --out, so a run that fails or is stopped late leaves nothing, and
// an existing recording is replaced only by a complete one, and only when it is a recording.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/sim/recording_writer.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/scenario_runner.hpp>

#include "scenario_test_support.hpp"

namespace scantling::sim {
namespace {

namespace fs = std::filesystem;
using test::read_tree;

/// 2 s with a small LiDAR and an IMU: the first sweeps are on disk long before the end.
const std::string kScenario = R"(
world: {type: cylinder}
vehicle:
  type: scripted
  trajectory: {type: helix, helix: {radius_m: 3.0, z0_m: 1.0}}
sensors:
  - {type: spinning_lidar, columns: 512, rate_hz: 10}
  - {type: imu}
duration_s: 2.0
export: {map_spacing_m: 0.3}
)";

constexpr double kLateTime_s = 1.0;  // half-way: several sweeps written already

class RecordingTransaction : public testing::Test {
  protected:
    void SetUp() override {
        const auto* info = testing::UnitTest::GetInstance()->current_test_info();
        parent_ = test::scenario_temp_dir("recording_transaction", info->name());
        fs::create_directories(parent_);
    }
    void TearDown() override { fs::remove_all(parent_); }

    /// Names in the parent folder: the recording and any temporary would show here.
    std::vector<std::string> entries() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(parent_)) {
            names.push_back(entry.path().filename().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }

    std::string rec() const { return (parent_ / "rec").string(); }

    Scenario scenario(std::uint64_t seed = 1) const {
        Scenario s = parse_scenario(kScenario, "transaction.yaml");
        s.seed = seed;
        return s;
    }

    fs::path parent_;
};

/// Thrown by the progress callback: a failure late in the run (distinct from the ConfigError
/// and FileError the runner itself may throw, which would pass the tests for a wrong reason).
struct LateFailure : std::runtime_error {
    LateFailure() : std::runtime_error("late failure") {}
};

ScenarioRunOptions failing_late(bool overwrite) {
    ScenarioRunOptions options;
    options.overwrite = overwrite;
    options.progress = [](const ScenarioProgress& p) {
        if (p.sim_time_s >= kLateTime_s) throw LateFailure();
    };
    return options;
}

TEST_F(RecordingTransaction, ARunThatFailsLateLeavesNoFolderAndNoTemporary) {
    EXPECT_THROW(run_scenario(scenario(), rec(), failing_late(false)), LateFailure);
    EXPECT_TRUE(entries().empty()) << entries().front();
}

TEST_F(RecordingTransaction, AStopRequestStopsBetweenTicksAndRemovesThePartialRecording) {
    ScenarioRunOptions options;
    double reached_s = 0.0;
    options.progress = [&](const ScenarioProgress& p) { reached_s = p.sim_time_s; };
    options.stop_requested = [&] { return reached_s >= kLateTime_s; };
    try {
        run_scenario(scenario(), rec(), options);
        FAIL() << "the run was not stopped";
    } catch (const ScenarioInterrupted& e) {
        EXPECT_NE(std::string(e.what()).find("nothing was written to " + rec()), std::string::npos)
            << e.what();
    }
    EXPECT_TRUE(entries().empty());
}

TEST_F(RecordingTransaction, AnOldRecordingIsReplacedOnlyByACompleteOne) {
    run_scenario(scenario(1), rec());
    const auto old_files = read_tree(rec());
    EXPECT_THROW(run_scenario(scenario(2), rec(), failing_late(true)), LateFailure);
    EXPECT_EQ(entries(), std::vector<std::string>{"rec"});
    EXPECT_TRUE(read_tree(rec()) == old_files) << "the failed run changed the old recording";

    run_scenario(scenario(2), rec(), ScenarioRunOptions{.progress = {}, .overwrite = true});
    EXPECT_EQ(entries(), std::vector<std::string>{"rec"});  // no temporary, no old copy left
    const auto new_files = read_tree(rec());
    EXPECT_EQ(new_files.size(), old_files.size());
    EXPECT_NE(new_files.at("lidar/000000.bin"), old_files.at("lidar/000000.bin"));
}

TEST_F(RecordingTransaction, OverwriteRefusesAFolderWithFilesThatAreNotARecording) {
    fs::create_directories(rec());
    std::ofstream(rec() + "/keep.txt") << "x";
    const auto overwrite = ScenarioRunOptions{.progress = {}, .overwrite = true};
    try {
        run_scenario(scenario(), rec(), overwrite);
        FAIL() << "a folder with a foreign file was replaced";
    } catch (const FileError& e) {
        EXPECT_EQ(e.path(), rec());
        EXPECT_NE(std::string(e.what()).find("keep.txt"), std::string::npos) << e.what();
    }
    EXPECT_EQ(entries(), std::vector<std::string>{"rec"});
    EXPECT_TRUE(fs::exists(rec() + "/keep.txt"));
    EXPECT_FALSE(fs::exists(rec() + "/summary.json"));
    EXPECT_THROW(run_scenario(scenario(), rec()), FileError);  // non-empty, no overwrite
}

TEST_F(RecordingTransaction, OnlyTheEntriesOfTheLayoutMakeARecording) {
    run_scenario(scenario(), rec());
    EXPECT_NO_THROW(check_replaceable_recording(rec()));
    // What a camera and an ROV mission write are part of a recording too (an ROV run could
    // not be replaced with --force before: images/defect_sightings.csv was "foreign").
    fs::create_directories(rec() + "/images");
    std::ofstream(rec() + "/images/defect_sightings.csv") << "x";
    std::ofstream(rec() + "/images/camera.json") << "x";
    fs::create_directories(rec() + "/mission");
    std::ofstream(rec() + "/mission/sonar_map.csv") << "x";
    EXPECT_NO_THROW(check_replaceable_recording(rec()));
    const auto expect_refused = [&](const std::string& entry) {
        try {
            check_replaceable_recording(rec());
            ADD_FAILURE() << entry << " was accepted";
        } catch (const FileError& e) {
            EXPECT_NE(std::string(e.what()).find("'" + entry + "'"), std::string::npos) << e.what();
        }
    };
    std::ofstream(rec() + "/lidar/notes.txt") << "mine";
    expect_refused("lidar/notes.txt");
    fs::remove(rec() + "/lidar/notes.txt");
    fs::create_directory(rec() + "/lidar/000099.bin");  // a folder named like a frame
    expect_refused("lidar/000099.bin");
    fs::remove(rec() + "/lidar/000099.bin");
    fs::create_directory_symlink(parent_, rec() + "/world_link");
    expect_refused("world_link");
    fs::remove(rec() + "/world_link");
    fs::remove_all(rec() + "/world");
    fs::create_directory_symlink(parent_, rec() + "/world");
    expect_refused("world");
}

TEST_F(RecordingTransaction, AWriterDestroyedWithoutCommitLeavesNothing) {
    {
        RecordingWriter writer(rec(), false);
        EXPECT_EQ(fs::path(writer.staging_directory()).parent_path(), fs::canonical(parent_));
        writer.add_imu(ImuSample{});
        writer.finish(RecordingSummary{});
        EXPECT_TRUE(fs::exists(fs::path(writer.staging_directory()) / "summary.json"));
        EXPECT_FALSE(fs::exists(rec()));
    }
    EXPECT_TRUE(entries().empty());
}

TEST_F(RecordingTransaction, ARecordingFolderNameNearNameMaxGetsAValidTemporary) {
    const std::string name(250, 'r');
    run_scenario(scenario(), (parent_ / name).string());
    EXPECT_EQ(entries(), std::vector<std::string>{name});
    EXPECT_TRUE(fs::exists(parent_ / name / "summary.json"));
}

}  // namespace
}  // namespace scantling::sim
