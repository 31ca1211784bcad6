#include <scantling/core/error.hpp>
#include <scantling/sim/legged_base.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

constexpr double kOneMinusInvE = 0.6321205588285577;

LeggedBaseConfig unsaturated() {
    LeggedBaseConfig c;
    c.max_accel_mps2 = 100.0;
    return c;
}

void run(LeggedBase& base, const LeggedCommand& cmd, double seconds) {
    const auto steps = static_cast<int>(std::lround(seconds / base.config().dt_s));
    for (int i = 0; i < steps; ++i) base.step(cmd);
}

TEST(LeggedBase, VelocityStepReaches63PercentAtTheTimeConstant) {
    LeggedBase base(unsaturated(), Eigen::Isometry3d::Identity());
    run(base, {0.8, 0.0, 0.0}, 0.3);
    EXPECT_NEAR(base.state().v_world_mps.x() / 0.8, kOneMinusInvE, 1e-9);
}

TEST(LeggedBase, LateralCommandIsInTheBodyFrame) {
    const Eigen::Isometry3d start(
        Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
    LeggedBase base(unsaturated(), start);
    run(base, {0.0, 0.5, 0.0}, 5.0);  // body left = world −x when facing +y
    EXPECT_NEAR(base.state().v_world_mps.x(), -0.5, 1e-6);
    EXPECT_NEAR(base.state().v_world_mps.y(), 0.0, 1e-9);
}

TEST(LeggedBase, BouncesOnlyWhileWalkingWithinTheAmplitude) {
    LeggedBaseConfig c = unsaturated();
    c.bounce_amplitude_m = 0.02;
    Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
    start.translation().z() = 0.4;
    LeggedBase base(c, start);
    run(base, {}, 1.0);
    EXPECT_EQ(base.state().T_world_body.translation().z(), 0.4);  // standing still
    double lo = 1.0, hi = 0.0;
    for (int i = 0; i < 800; ++i) {
        const double z = base.step({c.max_speed_mps, 0.0, 0.0}).T_world_body.translation().z();
        if (i > 400) {
            lo = std::min(lo, z);
            hi = std::max(hi, z);
        }
    }
    EXPECT_LE(hi, 0.42 + 1e-12);
    EXPECT_GE(lo, 0.38 - 1e-12);
    EXPECT_GT(hi - lo, 0.035);  // full stride reached
}

TEST(LeggedBase, AccelerationLimitAndYawRate) {
    LeggedBaseConfig c;
    c.max_accel_mps2 = 0.5;
    LeggedBase base(c, Eigen::Isometry3d::Identity());
    base.step({1.0, 0.0, 0.0});
    EXPECT_NEAR(base.state().a_world_mps2.head<2>().norm(), 0.5, 1e-12);
    run(base, {0.0, 0.0, 0.4}, 3.0);
    EXPECT_NEAR(base.state().omega_body_radps.z(), 0.4, 1e-3);
    EXPECT_GT(base.yaw_rad(), 0.8);
}

TEST(LeggedBase, BadConfigNamesTheField) {
    LeggedBaseConfig c;
    c.step_frequency_hz = 0.0;
    try {
        LeggedBase base(c, Eigen::Isometry3d::Identity());
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("legged_base.step_frequency_hz"), std::string::npos);
    }
    LeggedBase base(LeggedBaseConfig{}, Eigen::Isometry3d::Identity());
    EXPECT_THROW(base.step({INFINITY, 0.0, 0.0}), InputError);
}

}  // namespace
}  // namespace scantling::sim
