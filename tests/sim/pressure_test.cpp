#include <scantling/core/error.hpp>
#include <scantling/sim/pressure.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace scantling::sim {
namespace {

constexpr double kExact = 1e-9;

Eigen::Isometry3d at(const Eigen::Vector3d& p) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = p;
    return T;
}

PressureConfig noiseless() {
    PressureConfig c;
    c.pressure_sigma_pa = 0.0;
    return c;
}

TEST(Pressure, HydrostaticPressureGivesTheDepthBelowTheSurface) {
    PressureConfig config = noiseless();
    config.surface_z_m = 1.5;
    const PressureSensor sensor(config);
    Rng rng(1);
    const PressureSample s = sensor.measure(at({10.0, -4.0, -3.2}), rng, 7.0);
    EXPECT_EQ(s.stamp_s, 7.0);
    EXPECT_NEAR(s.pressure_pa, 101325.0 + 1025.0 * 9.81 * 4.7, kExact);
    EXPECT_NEAR(s.depth_m, 4.7, kExact);
    // In air the sensor feels the atmosphere: depth 0, while the true depth is negative.
    const PressureSample air = sensor.measure(at({0.0, 0.0, 2.0}), rng);
    EXPECT_NEAR(air.pressure_pa, 101325.0, kExact);
    EXPECT_NEAR(air.depth_m, 0.0, kExact);
    EXPECT_NEAR(sensor.true_depth_m(at({0.0, 0.0, 2.0})), -0.5, kExact);
}

TEST(Pressure, MountOffsetTurnsWithTheVehicle) {
    PressureConfig config = noiseless();
    config.T_body_sensor.translation() = Eigen::Vector3d(0.0, 0.0, -0.2);
    const PressureSensor sensor(config);
    Rng rng(2);
    Eigen::Isometry3d upside_down = at({0.0, 0.0, -2.0});
    upside_down.linear() =
        Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()).toRotationMatrix();
    EXPECT_NEAR(sensor.measure(at({0.0, 0.0, -2.0}), rng).depth_m, 2.2, kExact);
    EXPECT_NEAR(sensor.measure(upside_down, rng).depth_m, 1.8, kExact);
}

TEST(Pressure, NoiseHasTheConfiguredSigmaInDepth) {
    const PressureSensor sensor{PressureConfig{}};
    Rng rng(3);
    const int n = 5000;
    double sq = 0.0;
    for (int k = 0; k < n; ++k)
        sq += std::pow(sensor.measure(at({0, 0, -10.0}), rng).depth_m - 10.0, 2);
    const double sigma_m = 50.0 / (1025.0 * 9.81);  // ≈ 5 mm
    EXPECT_NEAR(std::sqrt(sq / n), sigma_m, 4.0 * sigma_m / std::sqrt(2.0 * n));
}

TEST(Pressure, SameSeedGivesIdenticalReadings) {
    const PressureSensor sensor{PressureConfig{}};
    Rng a(4), b(4);
    for (int k = 0; k < 20; ++k) {
        EXPECT_EQ(sensor.measure(at({0, 0, -1.0 * k}), a).depth_m,
                  sensor.measure(at({0, 0, -1.0 * k}), b).depth_m);
    }
}

TEST(Pressure, BadConfigAndInputThrow) {
    PressureConfig c;
    c.water_density_kgpm3 = 0.0;
    try {
        PressureSensor sensor(c);
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("pressure.water_density_kgpm3 = 0"),
                  std::string::npos);
    }
    c = PressureConfig{};
    c.surface_z_m = std::nan("");
    EXPECT_THROW(PressureSensor{c}, ConfigError);
    c = PressureConfig{};
    c.pressure_sigma_pa = -1.0;
    EXPECT_THROW(PressureSensor{c}, ConfigError);
    Rng rng(5);
    Eigen::Isometry3d bad = at({0, 0, 0});
    bad.translation().z() = std::nan("");
    EXPECT_THROW(PressureSensor{}.measure(bad, rng), InputError);
}

}  // namespace
}  // namespace scantling::sim
