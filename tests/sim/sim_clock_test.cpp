#include <scantling/core/error.hpp>
#include <scantling/sim/sim_clock.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace scantling::sim {
namespace {

/// Firings of each schedule over [0, duration) stepping the clock by dt.
std::vector<std::int64_t> count_over(double dt_s, double duration_s,
                                     const std::vector<RateSchedule>& schedules) {
    SimClock clock(dt_s);
    for (const RateSchedule& s : schedules) clock.add(s);
    std::vector<std::int64_t> counts(schedules.size(), 0);
    const auto ticks = static_cast<std::int64_t>(std::llround(duration_s / dt_s));
    for (std::int64_t k = 0; k < ticks; ++k, clock.advance()) {
        for (std::size_t i = 0; i < schedules.size(); ++i) counts[i] += clock.fire_count(i);
    }
    return counts;
}

TEST(SimClock, SensorsFireExactlyAtTheirRatesOverTenSeconds) {
    const std::vector<RateSchedule> sensors = {{10.0, 0.0}, {200.0, 0.0}, {30.0, 0.0}};
    for (const double dt : {0.001, 0.005}) {
        const std::vector<std::int64_t> counts = count_over(dt, 10.0, sensors);
        EXPECT_EQ(counts[0], 100) << dt;
        EXPECT_EQ(counts[1], 2000) << dt;
        EXPECT_EQ(counts[2], 300) << dt;
    }
}

TEST(SimClock, NoDriftOverAnHourWithAnAwkwardStep) {
    // dt = 0.7 ms and 30 Hz share no period; Σ dt in doubles would drift by ~1e-9 s.
    const std::vector<std::int64_t> counts = count_over(0.0007, 3600.0, {{30.0, 0.0}, {7.0, 0.05}});
    EXPECT_EQ(counts[0], 108000);
    EXPECT_EQ(counts[1], 25200);
}

TEST(SimClock, PhaseDelaysTheFirstFiringAndStampsAreNominal) {
    SimClock clock(0.005, 100.0);
    const std::size_t cam = clock.add({30.0, 0.012});
    EXPECT_FALSE(clock.due(cam));  // t = 0 < phase
    EXPECT_THROW(clock.last_fire_time_s(cam), InputError);
    clock.advance();
    clock.advance();
    EXPECT_FALSE(clock.due(cam));  // 10 ms
    clock.advance();
    EXPECT_TRUE(clock.due(cam));  // 15 ms: the 12 ms firing
    EXPECT_NEAR(clock.last_fire_time_s(cam), 100.012, 1e-12);
    EXPECT_NEAR(clock.now_s(), 100.015, 1e-12);
    for (int i = 0; i < 7; ++i) clock.advance();  // 50 ms: second firing at 45.33 ms
    EXPECT_EQ(clock.total_fired(cam), 2);
    EXPECT_NEAR(clock.last_fire_time_s(cam), 100.012 + 1.0 / 30.0, 1e-12);
}

TEST(SimClock, RatesAboveTheStepFireSeveralTimesPerTick) {
    SimClock clock(0.01);
    const std::size_t imu = clock.add({400.0, 0.0});
    const std::size_t lidar = clock.add({10.0, 0.0});
    EXPECT_EQ(clock.fire_count(imu), 1);  // t = 0
    clock.advance();
    EXPECT_EQ(clock.fire_count(imu), 4);
    EXPECT_EQ(clock.due_now(), std::vector<std::size_t>{imu});
    for (int i = 0; i < 9; ++i) clock.advance();
    EXPECT_EQ(clock.due_now(), (std::vector<std::size_t>{imu, lidar}));
    EXPECT_EQ(clock.tick(), 10);
    EXPECT_DOUBLE_EQ(clock.dt_s(), 0.01);
}

TEST(SimClock, BadStepOrScheduleNamesTheField) {
    EXPECT_THROW(SimClock(0.0), ConfigError);
    SimClock clock(0.01);
    clock.add({10.0, 0.0});
    try {
        clock.add({-5.0, 0.0});
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("sim_clock.schedules[1].rate_hz"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(clock.add({10.0, -1.0}), ConfigError);
    EXPECT_THROW(clock.fire_count(5), InputError);
}

}  // namespace
}  // namespace scantling::sim
