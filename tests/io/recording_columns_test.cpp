// Columns added to recordings after their first version: the VIO's feature quality and the
// defects in view per image; old files without them must still read.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/recording.hpp>

namespace scantling::io {
namespace {

namespace fs = std::filesystem;

class RecordingColumnsTest : public ::testing::Test {
  protected:
    void SetUp() override {
        // Per test and process: ctest runs every test as its own process, concurrently.
        dir_ = fs::path(::testing::TempDir()) /
               ("scantling_recording_columns_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    std::string write(const std::string& name, const std::string& text) const {
        const fs::path path = dir_ / name;
        std::ofstream(path) << text;
        return path.string();
    }
    fs::path dir_;
};

const std::string kVioRow = "0.5,1,1,2,3,0,0,0,1,0.1,0,0,1e-4,1e-4,1e-4,1e-6,1e-6,1e-6";

TEST_F(RecordingColumnsTest, VioFeatureQualityIsReadWhenPresent) {
    const std::string path =
        write("vio.csv", std::string(recording_layout::kVioFeatureQualityHeader) + "\n" + kVioRow +
                             ",0.375\n");
    const std::vector<VioRecord> vio = read_vio_csv(path);
    ASSERT_EQ(vio.size(), 1u);
    ASSERT_TRUE(vio[0].feature_quality.has_value());
    EXPECT_DOUBLE_EQ(*vio[0].feature_quality, 0.375);
    EXPECT_DOUBLE_EQ(vio[0].T_odom_body.translation().z(), 3.0);
}

TEST_F(RecordingColumnsTest, VioWithoutFeatureQualityReadsAsBefore) {
    const std::string path =
        write("vio.csv", std::string(recording_layout::kVioHeader) + "\n" + kVioRow + "\n");
    const std::vector<VioRecord> vio = read_vio_csv(path);
    ASSERT_EQ(vio.size(), 1u);
    EXPECT_FALSE(vio[0].feature_quality.has_value());
    EXPECT_TRUE(vio[0].valid);
}

TEST_F(RecordingColumnsTest, VioRowsMustMatchTheirHeader) {
    // The new header with an old row, and the old header with a new row.
    EXPECT_THROW(
        read_vio_csv(write("a.csv", std::string(recording_layout::kVioFeatureQualityHeader) + "\n" +
                                        kVioRow + "\n")),
        ParseError);
    EXPECT_THROW(read_vio_csv(write(
                     "b.csv", std::string(recording_layout::kVioHeader) + "\n" + kVioRow + ",1\n")),
                 ParseError);
}

TEST_F(RecordingColumnsTest, VisibleDefectsListIdsPerImage) {
    const std::string path =
        write("defects.csv", std::string(recording_layout::kVisibleDefectsHeader) +
                                 "\n0,0,3;7;12\n1,0.5,\n2,1,4\n");
    const std::vector<std::vector<int>> rows = read_visible_defects_csv(path);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0], (std::vector<int>{3, 7, 12}));
    EXPECT_TRUE(rows[1].empty());
    EXPECT_EQ(rows[2], (std::vector<int>{4}));
}

TEST_F(RecordingColumnsTest, MalformedVisibleDefectsNameTheLine) {
    const std::string header = std::string(recording_layout::kVisibleDefectsHeader) + "\n";
    for (const std::string& body :
         {std::string("0,0,1\n2,1,4\n"),  // index skips 1
          std::string("0,0,1\n1,1,x\n"),  // not an id
          std::string("0,0,1\n1,1,2;;3\n"), std::string("0,0,1\n1,1\n")}) {
        SCOPED_TRACE(body);
        try {
            read_visible_defects_csv(write("bad.csv", header + body));
            ADD_FAILURE() << "no error";
        } catch (const ParseError& e) {
            EXPECT_EQ(e.location().line, 3);
        }
    }
    EXPECT_THROW(read_visible_defects_csv(write("bad.csv", "index,ids\n")), ParseError);
}

TEST_F(RecordingColumnsTest, DefectSightingsKeepPixelsPerImage) {
    const std::string path =
        write("sightings.csv", std::string(recording_layout::kDefectSightingsHeader) +
                                   "\n0,0,3,10.5,20.25,4\n0,0,7,1,2,0\n2,1,3,11,21,4.5\n");
    const std::vector<DefectSighting> rows = read_defect_sightings_csv(path);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[1].defect_id, 7);
    EXPECT_EQ(rows[2].image, 2u);
    EXPECT_EQ(rows[2].stamp_s, 1.0);
    EXPECT_EQ(rows[0].pixel, Eigen::Vector2d(10.5, 20.25));
    EXPECT_EQ(rows[2].radius_px, 4.5);
}

TEST_F(RecordingColumnsTest, MalformedDefectSightingsNameTheLine) {
    const std::string header = std::string(recording_layout::kDefectSightingsHeader) + "\n";
    for (const std::string& body :
         {std::string("1,0,1,2,3,4\n0,0,1,2,3,4\n"),   // image index goes back
          std::string("0,0,1,2,3,4\n0,0,-1,2,3,4\n"),  // negative id
          std::string("0,0,1,2,3,4\n0,0,1,nan,3,4\n"), std::string("0,0,1,2,3,4\n0,0,1,2,3,-1\n"),
          std::string("0,0,1,2,3,4\n0,0,1,2,3\n")}) {
        SCOPED_TRACE(body);
        try {
            read_defect_sightings_csv(write("bad.csv", header + body));
            ADD_FAILURE() << "no error";
        } catch (const ParseError& e) {
            EXPECT_EQ(e.location().line, 3);
        }
    }
}

TEST_F(RecordingColumnsTest, CameraIntrinsicsRoundTripAndRefuseImpossibleValues) {
    const PinholeIntrinsics k{
        .width = 320, .height = 240, .fx = 246.5, .fy = 259.0, .cx = 159.5, .cy = 119.5};
    const PinholeIntrinsics back =
        read_camera_intrinsics(write("camera.json", camera_intrinsics_json(k)));
    EXPECT_EQ(back.width, 320);
    EXPECT_EQ(back.height, 240);
    EXPECT_EQ(back.fx, 246.5);
    EXPECT_EQ(back.cy, 119.5);
    for (const std::string& json :
         {std::string(R"({"width": 0, "height": 2, "fx": 1, "fy": 1, "cx": 0, "cy": 0})"),
          std::string(R"({"width": 2, "height": 2, "fx": -1, "fy": 1, "cx": 0, "cy": 0})"),
          std::string(R"({"width": 2, "height": 2, "fx": 1, "fy": 1, "cx": 0})"),
          std::string(R"({"width": 2, "height": 2, "fx": 1, "fy": 1, "cx": 0, "cy": 0, "k1": 0})"),
          std::string(R"({"width": 2.5, "height": 2, "fx": 1, "fy": 1, "cx": 0, "cy": 0})")}) {
        SCOPED_TRACE(json);
        EXPECT_THROW(read_camera_intrinsics(write("bad.json", json)), ParseError);
    }
}

}  // namespace
}  // namespace scantling::io
