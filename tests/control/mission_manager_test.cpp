// The mission manager flying a short sweep on the velocity plant: completion, pause and resume,
// take-over and hand back, go home, abort, an invalid estimate entering the failsafe, and
// refused commands reported as events (never thrown).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <scantling/control/mission_manager.hpp>
#include <scantling/core/error.hpp>
#include <scantling/planning/sweep_mission.hpp>

#include "../planning/expect_error.hpp"
#include "velocity_plant.hpp"

namespace scantling::control {
namespace {

using Type = OperatorCommandType;
using State = MissionState;

constexpr double kDt = 0.05;  // s: 20 Hz set-points
const Eigen::Vector3d kHome(1.5, -0.5, 2.5);

/// 4 × 2 m rectangle on the wall x = 0, 1.5 m stand-off: 3 lines, 6 waypoints at x = 1.5,
/// y ∈ {0, 4}, z ∈ {3, 2, 1}; the first leg runs along +y at z = 3.
planning::WaypointPath short_sweep() {
    const planning::WallRectangle wall{Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d::UnitX(),
                                       4.0, 2.0};
    return planning::plan_sweep(wall);
}

OperatorCommand command(Type type, const Eigen::Vector3d& v = Eigen::Vector3d::Zero()) {
    return {type, v, 0.0};
}

/// The manager in the loop with the plant; every command it outputs is checked finite.
class Flight {
  public:
    explicit Flight(const MissionManagerConfig& config = {}) : manager(short_sweep(), config) {}

    EstimatedState estimate() const { return {plant.p, yaw_rad, plant.v, true}; }

    MissionTick step(std::vector<OperatorCommand> commands = {}) {
        return step_with(estimate(), std::move(commands));
    }

    MissionTick step_with(const EstimatedState& estimate, std::vector<OperatorCommand> commands) {
        t_s += kDt;
        MissionTick tick = manager.update(estimate, t_s, commands);
        EXPECT_TRUE(tick.v_cmd_world_mps.allFinite() && std::isfinite(tick.yaw_rate_cmd_radps));
        max_speed_cmd_mps = std::max(max_speed_cmd_mps, tick.v_cmd_world_mps.norm());
        plant.step(tick.v_cmd_world_mps, kDt, Eigen::Vector3d::Zero());
        yaw_rad += tick.yaw_rate_cmd_radps * kDt;
        events.insert(events.end(), tick.events.begin(), tick.events.end());
        return tick;
    }

    /// Steps until `done` (true) or `max_s` more seconds (false).
    bool run_until(const std::function<bool()>& done, double max_s) {
        for (const double t_end = t_s + max_s; t_s < t_end;) {
            step();
            if (done()) return true;
        }
        return false;
    }
    bool run_until_state(State state, double max_s) {
        return run_until([&] { return manager.state() == state; }, max_s);
    }
    void run_for(double duration_s) {
        run_until([] { return false; }, duration_s);
    }

    std::vector<std::size_t> waypoints_reached(bool home_leg = false) const {
        std::vector<std::size_t> indices;
        for (const MissionEvent& e : events) {
            if (e.type == MissionEventType::kWaypointReached && e.home_leg == home_leg) {
                indices.push_back(*e.waypoint_index);
            }
        }
        return indices;
    }
    std::size_t count(MissionEventType type) const {
        return static_cast<std::size_t>(std::count_if(
            events.begin(), events.end(), [&](const MissionEvent& e) { return e.type == type; }));
    }

    MissionManager manager;
    test::Plant3d plant{kHome, Eigen::Vector3d::Zero()};
    double yaw_rad = 0.0;
    double t_s = 0.0;
    double max_speed_cmd_mps = 0.0;
    std::vector<MissionEvent> events;
};

const std::vector<std::size_t> kAllSix = {0, 1, 2, 3, 4, 5};

/// Started and 1.5 s into the first leg (0 → 4 m along y at z = 3): at cruise speed.
Flight flying_mid_leg(const MissionManagerConfig& config = {}) {
    Flight flight(config);
    flight.step();  // the first tick has no time step
    flight.step({command(Type::kStart)});
    EXPECT_EQ(flight.manager.state(), State::kRunning);
    EXPECT_TRUE(flight.run_until([&] { return flight.manager.current_waypoint() == 1; }, 20.0));
    flight.run_for(1.5);
    EXPECT_GT(flight.plant.v.norm(), 0.8);  // cruising along the leg
    return flight;
}

TEST(MissionManager, FliesTheSweepReachingEveryWaypointInOrder) {
    Flight flight;
    flight.step();
    const MissionTick started = flight.step({command(Type::kStart)});
    ASSERT_EQ(started.events.size(), 1u);
    EXPECT_EQ(started.events[0].to, State::kRunning);
    EXPECT_EQ(flight.manager.home_world_m(), kHome);
    ASSERT_TRUE(flight.run_until_state(State::kCompleted, 60.0));
    EXPECT_EQ(flight.waypoints_reached(), kAllSix);
    flight.run_for(3.0);  // holds at the last waypoint
    const Eigen::Vector3d last(1.5, 4.0, 1.0);
    std::printf("sweep completed at t = %.1f s, %.3f m from the last waypoint 3 s later\n",
                flight.t_s - 3.0, (flight.plant.p - last).norm());
    EXPECT_LT((flight.plant.p - last).norm(), 0.05);  // m: a steady hold, no wind
    EXPECT_LE(flight.max_speed_cmd_mps, 1.0 + 1e-9);  // the controller's clamp
}

TEST(MissionManager, PauseHoversInPlaceAndResumeCompletesTheMission) {
    Flight flight = flying_mid_leg();
    const Eigen::Vector3d p_pause = flight.plant.p;
    flight.step({command(Type::kPause)});
    EXPECT_EQ(flight.manager.state(), State::kPaused);
    double max_drift_m = 0.0;
    flight.run_until(
        [&] {
            max_drift_m = std::max(max_drift_m, (flight.plant.p - p_pause).norm());
            return false;
        },
        5.0);
    std::printf(
        "pause at 1 m/s: overshoot %.3f m, %.3f m from the pause point after 5 s, "
        "|v| = %.4f m/s\n",
        max_drift_m, (flight.plant.p - p_pause).norm(), flight.plant.v.norm());
    // At ~1 m/s the velocity lag alone coasts τ · v = 0.3 m; the hold pulls it back.
    EXPECT_LT(max_drift_m, 0.40);
    EXPECT_LT((flight.plant.p - p_pause).norm(), 0.05);
    EXPECT_LT(flight.plant.v.norm(), 0.05);
    EXPECT_EQ(flight.manager.current_waypoint(), 1u);  // still the same waypoint
    flight.step({command(Type::kResume)});
    EXPECT_EQ(flight.manager.state(), State::kRunning);
    ASSERT_TRUE(flight.run_until_state(State::kCompleted, 60.0));
    EXPECT_EQ(flight.waypoints_reached(), kAllSix);
}

/// Distance from p to the line through a and b.
double cross_track_m(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const Eigen::Vector3d u = (b - a).normalized();
    const Eigen::Vector3d d = p - a;
    return (d - d.dot(u) * u).norm();
}

TEST(MissionManager, TakeOverPassesTheOperatorVelocityAndHandBackRegainsThePath) {
    Flight flight = flying_mid_leg();
    const Eigen::Vector3d v_operator(0.3, 0.0, -0.4);  // away from the wall and down, 0.5 m/s
    const Eigen::Vector3d p_take_over = flight.plant.p;
    flight.step({command(Type::kTakeOver, v_operator)});
    EXPECT_EQ(flight.manager.state(), State::kOperator);
    flight.run_for(3.0);
    EXPECT_LT((flight.plant.v - v_operator).norm(), 1e-3);  // m/s: e^(−3 s / τ) of the change
    const Eigen::Vector3d moved = flight.plant.p - p_take_over;
    std::printf("take-over: moved (%.3f, %.3f, %.3f) m in 3 s, |v - v_op| = %.2e m/s\n", moved.x(),
                moved.y(), moved.z(), (flight.plant.v - v_operator).norm());
    EXPECT_NEAR(moved.x(), 0.3 * 3.0, 0.1);  // plus the lag's 0.3 · τ = 0.09 m short
    EXPECT_NEAR(moved.z(), -0.4 * 3.0, 0.15);
    // Clamped: the operator's 3 m/s is flown at the controller's 1 m/s.
    EXPECT_NEAR(flight.step({command(Type::kTakeOver, Eigen::Vector3d(3.0, 0.0, 0.0))})
                    .v_cmd_world_mps.norm(),
                1.0, 1e-12);
    flight.step({command(Type::kTakeOver, v_operator)});

    flight.step({command(Type::kHandBack)});
    EXPECT_EQ(flight.manager.state(), State::kRunning);
    const Eigen::Vector3d wp0(1.5, 0.0, 3.0);
    const Eigen::Vector3d wp1(1.5, 4.0, 3.0);
    const double off_path_m = cross_track_m(flight.plant.p, wp0, wp1);
    // The VTP segment still runs from waypoint 0: the vehicle returns to the line first.
    ASSERT_TRUE(
        flight.run_until([&] { return cross_track_m(flight.plant.p, wp0, wp1) < 0.2; }, 10.0));
    const double along_m = (flight.plant.p - wp0).dot((wp1 - wp0).normalized());
    std::printf(
        "hand back %.2f m off the path: back within 0.2 m of it at %.2f m along the "
        "4 m leg\n",
        off_path_m, along_m);
    EXPECT_GT(off_path_m, 1.0);
    EXPECT_LT(along_m, 3.8);  // before waypoint 1: the path was regained, not cut
    ASSERT_TRUE(flight.run_until_state(State::kCompleted, 60.0));
    EXPECT_EQ(flight.waypoints_reached(), kAllSix);
}

TEST(MissionManager, GoHomeEndsWithinToleranceOfHome) {
    Flight flight = flying_mid_leg();
    flight.step({command(Type::kGoHome)});
    EXPECT_EQ(flight.manager.state(), State::kGoingHome);
    ASSERT_TRUE(flight.run_until_state(State::kCompleted, 30.0));
    EXPECT_EQ(flight.waypoints_reached(true), (std::vector<std::size_t>{0}));
    EXPECT_EQ(flight.waypoints_reached(), (std::vector<std::size_t>{0}));  // the mission's
    EXPECT_LE((flight.plant.p - kHome).norm(), 0.20);                      // WP_tol
    flight.run_for(3.0);
    std::printf("go home: %.3f m from home 3 s after arriving\n", (flight.plant.p - kHome).norm());
    EXPECT_LT((flight.plant.p - kHome).norm(), 0.05);
}

TEST(MissionManager, GoHomeFliesToTheHeightOffsetAboveHome) {
    Flight flight = flying_mid_leg({.home_height_offset_m = 0.5});
    flight.step({command(Type::kGoHome)});
    ASSERT_TRUE(flight.run_until_state(State::kCompleted, 30.0));
    flight.run_for(3.0);
    EXPECT_LT((flight.plant.p - (kHome + Eigen::Vector3d(0.0, 0.0, 0.5))).norm(), 0.05);
}

TEST(MissionManager, AbortHoversWhereItAbortedAndRefusesToContinue) {
    Flight flight = flying_mid_leg();
    const Eigen::Vector3d p_abort = flight.plant.p;
    flight.step({command(Type::kAbort)});
    EXPECT_EQ(flight.manager.state(), State::kAborted);
    flight.run_for(5.0);
    EXPECT_LT((flight.plant.p - p_abort).norm(), 0.05);
    const MissionTick tick =
        flight.step({command(Type::kResume), command(Type::kPause), command(Type::kAbort)});
    ASSERT_EQ(tick.events.size(), 3u);
    for (const MissionEvent& e : tick.events) EXPECT_EQ(e.type, MissionEventType::kCommandRefused);
    EXPECT_EQ(tick.events[2].reason, "already stopped (aborted)");
    EXPECT_EQ(flight.manager.state(), State::kAborted);
}

TEST(MissionManager, AHoldableInvalidEstimateHoldsWhereItFailedThroughTheFailsafe) {
    Flight flight = flying_mid_leg();
    EstimatedState uncertain = flight.estimate();
    uncertain.valid = false;  // the world position's σ grew, the IMU still runs
    uncertain.holdable = true;
    const Eigen::Vector3d p_fail = uncertain.p_world_m;
    MissionTick tick = flight.step_with(uncertain, {});
    EXPECT_EQ(tick.events[0].type, MissionEventType::kEstimateInvalid);
    // Pushed 0.3 m off the point (a gust), the hold pulls back towards it, in the failsafe too.
    uncertain.p_world_m = p_fail + Eigen::Vector3d(0.3, 0.0, 0.0);
    for (int i = 0; i < 200; ++i) tick = flight.step_with(uncertain, {});
    EXPECT_EQ(flight.manager.state(), State::kFailsafe);
    EXPECT_LT(tick.v_cmd_world_mps.x(), -0.1);
    EXPECT_NEAR(tick.v_cmd_world_mps.y(), 0.0, 1e-9);
    // Not holdable (the IMU is gone): zero velocity.
    uncertain.holdable = false;
    tick = flight.step_with(uncertain, {});
    EXPECT_EQ(tick.v_cmd_world_mps, Eigen::Vector3d::Zero());
}

TEST(MissionManager, NanEstimateHoversThenEntersTheFailsafeWithoutANanCommand) {
    Flight flight = flying_mid_leg();  // estimate_timeout_s = 0.5
    EstimatedState lost = flight.estimate();
    lost.p_world_m.y() = std::numeric_limits<double>::quiet_NaN();
    const double t_lost_s = flight.t_s + kDt;
    MissionTick tick = flight.step_with(lost, {});
    ASSERT_EQ(tick.events.size(), 1u);
    EXPECT_EQ(tick.events[0].type, MissionEventType::kEstimateInvalid);
    EXPECT_EQ(tick.v_cmd_world_mps, Eigen::Vector3d::Zero());  // hover at once
    EXPECT_EQ(flight.manager.state(), State::kRunning);        // within the timeout
    while (flight.manager.state() == State::kRunning && flight.t_s < t_lost_s + 2.0) {
        tick = flight.step_with(lost, {});
        EXPECT_EQ(tick.v_cmd_world_mps, Eigen::Vector3d::Zero());
    }
    EXPECT_EQ(flight.manager.state(), State::kFailsafe);
    EXPECT_GE(flight.t_s - t_lost_s, 0.5 - 1e-9);  // s: the timeout, to one tick
    EXPECT_LE(flight.t_s - t_lost_s, 0.5 + kDt + 1e-9);
    ASSERT_EQ(tick.events.size(), 1u);
    EXPECT_EQ(tick.events[0].to, State::kFailsafe);
    EXPECT_NE(tick.events[0].reason.find("estimate non-finite for 0."), std::string::npos);
    EXPECT_NE(tick.events[0].reason.find("(timeout 0.50 s)"), std::string::npos);
    // A recovered estimate does not end the failsafe: still zero, and only the operator flies.
    tick = flight.step({command(Type::kResume), command(Type::kGoHome)});
    EXPECT_EQ(tick.v_cmd_world_mps, Eigen::Vector3d::Zero());
    EXPECT_EQ(flight.count(MissionEventType::kCommandRefused), 2u);
    tick = flight.step({command(Type::kTakeOver, Eigen::Vector3d(0.2, 0.0, 0.0))});
    EXPECT_EQ(tick.state, State::kOperator);
    EXPECT_EQ(tick.v_cmd_world_mps, Eigen::Vector3d(0.2, 0.0, 0.0));
    EXPECT_EQ(flight.step({command(Type::kHandBack)}).state, State::kFailsafe);
}

TEST(MissionManager, AnEstimateMarkedInvalidBrieflyIsRiddenOut) {
    Flight flight = flying_mid_leg();
    EstimatedState invalid = flight.estimate();
    invalid.valid = false;
    for (int i = 0; i < 5; ++i) flight.step_with(invalid, {});  // 0.25 s < 0.5 s
    EXPECT_EQ(flight.manager.state(), State::kRunning);
    EXPECT_EQ(flight.count(MissionEventType::kEstimateInvalid), 1u);
    ASSERT_TRUE(flight.run_until_state(State::kCompleted, 60.0));
    EXPECT_EQ(flight.waypoints_reached(), kAllSix);
}

TEST(MissionManager, CommandsThatDoNotApplyAreRefusedWithAReason) {
    Flight flight;
    flight.step();
    const MissionTick idle = flight.step({command(Type::kPause), command(Type::kResume),
                                          command(Type::kHandBack), command(Type::kGoHome)});
    ASSERT_EQ(idle.events.size(), 4u);
    EXPECT_EQ(idle.events[0].reason, "nothing to pause in idle");
    EXPECT_EQ(idle.events[1].reason, "not paused (idle)");
    EXPECT_EQ(idle.events[2].reason, "not taken over (idle)");
    EXPECT_EQ(idle.events[3].reason, "cannot go home from idle");
    EXPECT_EQ(idle.events[3].command, Type::kGoHome);
    EXPECT_EQ(idle.state, State::kIdle);
    EXPECT_EQ(idle.v_cmd_world_mps, Eigen::Vector3d::Zero());
    const MissionTick running =
        flight.step({command(Type::kStart), command(Type::kStart), command(Type::kResume),
                     command(Type::kTakeOver, Eigen::Vector3d(0.0, std::nan(""), 0.0))});
    ASSERT_EQ(running.events.size(), 4u);
    EXPECT_EQ(running.events[0].type, MissionEventType::kStateChanged);
    EXPECT_EQ(running.events[1].reason, "already started (running)");
    EXPECT_EQ(running.events[2].reason, "not paused (running)");
    EXPECT_EQ(running.events[3].reason, "the operator's velocity is not finite");
    EXPECT_EQ(running.state, State::kRunning);
}

TEST(MissionManager, StartNeedsAValidEstimateAndTimeMustIncrease) {
    Flight flight;
    EstimatedState invalid = flight.estimate();
    invalid.valid = false;
    const MissionTick tick = flight.step_with(invalid, {command(Type::kStart)});
    ASSERT_EQ(tick.events.size(), 2u);
    EXPECT_EQ(tick.events[1].reason, "no valid estimate yet");
    EXPECT_EQ(tick.state, State::kIdle);
    SCANTLING_EXPECT_ERROR(flight.manager.update(flight.estimate(), flight.t_s), InputError,
                           "expected finite and > the previous tick's");
    SCANTLING_EXPECT_ERROR(MissionManager(short_sweep(), {.estimate_timeout_s = -1.0}), ConfigError,
                           "mission_manager.estimate_timeout_s = -1");
    planning::WaypointPath bad = short_sweep();
    bad.waypoints[2].tolerance_m = 0.0;
    SCANTLING_EXPECT_ERROR(MissionManager{bad}, ConfigError,
                           "mission_manager.path.waypoints[2].tolerance_m");
}

TEST(MissionManager, AnEmptyMissionCompletesAtOnceAndCanStillGoHome) {
    MissionManager manager(planning::WaypointPath{});
    const EstimatedState here{kHome, 0.0, Eigen::Vector3d::Zero(), true};
    manager.update(here, 0.0);
    const std::vector<OperatorCommand> start = {command(Type::kStart)};
    EXPECT_EQ(manager.update(here, 0.05, start).state, State::kCompleted);
    const std::vector<OperatorCommand> home = {command(Type::kGoHome)};
    EXPECT_EQ(manager.update(here, 0.1, home).state, State::kCompleted);  // already home
}

}  // namespace
}  // namespace scantling::control
