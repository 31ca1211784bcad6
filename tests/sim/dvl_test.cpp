#include <scantling/core/error.hpp>
#include <scantling/sim/dvl.hpp>

#include "motion_test_support.hpp"
#include "sensor_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace scantling::sim {
namespace {

using testing::add_quad;
using testing::add_surface;
using testing::plate_at_z;
using testing::TestScene;

constexpr double kExact = 1e-9;

MotionState moving(double altitude_m, double yaw_rad = 0.7) {
    MotionState m;
    m.T_world_body.linear() =
        Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    m.T_world_body.translation() = Eigen::Vector3d(0.0, 0.0, altitude_m);
    m.v_world_mps = Eigen::Vector3d(0.5, -0.2, 0.1);
    return m;
}

Eigen::Vector3d true_v_body(const MotionState& m) {
    return m.T_world_body.linear().transpose() * m.v_world_mps;
}

TEST(Dvl, BottomLockGivesTheBodyVelocityAndAltitude) {
    const TestScene scene(plate_at_z(0.0, 100.0, true));
    const Dvl dvl(noiseless(DvlConfig{}));
    Rng rng(1);
    const MotionState m = moving(5.0);
    const DvlSample s = dvl.measure(scene.view(), m, rng);
    ASSERT_TRUE(s.valid);
    EXPECT_NEAR((s.v_body_mps - true_v_body(m)).norm(), 0.0, kExact);
    EXPECT_NEAR(s.altitude_m, 5.0, kExact);
    for (const DvlBeam& beam : s.beams) {
        EXPECT_TRUE(beam.locked);
        EXPECT_NEAR(beam.range_m, 5.0 / std::cos(dvl.config().beam_angle_rad), kExact);
    }
}

TEST(Dvl, BottomLockIsLostBeyondTheMaximumAltitude) {
    const TestScene scene(plate_at_z(0.0, 100.0, true));
    const Dvl dvl(DvlConfig{});
    Rng rng(2);
    const DvlSample s = dvl.measure(scene.view(), moving(55.0), rng);  // A50: 50 m
    EXPECT_FALSE(s.valid);
    EXPECT_TRUE(s.v_body_mps.hasNaN());
    for (const DvlBeam& beam : s.beams) EXPECT_FALSE(beam.locked);
    EXPECT_TRUE(dvl.measure(scene.view(), moving(45.0), rng).valid);
}

TEST(Dvl, ThreeLockedBeamsStillSolveAndTwoDoNot) {
    // Floor with the quadrant x < 0, y < 0 cut out: with yaw 0 one beam sees nothing.
    World world;
    const int tag = add_surface(world, "floor");
    add_quad(world, {-50, 0, 0}, {50, 0, 0}, {50, 50, 0}, {-50, 50, 0}, tag);
    add_quad(world, {0, -50, 0}, {50, -50, 0}, {50, 0, 0}, {0, 0, 0}, tag);
    const TestScene scene(std::move(world));
    const Dvl dvl(noiseless(DvlConfig{}));
    Rng rng(3);
    const MotionState m = moving(4.0, 0.0);
    const DvlSample s = dvl.measure(scene.view(), m, rng);
    int locked = 0;
    for (const DvlBeam& beam : s.beams) locked += beam.locked;
    EXPECT_EQ(locked, 3);
    ASSERT_TRUE(s.valid);
    EXPECT_NEAR((s.v_body_mps - true_v_body(m)).norm(), 0.0, kExact);
    MotionState shifted = m;  // over the half plane y > 0 only: two beams
    shifted.T_world_body.translation() = Eigen::Vector3d(-10.0, 1.0, 4.0);
    EXPECT_FALSE(dvl.measure(scene.view(), shifted, rng).valid);
}

TEST(Dvl, LeverArmAddsTheRotationalVelocity) {
    const TestScene scene(plate_at_z(0.0, 100.0, true));
    DvlConfig config = noiseless(DvlConfig{});
    config.T_body_sensor.translation() = Eigen::Vector3d(0.4, 0.0, -0.1);
    const Dvl dvl(config);
    Rng rng(4);
    MotionState m = moving(3.0);
    m.omega_body_radps = Eigen::Vector3d(0.0, 0.0, 0.5);
    const DvlSample s = dvl.measure(scene.view(), m, rng);
    ASSERT_TRUE(s.valid);
    const Eigen::Vector3d expected = true_v_body(m) + Eigen::Vector3d(0.0, 0.2, 0.0);  // ω × r
    EXPECT_NEAR((s.v_body_mps - expected).norm(), 0.0, kExact);
}

TEST(Dvl, VelocityNoiseMatchesTheReportedCovariance) {
    const TestScene scene(plate_at_z(0.0, 100.0, true));
    const Dvl dvl(DvlConfig{});
    Rng rng(5);
    const MotionState m = moving(5.0);
    const int n = 4000;
    Eigen::Vector3d sq = Eigen::Vector3d::Zero();
    Eigen::Matrix3d covariance;
    for (int k = 0; k < n; ++k) {
        const DvlSample s = dvl.measure(scene.view(), m, rng);
        sq += (s.v_body_mps - true_v_body(m)).cwiseAbs2();
        covariance = s.covariance;
    }
    for (int a = 0; a < 3; ++a) {
        const double sigma = std::sqrt(covariance(a, a));
        // Weights use measured radial speeds: the covariance differs from the truth by ≪ 1 %.
        EXPECT_NEAR(std::sqrt(sq[a] / n), sigma, 4.0 * sigma / std::sqrt(2.0 * n));
    }
}

TEST(Dvl, SameSeedGivesIdenticalSamples) {
    const TestScene scene(plate_at_z(0.0, 100.0, true));
    const Dvl dvl(DvlConfig{});
    Rng a(6), b(6);
    for (int k = 0; k < 20; ++k) {
        EXPECT_EQ(dvl.measure(scene.view(), moving(5.0), a).v_body_mps,
                  dvl.measure(scene.view(), moving(5.0), b).v_body_mps);
    }
}

TEST(Dvl, BadConfigsThrowNamingTheField) {
    DvlConfig c;
    c.max_altitude_m = 0.01;
    try {
        Dvl dvl(c);
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("dvl.max_altitude_m = 0.01"), std::string::npos)
            << e.what();
    }
    c = DvlConfig{};
    c.beam_angle_rad = 0.0;
    EXPECT_THROW(Dvl{c}, ConfigError);
    c = DvlConfig{};
    c.range_sigma_m = -1.0;
    EXPECT_THROW(Dvl{c}, ConfigError);
    const TestScene scene(plate_at_z(0.0, 100.0, true));
    MotionState bad = moving(5.0);
    bad.v_world_mps.x() = std::nan("");
    Rng rng(7);
    EXPECT_THROW(Dvl{}.measure(scene.view(), bad, rng), InputError);
}

}  // namespace
}  // namespace scantling::sim
