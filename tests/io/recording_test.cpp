// Recording reader: layout, round trip of hand-written files, errors naming file and line.
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

class RecordingTest : public testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::path(testing::TempDir()) /
               ("scantling_recording_test_" +
                std::string(testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "lidar");
        const std::vector<StampedPose> gt{{0.0, Eigen::Isometry3d::Identity()},
                                          {0.1, Eigen::Isometry3d::Identity()}};
        write_tum((dir_ / "groundtruth.tum").string(), gt);
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.translation() = Eigen::Vector3d(1.0, 2.0, 3.0);
        const std::vector<Eigen::Isometry3d> poses{pose, pose};
        write_kitti_poses((dir_ / "lidar/poses_gt.txt").string(), poses);
        write("lidar/times.txt", "0\n0.1\n");
        PointCloud sweep;
        sweep.points = {Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Vector3d(0.0, 2.5, -1.0)};
        sweep.intensities = {0.5f, 0.25f};
        write_kitti_bin((dir_ / "lidar/000000.bin").string(), sweep);
        write_kitti_bin((dir_ / "lidar/000001.bin").string(), sweep);
        write("imu.csv", "stamp_s,ax,ay,az,wx,wy,wz\n0,0,0,9.81,0,0,0.1\n0.005,0,0,9.8,0,0,0.1\n");
    }
    void TearDown() override { fs::remove_all(dir_); }
    void write(const std::string& name, const std::string& text) {
        std::ofstream(dir_ / name) << text;
    }
    fs::path dir_;
};

TEST_F(RecordingTest, ReadsStreamsStampsAndPoses) {
    const Recording recording = open_recording(dir_.string());
    ASSERT_EQ(recording.num_sweeps(), 2u);
    EXPECT_EQ(recording.ground_truth().size(), 2u);
    const PointCloud sweep = recording.read_sweep(1);
    EXPECT_DOUBLE_EQ(sweep.stamp_s, 0.1);
    ASSERT_EQ(sweep.size(), 2u);
    EXPECT_EQ(sweep.points[1], Eigen::Vector3d(0.0, 2.5, -1.0));
    EXPECT_FLOAT_EQ(sweep.intensities[0], 0.5f);
    EXPECT_EQ(recording.sweep_pose_gt(0).translation(), Eigen::Vector3d(1.0, 2.0, 3.0));
    ASSERT_EQ(recording.imu().size(), 2u);
    EXPECT_DOUBLE_EQ(recording.imu()[1].specific_force_mps2.z(), 9.8);
    EXPECT_DOUBLE_EQ(recording.imu()[0].angular_rate_radps.z(), 0.1);
    EXPECT_EQ(recording.num_depth_frames(), 0u);
    EXPECT_TRUE(recording.vio().empty());
    EXPECT_TRUE(recording.lidar_T_body_sensor().isApprox(Eigen::Isometry3d::Identity()));
}

TEST_F(RecordingTest, OutOfRangeFramesAreInputErrors) {
    const Recording recording = open_recording(dir_.string());
    EXPECT_THROW(recording.read_sweep(2), InputError);
    EXPECT_THROW(recording.sweep_pose_gt(2), InputError);
    EXPECT_THROW(recording.image_path(0), InputError);
}

TEST_F(RecordingTest, MissingDirectoryOrGroundTruthIsAFileError) {
    EXPECT_THROW(open_recording((dir_ / "nope").string()), FileError);
    fs::remove(dir_ / "groundtruth.tum");
    EXPECT_THROW(open_recording(dir_.string()), FileError);
}

TEST_F(RecordingTest, StampAndPoseCountsMustAgree) {
    write("lidar/times.txt", "0\n0.1\n0.2\n");
    try {
        open_recording(dir_.string());
        ADD_FAILURE() << "no error";
    } catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find("2 poses"), std::string::npos) << e.what();
    }
}

TEST_F(RecordingTest, MalformedCsvNamesTheLine) {
    write("imu.csv", "stamp_s,ax,ay,az,wx,wy,wz\n0,0,0,9.81,0,0,0.1\n0.005,0,x,9.8,0,0,0.1\n");
    try {
        open_recording(dir_.string());
        ADD_FAILURE() << "no error";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.location().line, 3);
    }
    write("imu.csv", "t,ax\n");
    EXPECT_THROW(open_recording(dir_.string()), ParseError);
    write("imu.csv", "stamp_s,ax,ay,az,wx,wy,wz\n0,0,0\n");
    EXPECT_THROW(read_imu_csv((dir_ / "imu.csv").string()), ParseError);
}

TEST_F(RecordingTest, VioCsvRoundTripsPoseAndValidity) {
    write("vio.csv", std::string(recording_layout::kVioHeader) +
                         "\n0.5,1,1,2,3,0,0,0.7071067811865476,0.7071067811865476,0.1,0,0,"
                         "1e-4,1e-4,1e-4,1e-6,1e-6,1e-6\n0.6,0,1,2,3,0,0,0,1,0,0,0,0,0,0,0,0,0\n");
    const std::vector<VioRecord> vio = read_vio_csv((dir_ / "vio.csv").string());
    ASSERT_EQ(vio.size(), 2u);
    EXPECT_TRUE(vio[0].valid);
    EXPECT_FALSE(vio[1].valid);
    EXPECT_NEAR(vio[0].T_odom_body.rotation()(1, 0), 1.0, 1e-12);  // yaw 90°
    EXPECT_DOUBLE_EQ(vio[0].variances[3], 1e-6);
}

TEST(RecordingLayout, FrameStemsAreSixDigits) {
    EXPECT_EQ(recording_layout::frame_stem(0), "000000");
    EXPECT_EQ(recording_layout::frame_stem(1234), "001234");
}

}  // namespace
}  // namespace scantling::io
