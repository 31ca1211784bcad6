// Frame × longitudinal landmarks on synthetic depth-like clouds with known intersections.
#include <gtest/gtest.h>

#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/perception/frame_landmarks.hpp>

#include "bay_corner.hpp"

namespace scantling::perception {
namespace {

using test_support::add_rectangle;
using test_support::bay_corner;

const Eigen::Vector3d kViewpoint(0.6, 1.0, 0.9);

TEST(FrameLandmarks, FindsEveryIntersectionWithinOneCentimetre) {
    const PointCloud cloud = bay_corner(2.0, {0.6, 1.2}, 0.1, 0.003, 1);
    const FrameLandmarks found = detect_frame_landmarks(cloud, kViewpoint);
    ASSERT_EQ(found.frame_planes.size(), 1u);
    ASSERT_EQ(found.lines.size(), 2u);
    ASSERT_EQ(found.landmarks.size(), 2u);
    std::vector<Eigen::Vector3d> expected{{2.0, 0.6, 0.1}, {2.0, 1.2, 0.1}};
    for (const DetectedLandmark& l : found.landmarks) {
        double nearest = 1e9;
        for (const auto& e : expected) nearest = std::min(nearest, (l.position - e).norm());
        EXPECT_LT(nearest, 0.01) << l.position.transpose();
        // The frame's face seen from the viewpoint faces -x; the plate faces up.
        EXPECT_GT(-l.frame_normal.x(), std::cos(1.0 * M_PI / 180.0));
        EXPECT_GT(l.plate_normal.z(), std::cos(1.0 * M_PI / 180.0));
    }
}

TEST(FrameLandmarks, WorksInAFrameRotatedAFewDegrees) {
    // The cloud comes through a predicted pose: a few degrees off must not matter.
    PointCloud cloud = bay_corner(2.0, {0.6, 1.2}, 0.1, 0.003, 2);
    const Eigen::Isometry3d T(Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(3.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()));
    for (auto& p : cloud.points) p = T * p;
    const FrameLandmarks found = detect_frame_landmarks(cloud, T * kViewpoint);
    ASSERT_EQ(found.landmarks.size(), 2u);
    for (const DetectedLandmark& l : found.landmarks) {
        const Eigen::Vector3d back = T.inverse() * l.position;
        EXPECT_NEAR(back.x(), 2.0, 0.01);
        EXPECT_NEAR(back.z(), 0.1, 0.01);
        EXPECT_TRUE(std::abs(back.y() - 0.6) < 0.01 || std::abs(back.y() - 1.2) < 0.01);
    }
}

TEST(FrameLandmarks, NoFrameInViewGivesLinesButNoLandmarks) {
    PointCloud cloud = bay_corner(2.0, {0.6}, 0.1, 0.003, 3);
    // Drop the frame: only the bottom and the stiffener remain.
    PointCloud kept;
    for (const auto& p : cloud.points) {
        if (p.x() < 1.99) kept.points.push_back(p);
    }
    const FrameLandmarks found = detect_frame_landmarks(kept, kViewpoint);
    EXPECT_EQ(found.frame_planes.size(), 0u);
    EXPECT_EQ(found.lines.size(), 1u);
    EXPECT_TRUE(found.landmarks.empty());
}

TEST(FrameLandmarks, AStiffenerEndingShortOfTheFrameIsNotALandmark) {
    PointCloud cloud = bay_corner(2.0, {}, 0.1, 0.003, 4);
    Rng rng(5);
    // A stiffener ending 0.6 m before the frame (a bracket, not a frame crossing).
    add_rectangle(cloud, rng, {0.0, 0.795, 0.0}, Eigen::Vector3d::UnitX(), 1.4,
                  Eigen::Vector3d::UnitZ(), 0.1, 0.003);
    add_rectangle(cloud, rng, {0.0, 0.805, 0.0}, Eigen::Vector3d::UnitX(), 1.4,
                  Eigen::Vector3d::UnitZ(), 0.1, 0.003);
    const FrameLandmarks found = detect_frame_landmarks(cloud, kViewpoint);
    EXPECT_EQ(found.lines.size(), 1u);
    EXPECT_TRUE(found.landmarks.empty());
}

TEST(FrameLandmarks, EmptyCloudFindsNothingAndBadInputIsRefused) {
    EXPECT_TRUE(detect_frame_landmarks(PointCloud{}, kViewpoint).landmarks.empty());
    PointCloud bad = bay_corner(2.0, {0.6}, 0.1, 0.003, 6);
    bad.points[10].y() = std::nan("");
    EXPECT_THROW(detect_frame_landmarks(bad, kViewpoint), InputError);
    EXPECT_THROW(detect_frame_landmarks(PointCloud{}, Eigen::Vector3d::Constant(NAN)), InputError);
    FrameLandmarkConfig c;
    c.max_stiffener_height_m = 0.01;
    try {
        detect_frame_landmarks(PointCloud{}, kViewpoint, c);
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("landmarks.max_stiffener_height_m"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace scantling::perception
