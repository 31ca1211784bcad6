// The ROV's stack as a plain object (mission/rov_stack.hpp), without the simulator: what it does
// with pings that show no hull, operator commands, a silent IMU and a bad config.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/mission/rov_stack.hpp>

#include "../planning/expect_error.hpp"

namespace scantling::mission {
namespace {

constexpr double kImuPeriodS = 0.005;

planning::WaypointPath straight_slice() {
    planning::WaypointPath path;
    path.waypoints.push_back({.p_world_m = {1.0, -1.0, -1.0}, .yaw_rad = M_PI / 2.0});
    path.waypoints.push_back({.p_world_m = {5.0, -1.0, -1.0}, .yaw_rad = M_PI / 2.0});
    return path;
}

perception::InspectionRectangle hull_plane() {
    return {.corner_world = {0.0, 0.0, -2.0},
            .u_world = Eigen::Vector3d::UnitX(),
            .v_world = Eigen::Vector3d::UnitZ(),
            .width_m = 6.0,
            .height_m = 2.0};
}

RovStack make_stack(RovStackConfig config = {}) {
    const Eigen::Isometry3d start(Eigen::Translation3d(1.0, -1.2, -1.0) *
                                  Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitZ()));
    return RovStack(config, straight_slice(), hull_plane(), start);
}

/// A level vehicle at rest: gravity only.
io::ImuRecord still_imu(double t_s) {
    return {t_s, Eigen::Vector3d(0.0, 0.0, 9.81), Eigen::Vector3d::Zero()};
}

/// A ping of 64 beams and 128 bins over 5 m that saw nothing.
io::SonarPing empty_ping(double t_s) {
    io::SonarPing ping;
    ping.stamp_s = t_s;
    ping.num_beams = 64;
    ping.num_bins = 128;
    ping.intensity.assign(64 * 128, 0.0F);
    for (int b = 0; b < 64; ++b) ping.bearings_rad.push_back(-1.1 + 2.2 * b / 63.0);
    for (int i = 0; i < 128; ++i) ping.ranges_m.push_back(0.1 + (i + 0.5) * 4.9 / 128.0);
    ping.min_range_m = 0.1;
    ping.max_range_m = 5.0;
    ping.horizontal_fov_rad = 2.2;
    return ping;
}

std::vector<std::string> types(const RovStackCommand& c) {
    std::vector<std::string> out;
    for (const StackEvent& e : c.events) out.push_back(e.type);
    return out;
}

bool has(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

TEST(RovStack, PingsWithoutAHullAreOneEventPerEpisodeAndLeaveThePathAlone) {
    RovStack stack = make_stack();
    const control::OperatorCommand start{control::OperatorCommandType::kStart};
    stack.add_imu(still_imu(0.0));
    stack.command(0.0, std::span(&start, 1));
    const planning::WaypointPath before = stack.path();
    std::vector<std::string> events;
    for (int k = 1; k <= 3; ++k) {
        stack.add_imu(still_imu(k * kImuPeriodS));
        const auto line = stack.add_sonar(empty_ping(k * kImuPeriodS));
        ASSERT_TRUE(line.has_value());
        EXPECT_EQ(line->status, perception::SonarHullLineStatus::kNoReturn);
        for (const std::string& t : types(stack.command(k * kImuPeriodS, {}))) events.push_back(t);
    }
    EXPECT_EQ(std::count(events.begin(), events.end(), "hull_line_lost"), 1);
    EXPECT_TRUE(stack.path().waypoints[1].p_world_m.isApprox(before.waypoints[1].p_world_m));
    EXPECT_EQ(stack.counters().pings, 3u);
    EXPECT_EQ(stack.counters().hull_lines, 0u);
}

TEST(RovStack, AMalformedPingIsDroppedAsAnInputRejection) {
    RovStack stack = make_stack();
    stack.add_imu(still_imu(0.0));
    io::SonarPing ping = empty_ping(0.0);
    ping.intensity.pop_back();  // sizes disagree
    EXPECT_FALSE(stack.add_sonar(ping).has_value());
    EXPECT_EQ(stack.counters().inputs_rejected, 1u);
    EXPECT_TRUE(has(types(stack.command(0.0, {})), "input_rejected"));
}

TEST(RovStack, OperatorCommandsMoveTheStatesAndUnsupportedOnesAreRefused) {
    RovStack stack = make_stack();
    using Type = control::OperatorCommandType;
    const auto send = [&](Type type, double t_s) {
        stack.add_imu(still_imu(t_s));
        const control::OperatorCommand c{type};
        return stack.command(t_s, std::span(&c, 1));
    };
    EXPECT_EQ(send(Type::kStart, 0.0).state, control::MissionState::kRunning);
    EXPECT_EQ(send(Type::kPause, 0.005).state, control::MissionState::kPaused);
    EXPECT_TRUE(has(types(send(Type::kTakeOver, 0.010)), "command_refused"));
    EXPECT_EQ(send(Type::kResume, 0.015).state, control::MissionState::kRunning);
    EXPECT_EQ(send(Type::kAbort, 0.020).state, control::MissionState::kAborted);
    EXPECT_EQ(send(Type::kResume, 0.025).state, control::MissionState::kAborted);
}

TEST(RovStack, ASilentImuStopsTheVehicle) {
    RovStack stack = make_stack();
    const control::OperatorCommand start{control::OperatorCommandType::kStart};
    stack.add_imu(still_imu(0.0));
    stack.command(0.0, std::span(&start, 1));
    stack.add_imu(still_imu(0.005));
    EXPECT_TRUE(stack.estimate_valid(0.005));
    const RovStackCommand silent = stack.command(0.2, {});  // 195 ms without a sample
    EXPECT_TRUE(has(types(silent), "estimate_invalid"));
    EXPECT_EQ(silent.v_world_mps.norm(), 0.0);
    EXPECT_EQ(silent.yaw_rate_radps, 0.0);
}

TEST(RovStack, ABadConfigIsRefusedNamingTheField) {
    RovStackConfig config;
    config.survey_speed_mps = 0.0;
    SCANTLING_EXPECT_ERROR(make_stack(config), ConfigError, "stack.survey_speed_mps");
    config = {};
    config.max_waypoint_z_m = -5.0;  // an inverted range
    config.min_waypoint_z_m = -1.0;
    SCANTLING_EXPECT_ERROR(make_stack(config), ConfigError, "stack.min_waypoint_z_m");
    config = {};
    config.hull_line.min_inliers = 1;
    SCANTLING_EXPECT_ERROR(make_stack(config), ConfigError, "stack.hull_line.min_inliers");
}

}  // namespace
}  // namespace scantling::mission
