// Recordings whose stamps and files disagree, or whose stamps go backwards or repeat, are
// refused by open_recording with an error naming the file and the line (no frame is dropped
// or read out of order without a word).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/io/kitti.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/io/tum.hpp>

namespace scantling::io {
namespace {

namespace fs = std::filesystem;

/// A valid recording with 3 LiDAR sweeps (lidar/000000.bin ... 000002.bin) and an IMU file.
class RecordingConsistency : public testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::path(testing::TempDir()) /
               ("scantling_recording_consistency_" +
                std::string(testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "lidar");
        write_tum(file("groundtruth.tum"),
                  std::vector<StampedPose>{{0.0, Eigen::Isometry3d::Identity()},
                                           {0.3, Eigen::Isometry3d::Identity()}});
        write_kitti_poses(file("lidar/poses_gt.txt"),
                          std::vector<Eigen::Isometry3d>(3, Eigen::Isometry3d::Identity()));
        write("lidar/times.txt", "0\n0.1\n0.2\n");
        for (int i = 0; i < 3; ++i) write_sweep(i, ".bin");
        write("imu.csv", "stamp_s,ax,ay,az,wx,wy,wz\n0,0,0,9.81,0,0,0\n0.005,0,0,9.81,0,0,0\n");
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string file(const std::string& name) const { return (dir_ / name).string(); }
    void write(const std::string& name, const std::string& text) const {
        std::ofstream(dir_ / name) << text;
    }
    void write_sweep(int index, const char* extension) const {
        PointCloud sweep;
        sweep.points = {Eigen::Vector3d(1.0, 0.0, 0.0)};
        sweep.intensities = {0.5f};
        write_kitti_bin(file("lidar/" + recording_layout::frame_stem(index) + extension), sweep);
    }

    /// open_recording throws a ParseError whose message holds every one of `parts`.
    void expect_refused(const std::vector<std::string>& parts) const {
        try {
            open_recording(dir_.string());
            ADD_FAILURE() << "the recording was accepted";
        } catch (const ParseError& e) {
            for (const std::string& part : parts) {
                EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
                    << "'" << part << "' not in: " << e.what();
            }
        }
    }

    fs::path dir_;
};

TEST_F(RecordingConsistency, TheValidRecordingOpens) {
    EXPECT_EQ(open_recording(dir_.string()).num_sweeps(), 3u);
}

TEST_F(RecordingConsistency, ASweepFileWithoutAStampIsRefused) {
    write_sweep(3, ".bin");  // e.g. times.txt and poses_gt.txt cut short by hand
    expect_refused({file("lidar/times.txt"), "3 stamps", "000003.bin"});
}

TEST_F(RecordingConsistency, AStampWithoutItsSweepFileIsRefusedNamingTheLine) {
    fs::remove(dir_ / "lidar/000001.bin");
    expect_refused({file("lidar/times.txt") + ": line 2:", "frame 1", "000001.bin"});
}

TEST_F(RecordingConsistency, AnEmptySweepStoredAsPlyAloneIsAFrame) {
    fs::remove(dir_ / "lidar/000002.bin");
    std::ofstream(dir_ / "lidar/000002.ply") << "";  // existence is what the check looks at
    EXPECT_EQ(open_recording(dir_.string()).num_sweeps(), 3u);
}

TEST_F(RecordingConsistency, OtherFilesInTheFolderAreNotFrames) {
    write("lidar/notes.txt", "not a frame");
    write("lidar/12.bin", "too few digits for a frame stem");
    EXPECT_EQ(open_recording(dir_.string()).num_sweeps(), 3u);
}

TEST_F(RecordingConsistency, StampsGoingBackwardsAreRefusedNamingTheLine) {
    write("lidar/times.txt", "0\n0.2\n0.1\n");
    expect_refused({file("lidar/times.txt") + ": line 3:", "not after the previous one"});
}

TEST_F(RecordingConsistency, RepeatedStampsAreRefusedNamingTheLine) {
    write("lidar/times.txt", "0\n\n0.1\n0.1\n");  // the blank line is skipped, not counted
    expect_refused({file("lidar/times.txt") + ": line 4:", "line 3"});
}

TEST_F(RecordingConsistency, ImuStampsGoingBackwardsAreRefusedNamingTheLine) {
    write("imu.csv", "stamp_s,ax,ay,az,wx,wy,wz\n0.01,0,0,9.81,0,0,0\n0.005,0,0,9.81,0,0,0\n");
    expect_refused({file("imu.csv") + ": line 3:", "0.005"});
}

TEST_F(RecordingConsistency, NonFiniteStampsInFilesThatAllowNanAreRefused) {
    write("range.csv", "stamp_s,valid,range_m\n0,1,2.5\nnan,0,nan\n");
    expect_refused({file("range.csv") + ": line 3:", "not a finite number"});
}

TEST_F(RecordingConsistency, UwbRowsOfOneRoundShareAStampButMayNotGoBack) {
    write("uwb.csv", "stamp_s,anchor_id,range_m,valid,los\n0,1,2,1,1\n0,2,3,1,1\n0.1,1,2,1,1\n");
    EXPECT_EQ(open_recording(dir_.string()).uwb().size(), 3u);
    write("uwb.csv", "stamp_s,anchor_id,range_m,valid,los\n0.1,1,2,1,1\n0,2,3,1,1\n");
    expect_refused({file("uwb.csv") + ": line 3:"});
}

TEST_F(RecordingConsistency, AnExtrinsicFileOfTwoPosesIsAParseErrorNamingIt) {
    write_kitti_poses(file("lidar/T_body_sensor.txt"),
                      std::vector<Eigen::Isometry3d>(2, Eigen::Isometry3d::Identity()));
    expect_refused({file("lidar/T_body_sensor.txt"), "expected exactly one"});
}

TEST(RecordingStamps, ReadStampsRefusesStampsThatDoNotIncrease) {
    const fs::path path =
        fs::path(testing::TempDir()) / ("scantling_stamps_" + std::to_string(::getpid()));
    std::ofstream(path) << "0.0\n0.1\n0.1\n";
    EXPECT_THROW(read_stamps(path.string()), ParseError);
    std::ofstream(path) << "0.0\n0.1\n0.2\n";
    EXPECT_EQ(read_stamps(path.string()).size(), 3u);
    fs::remove(path);
}

}  // namespace
}  // namespace scantling::io
