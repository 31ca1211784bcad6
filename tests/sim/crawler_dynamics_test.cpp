#include <scantling/core/error.hpp>
#include <scantling/sim/crawler_dynamics.hpp>

#include "vehicle_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

constexpr double kOnSurfaceM = 1e-6;  // the brief's bound; projections give ~1e-15
constexpr double kAligned = 1e-9;     // 1 − cos of the body-z / normal angle
constexpr double kPi = std::numbers::pi;

CrawlerDynamicsConfig no_slip() {
    CrawlerDynamicsConfig c;
    c.slip_mean = 0.0;
    c.slip_sigma = 0.0;
    c.lateral_slip_sigma = 0.0;
    c.yaw_slip_sigma = 0.0;
    c.velocity_time_constant_s = 0.0;
    return c;
}

/// Body-z alignment and surface distance after every step.
void drive_and_check(CrawlerDynamics& crawler, const SurfaceProjector& surface,
                     const CrawlerCommand& cmd, int steps) {
    for (int i = 0; i < steps; ++i) {
        const MotionState& m = crawler.step(cmd);
        const Eigen::Vector3d p = m.T_world_body.translation();
        const SurfacePoint s = surface.project(p);
        ASSERT_LT((s.point - p).norm(), kOnSurfaceM) << i;
        ASSERT_GT(m.T_world_body.linear().col(2).dot(s.normal), 1.0 - kAligned) << i;
    }
}

TEST(CrawlerDynamics, StaysOnATiltedPlateWithBodyZAlongItsNormal) {
    const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
    const PlaneSurface plate(Eigen::Vector3d(1, 2, 3), n);
    CrawlerDynamics crawler(CrawlerDynamicsConfig{}, plate, Eigen::Isometry3d::Identity(), 4);
    drive_and_check(crawler, plate, {0.2, 0.3}, 2000);
}

TEST(CrawlerDynamics, WithoutSlipDrivesTheUnicycleCircle) {
    const PlaneSurface floor(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
    CrawlerDynamics crawler(no_slip(), floor, Eigen::Isometry3d::Identity(), 1);
    // v / ω = 0.5 m radius; a quarter turn in π / 2 / 0.4 s ends at (0.5, 0.5).
    const int steps = static_cast<int>(std::lround(kPi / 2 / 0.4 / crawler.config().dt_s));
    for (int i = 0; i < steps; ++i) crawler.step({0.2, 0.4});
    const Eigen::Vector3d p = crawler.state().T_world_body.translation();
    EXPECT_LT((p - Eigen::Vector3d(0.5, 0.5, 0.0)).norm(), 2e-3);  // 1.5708/0.01 rounds to 393
    EXPECT_NEAR(crawler.wheel_distance_m(), 0.2 * steps * 0.01, 1e-12);
}

TEST(CrawlerDynamics, DrivesRoundAStorageTankWallAtConstantHeight) {
    const CylinderSurface tank(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 3.0);
    Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
    start.linear() << 0, 0, 1, 1, 0, 0, 0, 1, 0;  // heading +y (tangent), body z = +x (radial)
    start.translation() = Eigen::Vector3d(3.0, 0.0, 1.5);
    CrawlerDynamics crawler(no_slip(), tank, start, 2);
    drive_and_check(crawler, tank, {0.3, 0.0}, 3000);  // 9 m: half-way round
    const Eigen::Vector3d p = crawler.state().T_world_body.translation();
    EXPECT_NEAR(p.z(), 1.5, 1e-9);  // "straight" on a cylinder along a ring is a geodesic
    EXPECT_NEAR(std::atan2(p.y(), p.x()), 3.0, 1e-3);  // 9 m / 3 m radius
}

TEST(CrawlerDynamics, StaysOnAMeshCylinderWithSlip) {
    const MeshSurface tank(testing::open_cylinder(2.0, 4.0, 64, 8));
    Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
    start.linear() << 0, 0, 1, 0.6, -0.8, 0, 0.8, 0.6, 0;  // climbing diagonally
    start.translation() = Eigen::Vector3d(2.0, 0.0, 0.5);
    CrawlerDynamics crawler(CrawlerDynamicsConfig{}, tank, start, 9);
    drive_and_check(crawler, tank, {0.2, 0.05}, 800);
    EXPECT_GT(crawler.state().T_world_body.translation().z(), 1.0);
}

TEST(CrawlerDynamics, SlipMakesTheWheelsOverestimateTheDistance) {
    CrawlerDynamicsConfig c = no_slip();
    c.slip_mean = 0.1;
    const PlaneSurface floor(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
    CrawlerDynamics crawler(c, floor, Eigen::Isometry3d::Identity(), 1);
    for (int i = 0; i < 1000; ++i) crawler.step({0.2, 0.0});
    EXPECT_NEAR(crawler.wheel_distance_m(), 2.0, 1e-12);
    EXPECT_NEAR(crawler.state().T_world_body.translation().x(), 1.8, 1e-12);
}

TEST(CrawlerDynamics, SameSeedSamePathDifferentSeedDifferentSlip) {
    const PlaneSurface floor(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
    const auto final_pose = [&](std::uint64_t seed) {
        CrawlerDynamics crawler(CrawlerDynamicsConfig{}, floor, Eigen::Isometry3d::Identity(),
                                seed);
        for (int i = 0; i < 500; ++i) crawler.step({0.25, 0.1});
        return crawler.state().T_world_body;
    };
    EXPECT_EQ(final_pose(8).matrix(), final_pose(8).matrix());
    EXPECT_GT((final_pose(8).translation() - final_pose(9).translation()).norm(), 1e-4);
}

TEST(CrawlerDynamics, BadConfigNamesTheField) {
    const PlaneSurface floor(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
    CrawlerDynamicsConfig c;
    c.slip_mean = 1.5;
    try {
        CrawlerDynamics crawler(c, floor, Eigen::Isometry3d::Identity(), 1);
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("crawler.slip_mean"), std::string::npos);
    }
    c = {};
    c.max_speed_mps = 0.0;
    EXPECT_THROW(CrawlerDynamics(c, floor, Eigen::Isometry3d::Identity(), 1), ConfigError);
}

}  // namespace
}  // namespace scantling::sim
