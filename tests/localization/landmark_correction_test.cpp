// Landmark corrections (art. B) through known poses, and compartments followed through manholes.
#include <gtest/gtest.h>

#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/localization/compartment_tracker.hpp>
#include <scantling/localization/landmark_correction.hpp>

#include "../perception/bay_corner.hpp"

namespace scantling::localization {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// Bays split by web frames at x = 2 and 4 (1 cm plates), stiffeners on the bottom at
/// y = 0.6 and 1.2 (0.1 m high), manholes at (2, 1.5, 0.8) and (4, 1.5, 0.8), 0.6 × 0.8 m.
/// Landmarks on both faces of the first frame.
io::StructuralMap three_bays() {
    io::StructuralMap m;
    m.compartments = {{0, "bay_1", Aabb{{0, 0, 0}, {2, 2, 1.5}}, 0},
                      {1, "bay_2", Aabb{{2, 0, 0}, {4, 2, 1.5}}, 0},
                      {2, "bay_3", Aabb{{4, 0, 0}, {6, 2, 1.5}}, 0}};
    m.frames = {{1, {2.0, 1.0, 0.75}, Eigen::Vector3d::UnitX(), "web_frame"}};
    m.longitudinals = {{1, {0.0, 0.6, 0.1}, Eigen::Vector3d::UnitX(), "bottom"},
                       {2, {0.0, 1.2, 0.1}, Eigen::Vector3d::UnitX(), "bottom"}};
    int id = 0;
    for (const auto& [compartment, x] : {std::pair{0, 1.995}, std::pair{1, 2.005}}) {
        for (const io::FrameLine& l : m.longitudinals) {
            io::Landmark landmark;
            landmark.id = id++;
            landmark.position = {x, l.point.y(), l.point.z()};
            landmark.compartment = compartment;
            landmark.frame = 1;
            landmark.longitudinal = l.number;
            m.landmarks.push_back(landmark);
        }
    }
    io::Connection manhole;
    manhole.kind = io::ConnectionKind::Manhole;
    manhole.compartment_a = 0;
    manhole.compartment_b = 1;
    manhole.centre = {2.0, 1.5, 0.8};
    manhole.normal = Eigen::Vector3d::UnitX();
    manhole.width_m = 0.6;
    manhole.height_m = 0.8;
    m.connections = {manhole, manhole};
    m.connections[1].id = 1;
    m.connections[1].compartment_a = 1;
    m.connections[1].compartment_b = 2;
    m.connections[1].centre.x() = 4.0;
    return m;
}

Eigen::Isometry3d pose(double x, double y, double z, double yaw_deg) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, z);
    return T;
}

struct Scene {
    io::StructuralMap map = three_bays();
    Eigen::Isometry3d T_world_body = pose(0.9, 1.0, 0.9, 3.0);
    Eigen::Isometry3d T_body_sensor = pose(0.1, 0.0, -0.05, 0.0);
    PointCloud frame_sensor;

    Scene() {
        // The first bay's corner (its face of the web frame at x = 1.995), seen by the sensor.
        const PointCloud world = test_support::bay_corner(1.995, {0.6, 1.2}, 0.1, 0.003, 7);
        frame_sensor = transformed(world, (T_world_body * T_body_sensor).inverse());
    }
    AbsolutePose predicted(const Eigen::Isometry3d& error) const {
        return {10.0, error * T_world_body, Matrix6d::Identity() * 0.01};
    }
};

TEST(LandmarkCorrection, RecoversThePoseFromADriftedPrediction) {
    const Scene s;
    const Eigen::Isometry3d drift = pose(0.06, -0.04, 0.03, 2.0);
    const LandmarkCorrection c = correct_with_landmarks(
        s.frame_sensor, s.predicted(drift), s.T_body_sensor, s.map, 0, LandmarkCorrectionConfig{});
    ASSERT_TRUE(c.ok()) << c.failure << ": " << c.reason;
    EXPECT_EQ(c.matches.size(), 2u);
    const Vector6d e = position_attitude_error(s.T_world_body, c.pose.T_world_body);
    EXPECT_LT(e.head<3>().norm(), 0.01) << e.transpose();
    EXPECT_LT(std::abs(e[5]), 0.3 * kDeg) << "yaw error " << e[5] / kDeg << " deg";
    EXPECT_DOUBLE_EQ(c.pose.stamp_s, 10.0);
    // Two landmarks: 1 cm / sqrt(2) per axis at the body.
    const Matrix6d C =
        position_attitude_covariance(c.pose.covariance, c.pose.T_world_body.translation());
    EXPECT_NEAR(std::sqrt(C(0, 0)), 0.01 / std::sqrt(2.0), 1e-3);
    EXPECT_NEAR(std::sqrt(C(3, 3)), 0.5, 1e-3);  // roll about the frame normal: not observed
}

TEST(LandmarkCorrection, OnlyTheBaysInViewAndTheFaceSeenAreMatched) {
    const Scene s;
    // Claimed in bay 3, whose manhole opens onto bay 2 only: bay 1's landmarks are not admissible.
    const LandmarkCorrection far =
        correct_with_landmarks(s.frame_sensor, s.predicted(pose(0.0, 0.0, 0.0, 0.0)),
                               s.T_body_sensor, s.map, 2, LandmarkCorrectionConfig{});
    EXPECT_EQ(far.failure, "no_match");
    // In bay 2 (next door through the manhole) or unknown: matched, and always with the face
    // towards the camera (bay 1's), never bay 2's 1 cm behind it.
    for (const int compartment : {1, -1}) {
        const LandmarkCorrection c =
            correct_with_landmarks(s.frame_sensor, s.predicted(pose(0.0, 0.0, 0.0, 0.0)),
                                   s.T_body_sensor, s.map, compartment, LandmarkCorrectionConfig{});
        ASSERT_TRUE(c.ok()) << c.reason;
        for (const LandmarkMatch& m : c.matches) {
            EXPECT_EQ(s.map.landmarks[static_cast<std::size_t>(m.map_landmark)].compartment, 0);
        }
    }
}

TEST(LandmarkCorrection, APredictionOffByAStiffenerSpacingFindsNoMatch) {
    const Scene s;
    // 0.3 m across the ship: half-way between stiffeners, beyond the 0.2 m gate.
    const LandmarkCorrection c =
        correct_with_landmarks(s.frame_sensor, s.predicted(pose(0.0, 0.3, 0.0, 0.0)),
                               s.T_body_sensor, s.map, 0, LandmarkCorrectionConfig{});
    EXPECT_EQ(c.failure, "no_match") << c.reason;
}

TEST(LandmarkCorrection, AFrameWithoutLandmarksSaysSo) {
    const Scene s;
    const LandmarkCorrection c =
        correct_with_landmarks(PointCloud{}, s.predicted(Eigen::Isometry3d::Identity()),
                               s.T_body_sensor, s.map, 0, LandmarkCorrectionConfig{});
    EXPECT_EQ(c.failure, "no_landmarks");
    LandmarkCorrectionConfig bad;
    bad.association_distance_m = 0.0;
    EXPECT_THROW(correct_with_landmarks(PointCloud{}, s.predicted(Eigen::Isometry3d::Identity()),
                                        s.T_body_sensor, s.map, 0, bad),
                 ConfigError);
}

TEST(CompartmentTracker, ChangesOnlyThroughTheManhole) {
    const io::StructuralMap map = three_bays();
    CompartmentTracker tracker(&map);
    tracker.locate({1.0, 1.0, 0.8});
    EXPECT_EQ(tracker.current(), 0);
    // Through the plate beside the manhole (an estimate straying across the wall): no change.
    EXPECT_EQ(tracker.move({1.9, 0.5, 0.8}, {2.1, 0.5, 0.8}), 0);
    // Through the manhole: bay 2; and back.
    EXPECT_EQ(tracker.move({1.9, 1.5, 0.8}, {2.1, 1.55, 0.85}), 1);
    EXPECT_EQ(tracker.move({2.1, 1.5, 0.8}, {1.9, 1.5, 0.8}), 0);
    // Just outside the opening's edge, within the 0.1 m margin, still counts.
    EXPECT_EQ(tracker.move({1.95, 1.85, 0.8}, {2.05, 1.85, 0.8}), 1);
    // Unknown: located where the robot is.
    tracker.reset(-1);
    EXPECT_EQ(tracker.move({3.0, 1.0, 0.5}, {3.1, 1.0, 0.5}), 1);
    EXPECT_THROW(CompartmentTracker(&map, -0.1), ConfigError);
    CompartmentTracker none(nullptr);
    EXPECT_EQ(none.move({0, 0, 0}, {1, 1, 1}), -1);
}

}  // namespace
}  // namespace scantling::localization
