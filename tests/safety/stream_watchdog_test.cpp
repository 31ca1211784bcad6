#include <gtest/gtest.h>

#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/safety/stream_watchdog.hpp>

namespace scantling::safety {
namespace {

TEST(StreamWatchdog, FreshStreamReportsNothing) {
    StreamWatchdog w("imu", 0.05, 0.0);
    for (int k = 0; k < 100; ++k) {
        const double t = 0.005 * k;
        w.feed(t);
        EXPECT_FALSE(w.check(t).has_value()) << t;
    }
    EXPECT_FALSE(w.lost());
}

TEST(StreamWatchdog, GapIsLostOnceThenRestoredOnce) {
    StreamWatchdog w("lidar", 0.3, 0.0);
    w.feed(0.0);
    EXPECT_FALSE(w.check(0.3).has_value());  // exactly max age: still fresh
    const auto lost = w.check(0.31);
    ASSERT_TRUE(lost.has_value());
    EXPECT_EQ(lost->change, StreamChange::kLost);
    EXPECT_NEAR(lost->age_s, 0.31, 1e-12);
    EXPECT_TRUE(w.lost());
    EXPECT_FALSE(w.check(1.0).has_value());  // reported once
    w.feed(2.0);
    const auto restored = w.check(2.05);
    ASSERT_TRUE(restored.has_value());
    EXPECT_EQ(restored->change, StreamChange::kRestored);
    EXPECT_NEAR(restored->age_s, 0.05, 1e-12);
    EXPECT_FALSE(w.lost());
}

TEST(StreamWatchdog, SensorThatNeverStartsIsLost) {
    StreamWatchdog w("uwb", 1.0, 10.0);
    EXPECT_FALSE(w.check(10.5).has_value());
    const auto lost = w.check(11.5);
    ASSERT_TRUE(lost.has_value());
    EXPECT_EQ(lost->change, StreamChange::kLost);
    EXPECT_FALSE(w.ever_fed());
}

TEST(StreamWatchdog, OldOrNonFiniteSamplesDoNotRefresh) {
    StreamWatchdog w("imu", 0.05, 0.0);
    w.feed(1.0);
    w.feed(0.5);  // out of order
    w.feed(std::nan(""));
    EXPECT_NEAR(w.age_s(1.02), 0.02, 1e-12);
    ASSERT_TRUE(w.check(1.2).has_value());
}

TEST(StreamWatchdog, RejectsImpossibleConfig) {
    EXPECT_THROW(StreamWatchdog("imu", 0.0, 0.0), ConfigError);
    EXPECT_THROW(StreamWatchdog("imu", std::nan(""), 0.0), ConfigError);
    EXPECT_THROW(StreamWatchdog("imu", 0.05, INFINITY), InputError);
    try {
        StreamWatchdog("lidar", -1.0, 0.0);
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("lidar"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace scantling::safety
