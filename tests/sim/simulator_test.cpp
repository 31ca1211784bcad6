// The steppable simulator of the closed loop (sim/simulator.hpp): commands move the vehicle,
// each tick returns the readings due, a motion-distorted sweep arrives once complete, and the
// same seed and commands give the same readings.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <variant>

#include <scantling/core/error.hpp>
#include <scantling/sim/mav_dynamics.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/simulator.hpp>

namespace scantling::sim {
namespace {

/// A MAV in calm air in the mock-up, with a 10 Hz sweep (DISTORTION), a 200 Hz IMU, a
/// down-looking range finder and a barometer.
const std::string kScenario = R"(
world:
  type: ballast_tank_mockup
vehicle:
  type: mav
sensors:
  - type: spinning_lidar
    columns: 512
    motion_distortion: DISTORTION
  - type: imu
    rate_hz: 200
  - type: range_finder
    rate_hz: 20
    T_body_sensor: {rpy_deg: [180.0, 0.0, 0.0]}
  - type: barometer
    rate_hz: 50
duration_s: 1.0
seed: 5
export: {world: false}
)";

Scenario scenario(bool distortion) {
    std::string yaml = kScenario;
    yaml.replace(yaml.find("DISTORTION"), 10, distortion ? "true" : "false");
    return parse_scenario(yaml, "closed_loop.yaml");
}

const Eigen::Isometry3d kStart(Eigen::Translation3d(1.0, 1.8, 1.0));

struct Counts {
    int sweeps = 0, imu = 0, ranges = 0, baro = 0;
    double last_sweep_stamp_s = -1.0, last_sweep_tick_s = -1.0;
};

void count(const SimStep& step, Counts& counts) {
    for (const SensorReading& r : step.readings) {
        if (std::holds_alternative<LidarReading>(r.data)) {
            ++counts.sweeps;
            counts.last_sweep_stamp_s = r.stamp_s;
            counts.last_sweep_tick_s = step.truth.stamp_s;
        }
        counts.imu += std::holds_alternative<ImuSample>(r.data) ? 1 : 0;
        counts.ranges += std::holds_alternative<RangeMeasurement>(r.data) ? 1 : 0;
        counts.baro += std::holds_alternative<BarometerSample>(r.data) ? 1 : 0;
    }
}

Counts fly(Simulator& sim, const VehicleCommand& command, int ticks) {
    Counts counts;
    count(sim.start(), counts);
    for (int k = 0; k < ticks; ++k) count(sim.step(command), counts);
    return counts;
}

TEST(Simulator, ReadingsComeAtTheirRates) {
    Simulator sim(scenario(false), kStart);
    const Counts counts = fly(sim, {}, 200);  // t = 0 .. 1 s inclusive
    EXPECT_NEAR(sim.now_s(), 1.0, 1e-12);
    EXPECT_EQ(counts.sweeps, 11);
    EXPECT_EQ(counts.imu, 201);
    EXPECT_EQ(counts.ranges, 21);
    EXPECT_EQ(counts.baro, 51);
    // Hovering in calm air: the vehicle stays where it started.
    EXPECT_LT((sim.truth().T_world_body.translation() - kStart.translation()).norm(), 1e-9);
}

TEST(Simulator, CommandMovesTheVehicle) {
    Simulator sim(scenario(false), kStart);
    fly(sim, {.v_world_mps = Eigen::Vector3d(0.5, 0.0, 0.0), .yaw_rate_radps = 0.0}, 400);
    // v̇ = (v_cmd − v) / τ − c v: the steady speed is v_cmd / (1 + c τ), reached with the time
    // constant τ' = τ / (1 + c τ); after 2 s the MAV moved v_ss (2 − τ' (1 − e^{−2/τ'})).
    const MavDynamicsConfig mav{};
    const double v_ss = 0.5 / (1.0 + mav.drag_coefficient_per_s * mav.velocity_time_constant_s);
    const double tau_s = mav.velocity_time_constant_s /
                         (1.0 + mav.drag_coefficient_per_s * mav.velocity_time_constant_s);
    const Eigen::Vector3d moved = sim.truth().T_world_body.translation() - kStart.translation();
    EXPECT_NEAR(moved.x(), v_ss * (2.0 - tau_s * (1.0 - std::exp(-2.0 / tau_s))), 1e-3);
    EXPECT_NEAR(moved.y(), 0.0, 1e-9);
    EXPECT_NEAR(sim.truth().v_world_mps.x(), v_ss, 1e-3);
}

TEST(Simulator, DistortedSweepArrivesWhenComplete) {
    Simulator sim(scenario(true), kStart);
    const Counts counts = fly(sim, {.v_world_mps = Eigen::Vector3d(0.3, 0.0, 0.0)}, 200);
    // Sweeps started at 0 .. 0.9 s are complete by 1 s; the one of 1.0 s is not yet.
    EXPECT_EQ(counts.sweeps, 10);
    EXPECT_NEAR(counts.last_sweep_stamp_s, 0.9, 1e-9);
    EXPECT_NEAR(counts.last_sweep_tick_s, 1.0, 1e-9);
}

TEST(Simulator, SameSeedAndCommandsGiveTheSameReadings) {
    Simulator a(scenario(false), kStart);
    Simulator b(scenario(false), kStart);
    a.start();
    b.start();
    for (int k = 0; k < 40; ++k) {
        const VehicleCommand command{.v_world_mps = Eigen::Vector3d(0.2, 0.1 * std::sin(k), 0.0),
                                     .yaw_rate_radps = 0.1};
        const SimStep sa = a.step(command);
        const SimStep sb = b.step(command);
        ASSERT_EQ(sa.readings.size(), sb.readings.size());
        for (std::size_t i = 0; i < sa.readings.size(); ++i) {
            if (const auto* imu = std::get_if<ImuSample>(&sa.readings[i].data)) {
                const auto& other = std::get<ImuSample>(sb.readings[i].data);
                EXPECT_EQ(imu->specific_force_mps2, other.specific_force_mps2);
                EXPECT_EQ(imu->angular_rate_radps, other.angular_rate_radps);
            }
        }
    }
    EXPECT_TRUE(a.truth().T_world_body.isApprox(b.truth().T_world_body, 0.0));
}

TEST(Simulator, RefusesBadUse) {
    Simulator sim(scenario(false), kStart);
    EXPECT_THROW(sim.step({}), InputError);  // before start
    sim.start();
    EXPECT_THROW(sim.start(), InputError);
    VehicleCommand nan_command;
    nan_command.v_world_mps.x() = std::nan("");
    EXPECT_THROW(sim.step(nan_command), InputError);
    Scenario scripted = scenario(false);
    scripted.vehicle.type = VehicleType::kScripted;
    EXPECT_THROW(Simulator(scripted, kStart), ConfigError);
    Eigen::Isometry3d bad = kStart;
    bad.translation().x() = std::nan("");
    EXPECT_THROW(Simulator(scenario(false), bad), InputError);
}

}  // namespace
}  // namespace scantling::sim
