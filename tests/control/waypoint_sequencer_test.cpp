// Waypoint sequencing (advance within WP_tol, events, WP_prev = start for the first) and the
// follower in the loop: on a straight leg under a constant lateral disturbance the VTP keeps
// the vehicle closer to the line than flying at the waypoint; a whole sweep mission is flown.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <scantling/control/position_controller.hpp>
#include <scantling/control/waypoint_sequencer.hpp>
#include <scantling/core/error.hpp>
#include <scantling/planning/sweep_mission.hpp>

#include "../planning/expect_error.hpp"
#include "velocity_plant.hpp"

namespace scantling::control {
namespace {

using planning::Waypoint;
using planning::WaypointPath;

constexpr double kDt = 0.05;  // s: 20 Hz set-points

WaypointPath three_waypoints() {
    return {{Waypoint{Eigen::Vector3d(1.0, 0.0, 0.0), std::nullopt, 0.2},
             Waypoint{Eigen::Vector3d(1.1, 0.0, 0.0), 0.5, 0.2},
             Waypoint{Eigen::Vector3d(5.0, 0.0, 0.0), std::nullopt, 0.5}}};
}

TEST(WaypointSequencer, AdvancesWithinToleranceAndReportsEachWaypointReached) {
    WaypointSequencer sequencer(three_waypoints(), Eigen::Vector3d(-2.0, 0.0, 0.0));
    EXPECT_EQ(sequencer.previous_world_m(), Eigen::Vector3d(-2.0, 0.0, 0.0));  // the start
    EXPECT_TRUE(sequencer.update(Eigen::Vector3d(0.7, 0.0, 0.0)).empty());     // 0.3 m away
    // 0.05 m from the first and 0.15 m from the second: both reached in one update.
    EXPECT_EQ(sequencer.update(Eigen::Vector3d(0.95, 0.0, 0.0)), (std::vector<std::size_t>{0, 1}));
    EXPECT_EQ(sequencer.current_index(), 2u);
    EXPECT_EQ(sequencer.previous_world_m(), Eigen::Vector3d(1.1, 0.0, 0.0));
    EXPECT_EQ(sequencer.update(Eigen::Vector3d(4.6, 0.1, 0.0)), (std::vector<std::size_t>{2}));
    EXPECT_TRUE(sequencer.finished());
    EXPECT_TRUE(sequencer.update(Eigen::Vector3d::Zero()).empty());
}

TEST(WaypointSequencer, TargetIsTheWaypointWithTheFollowerOffAndTheVtpWithItOn) {
    WaypointSequencer sequencer(three_waypoints(), Eigen::Vector3d(-2.0, 0.0, 0.0));
    const Eigen::Vector3d p(-1.0, 0.1, 0.0);  // on the first leg (from the start), d = λ/2
    const TrackingTarget off = sequencer.target(p, {.use_vtp = false, .vtp = {}});
    EXPECT_EQ(off.p_target_world_m, Eigen::Vector3d(1.0, 0.0, 0.0));
    EXPECT_FALSE(off.vtp.has_value());
    const TrackingTarget on = sequencer.target(p, {});
    ASSERT_TRUE(on.vtp.has_value());
    EXPECT_EQ(on.vtp->vtp_case, VtpCase::kOnPath);
    EXPECT_TRUE(on.p_target_world_m.isApprox(Eigen::Vector3d(0.0, 0.0, 0.0), 1e-12));  // L = 1
    sequencer.update(Eigen::Vector3d(0.85, 0.0, 0.0));  // the first only (0.25 m from the second)
    ASSERT_EQ(sequencer.current_index(), 1u);
    EXPECT_EQ(sequencer.target(p, {}).yaw_rad, 0.5);  // the second waypoint's heading
}

TEST(WaypointSequencer, HoldsAtTheLastWaypointOrTheStart) {
    WaypointSequencer sequencer(three_waypoints(), Eigen::Vector3d::Zero());
    sequencer.update(Eigen::Vector3d(1.0, 0.0, 0.0));
    sequencer.update(Eigen::Vector3d(5.0, 0.0, 0.0));
    ASSERT_TRUE(sequencer.finished());
    const TrackingTarget hold = sequencer.target(Eigen::Vector3d(4.0, 1.0, 0.0), {});
    EXPECT_EQ(hold.p_target_world_m, Eigen::Vector3d(5.0, 0.0, 0.0));
    EXPECT_FALSE(hold.vtp.has_value());
    WaypointSequencer empty(WaypointPath{}, Eigen::Vector3d(1.0, 2.0, 3.0));
    EXPECT_TRUE(empty.finished());
    EXPECT_EQ(empty.target(Eigen::Vector3d::Zero(), {}).p_target_world_m,
              Eigen::Vector3d(1.0, 2.0, 3.0));
}

TEST(WaypointSequencer, BadPathsAndPositionsAreRefused) {
    WaypointPath path = three_waypoints();
    path.waypoints[2].tolerance_m = 0.0;
    SCANTLING_EXPECT_ERROR(WaypointSequencer(path, Eigen::Vector3d::Zero()), ConfigError,
                           "waypoint_sequencer.path.waypoints[2].tolerance_m = 0");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    SCANTLING_EXPECT_ERROR(WaypointSequencer(three_waypoints(), Eigen::Vector3d::Constant(nan)),
                           InputError, "p_start_world_m");
    WaypointSequencer sequencer(three_waypoints(), Eigen::Vector3d::Zero());
    SCANTLING_EXPECT_ERROR(sequencer.update(Eigen::Vector3d(nan, 0.0, 0.0)), InputError,
                           "p_world_m = (nan, 0, 0)");
}

/// Deviation from the intended path while flying it on the test plant.
struct Flight {
    double max_deviation_m = 0.0;
    double mean_deviation_m = 0.0;
    std::size_t reached = 0;
    double duration_s = 0.0;
};

/// Distance from p to the polyline start → waypoints (the intended path).
double distance_to_path(const Eigen::Vector3d& p, const Eigen::Vector3d& start,
                        const WaypointPath& path) {
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector3d a = start;
    for (const Waypoint& wp : path.waypoints) {
        const Eigen::Vector3d ab = wp.p_world_m - a;
        const double t =
            ab.squaredNorm() > 0.0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
        best = std::min(best, (p - (a + t * ab)).norm());
        a = wp.p_world_m;
    }
    return best;
}

Flight fly(const WaypointPath& path, const Eigen::Vector3d& start, bool use_vtp,
           const Eigen::Vector3d& disturbance_mps, double max_time_s) {
    WaypointSequencer sequencer(path, start);
    PositionController controller;
    test::Plant3d plant{start, Eigen::Vector3d::Zero()};
    const TrackingConfig tracking{.use_vtp = use_vtp, .vtp = {}};
    Flight flight;
    double sum = 0.0;
    std::size_t samples = 0;
    for (; flight.duration_s < max_time_s && !sequencer.finished(); flight.duration_s += kDt) {
        flight.reached += sequencer.update(plant.p).size();
        const TrackingTarget target = sequencer.target(plant.p, tracking);
        const VelocityCommand command =
            controller.update(plant.p, 0.0, target.p_target_world_m, std::nullopt, kDt);
        plant.step(command.v_cmd_world_mps, kDt, disturbance_mps);
        const double deviation_m = distance_to_path(plant.p, start, path);
        flight.max_deviation_m = std::max(flight.max_deviation_m, deviation_m);
        sum += deviation_m;
        ++samples;
    }
    flight.reached += sequencer.update(plant.p).size();
    flight.mean_deviation_m = samples > 0 ? sum / static_cast<double>(samples) : 0.0;
    return flight;
}

TEST(WaypointSequencer, FollowerKeepsCloserToAStraightLegUnderALateralDisturbance) {
    // A 20 m leg along x; a constant 0.3 m/s push along +y (a third of the speed limit).
    const Eigen::Vector3d start(0.0, 0.0, 2.0);
    const WaypointPath leg{{Waypoint{Eigen::Vector3d(20.0, 0.0, 2.0), std::nullopt, 0.2}}};
    const Eigen::Vector3d push(0.0, 0.3, 0.0);
    const Flight off = fly(leg, start, false, push, 120.0);
    const Flight on = fly(leg, start, true, push, 120.0);
    ASSERT_EQ(off.reached, 1u);
    ASSERT_EQ(on.reached, 1u);
    RecordProperty("max_deviation_off_m", std::to_string(off.max_deviation_m));
    RecordProperty("max_deviation_on_m", std::to_string(on.max_deviation_m));
    std::printf(
        "follower off: max %.3f m, mean %.3f m, %.1f s; on: max %.3f m, mean %.3f m, %.1f s\n",
        off.max_deviation_m, off.mean_deviation_m, off.duration_s, on.max_deviation_m,
        on.mean_deviation_m, on.duration_s);
    // Measured (20 Hz, τ = 0.3 s): off 0.56 m max, 0.43 m mean (flying at the waypoint, the
    // push is corrected only as the line's end comes nearer); on 0.16 m, 0.03 m. With a speed
    // limit that scaled the whole command (before clamp_along_error): off 2.27 / 1.53 m, on
    // 0.27 / 0.10 m.
    constexpr double kMaxDeviationOnM = 0.2;   // ~λ + the disturbance's push over τ
    constexpr double kMaxDeviationOffM = 0.5;  // at least this far off without the follower
    EXPECT_LE(on.max_deviation_m, kMaxDeviationOnM);
    EXPECT_GE(off.max_deviation_m, kMaxDeviationOffM);
    EXPECT_LT(3.0 * on.max_deviation_m, off.max_deviation_m);  // issue 13's "3× smaller"
    EXPECT_LT(3.0 * on.mean_deviation_m, off.mean_deviation_m);
}

TEST(WaypointSequencer, FliesAWholeSweepMission) {
    const planning::WallRectangle wall{Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d::UnitX(),
                                       8.0, 5.0};
    const WaypointPath sweep = planning::plan_sweep(wall);
    const Eigen::Vector3d start(1.5, 0.0, 0.5);
    const Flight flight = fly(sweep, start, true, Eigen::Vector3d::Zero(), 300.0);
    EXPECT_EQ(flight.reached, sweep.waypoints.size());
    EXPECT_LE(flight.max_deviation_m, 0.15);  // measured 0.07 m: corners cut within WP_tol
    std::printf("sweep 8 x 5 m, calm: max %.3f m, mean %.3f m, %.1f s\n", flight.max_deviation_m,
                flight.mean_deviation_m, flight.duration_s);
}

}  // namespace
}  // namespace scantling::control
