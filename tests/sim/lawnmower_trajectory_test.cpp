#include <scantling/core/error.hpp>
#include <scantling/sim/lawnmower_trajectory.hpp>

#include "vehicle_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

namespace scantling::sim {
namespace {

constexpr double kExactM = 1e-12;
constexpr double kPi = std::numbers::pi;

/// A vertical wall along world x at y = 0, facing −y (the vehicle on the −y side): wall x =
/// world x, wall y = world z, wall z (normal) = world −y.
Eigen::Isometry3d wall_along_x() {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    T.translation() = Eigen::Vector3d(2.0, 0.0, 0.5);
    return T;
}

LawnmowerTrajectoryConfig sweep_8x5() {
    LawnmowerTrajectoryConfig c;
    c.T_world_wall = wall_along_x();
    c.width_m = 8.0;
    c.height_m = 5.0;
    c.standoff_m = 1.5;
    c.slice_spacing_m = 1.0;
    return c;
}

Eigen::Vector3d in_wall(const LawnmowerTrajectoryConfig& c, const Eigen::Vector3d& p_world) {
    return c.T_world_wall.inverse() * p_world;
}

TEST(LawnmowerTrajectory, HorizontalSlicesSweepTopToBottomAtTheStandOff) {
    const LawnmowerTrajectoryConfig c = sweep_8x5();
    const LawnmowerTrajectory sweep(c);
    EXPECT_EQ(sweep.num_slices(), 6);  // 5 m / 1 m spacing: slices at 5, 4, ..., 0
    EXPECT_NEAR(sweep.slice_step_m(), 1.0, kExactM);
    ASSERT_EQ(sweep.waypoints().size(), 12u);
    std::set<double> heights;
    for (std::size_t i = 0; i < sweep.waypoints().size(); ++i) {
        const Eigen::Vector3d q = in_wall(c, sweep.waypoints()[i].position_m);
        EXPECT_NEAR(q.z(), 1.5, kExactM);
        heights.insert(std::round(q.y() * 1e6) / 1e6);
        if (i % 2 == 1) {  // a slice spans the whole width
            const Eigen::Vector3d q0 = in_wall(c, sweep.waypoints()[i - 1].position_m);
            EXPECT_NEAR(std::abs(q.x() - q0.x()), 8.0, kExactM);
            EXPECT_NEAR(q.y(), q0.y(), kExactM);
        }
    }
    EXPECT_EQ(heights.size(), 6u);
    EXPECT_NEAR(in_wall(c, sweep.waypoints().front().position_m).y(), 5.0, kExactM);  // top
    EXPECT_NEAR(in_wall(c, sweep.waypoints().back().position_m).y(), 0.0, kExactM);
}

TEST(LawnmowerTrajectory, SpacingIsShrunkSoTheLastSliceLiesOnTheEdge) {
    LawnmowerTrajectoryConfig c = sweep_8x5();
    c.slices = SliceDirection::kVertical;
    c.slice_spacing_m = 1.3;  // SPEC §5 vertical slices at 1.3 m
    const LawnmowerTrajectory sweep(c);
    EXPECT_EQ(sweep.num_slices(), 8);  // ⌈8 / 1.3⌉ + 1
    EXPECT_NEAR(sweep.slice_step_m(), 8.0 / 7.0, kExactM);
    EXPECT_LE(sweep.slice_step_m(), 1.3);
    // Vertical slices: x constant along a slice, first one descending from the top.
    const Eigen::Vector3d a = in_wall(c, sweep.waypoints()[0].position_m);
    const Eigen::Vector3d b = in_wall(c, sweep.waypoints()[1].position_m);
    EXPECT_NEAR(a.x(), 0.0, kExactM);
    EXPECT_NEAR(b.x(), 0.0, kExactM);
    EXPECT_NEAR(a.y(), 5.0, kExactM);
    EXPECT_NEAR(b.y(), 0.0, kExactM);
    EXPECT_NEAR(in_wall(c, sweep.waypoints().back().position_m).x(), 8.0, kExactM);
}

TEST(LawnmowerTrajectory, FlightCoversTheRectangleAndStaysInsideIt) {
    const LawnmowerTrajectoryConfig c = sweep_8x5();
    const LawnmowerTrajectory sweep(c);
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
    for (int i = 0; i <= 4000; ++i) {
        const MotionState m = sweep.at(sweep.duration_s() * i / 4000.0);
        const Eigen::Vector3d q = in_wall(c, m.T_world_body.translation());
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
        EXPECT_NEAR(q.z(), 1.5, 1e-9);
    }
    EXPECT_NEAR(lo.x(), 0.0, 1e-9);
    EXPECT_NEAR(hi.x(), 8.0, 1e-9);
    EXPECT_NEAR(lo.y(), 0.0, 1e-9);
    EXPECT_NEAR(hi.y(), 5.0, 1e-9);
}

TEST(LawnmowerTrajectory, FacesTheWallAndIsDifferentiable) {
    const LawnmowerTrajectory sweep(sweep_8x5());
    const MotionState m = sweep.at(10.0);
    // The vehicle is on the −y side of the wall: facing the wall is facing +y.
    EXPECT_NEAR(m.T_world_body.linear().col(0).dot(Eigen::Vector3d::UnitY()), 1.0, 1e-12);
    testing::expect_consistent_derivatives_along(sweep, 101);
}

TEST(LawnmowerTrajectory, FootprintSpacingFollowsTheCameraGeometry) {
    // 90° FOV at 1 m: a 2 m footprint; 25 % overlap leaves 1.5 m between slices.
    EXPECT_NEAR(footprint_slice_spacing_m(kPi / 2, 1.0, 0.25), 1.5, 1e-12);
    EXPECT_THROW(footprint_slice_spacing_m(0.0, 1.0, 0.2), InputError);
    EXPECT_THROW(footprint_slice_spacing_m(1.0, 1.0, 1.0), InputError);
}

TEST(LawnmowerTrajectory, BadConfigNamesTheField) {
    LawnmowerTrajectoryConfig c = sweep_8x5();
    c.slice_spacing_m = 0.0;
    try {
        LawnmowerTrajectory sweep(c);
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("lawnmower_trajectory.slice_spacing_m"),
                  std::string::npos);
    }
    c = sweep_8x5();
    c.width_m = -1.0;
    EXPECT_THROW(LawnmowerTrajectory{c}, ConfigError);
    c = sweep_8x5();
    c.T_world_wall.linear() *= 2.0;
    EXPECT_THROW(LawnmowerTrajectory{c}, ConfigError);
}

}  // namespace
}  // namespace scantling::sim
