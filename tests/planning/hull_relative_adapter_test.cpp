// Hull-relative adaptation of the remaining survey path (SPEC §5, issue 14 item 3): a hull met
// off its planned place, a hull turned, the low-pass over scans and its clamps, a curved hull
// followed at the stand-off, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <scantling/core/error.hpp>
#include <scantling/planning/hull_relative_adapter.hpp>

#include "expect_error.hpp"

namespace scantling::planning {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2.0;
constexpr double kExact = 1e-12;

// A slice planned along x at y = −1, facing the hull (+y) that the plan puts at y = 0.
WaypointPath slice() {
    WaypointPath path;
    for (const double x : {-8.0, 0.0, 8.0}) path.waypoints.push_back({{x, -1.0, -2.0}, kHalfPi});
    return path;
}

HullRelativeAdapterConfig unclamped(double gain = 1.0) {
    HullRelativeAdapterConfig config;
    config.gain = gain;
    config.max_shift_per_scan_m = 100.0;
    config.max_turn_per_scan_rad = 3.0;
    return config;
}

HullLineObservation hull_at_y(double y) { return {{0.0, y}, {0.0, 1.0}}; }

TEST(HullRelativeAdapter, AHullFurtherAwayMovesTheRestOfThePathToTheStandOff) {
    HullRelativeAdapter adapter(slice(), unclamped());
    const AdaptationStep step = adapter.adapt(hull_at_y(0.3), {-4.0, -1.0, -2.0}, 1);
    EXPECT_NEAR(step.stand_off_measured_m, 1.3, kExact);
    EXPECT_NEAR(step.shift_m, 0.3, kExact);
    EXPECT_NEAR(step.turn_rad, 0.0, kExact);
    EXPECT_EQ(step.waypoints_moved, 2u);
    const auto& w = adapter.path().waypoints;
    EXPECT_NEAR(w[0].p_world_m.y(), -1.0, kExact);  // behind the vehicle: untouched
    for (std::size_t i = 1; i < 3; ++i) {
        EXPECT_NEAR(w[i].p_world_m.y(), -0.7, kExact);
        EXPECT_NEAR(w[i].p_world_m.z(), -2.0, kExact);  // depth is heave's
        EXPECT_NEAR(*w[i].yaw_rad, kHalfPi, kExact);
    }
}

TEST(HullRelativeAdapter, ATurnedHullTurnsThePathAboutThePivotAndFacesIt) {
    HullRelativeAdapter adapter(slice(), unclamped());
    const double tilt = 5.0 * std::numbers::pi / 180.0;
    // The hull through (−4, 0) with its normal turned by 5°.
    const HullLineObservation turned{{-4.0, 0.0},
                                     {std::cos(kHalfPi + tilt), std::sin(kHalfPi + tilt)}};
    const AdaptationStep step = adapter.adapt(turned, {-4.0, -1.0, -2.0}, 1);
    EXPECT_NEAR(step.turn_rad, tilt, kExact);
    for (const Waypoint& w : adapter.path().waypoints) {
        if (&w == &adapter.path().waypoints[0]) continue;
        // On the line at the stand-off from the measured hull, facing it.
        const Eigen::Vector2d p = w.p_world_m.head<2>();
        EXPECT_NEAR(turned.normal_world.dot(p - turned.point_world_m), -1.0, 1e-9);
        EXPECT_NEAR(*w.yaw_rad, kHalfPi + tilt, kExact);
    }
}

TEST(HullRelativeAdapter, TheGainFiltersOverScansAndTheClampsLimitOneScan) {
    HullRelativeAdapter filtered(slice(), unclamped(0.5));
    for (int scan = 0; scan < 10; ++scan) filtered.adapt(hull_at_y(0.4), {-4, -1, -2}, 1);
    // Half the remaining error per scan: 0.4 · 0.5^10 left.
    EXPECT_NEAR(filtered.path().waypoints[2].p_world_m.y(), -0.6 - 0.4 * std::pow(0.5, 10), 1e-9);

    HullRelativeAdapter clamped(slice());  // defaults: gain 0.5, 0.2 m and 10° per scan
    const AdaptationStep step = clamped.adapt(hull_at_y(2.0), {-4, -1, -2}, 1);
    EXPECT_TRUE(step.clamped);
    EXPECT_NEAR(step.shift_m, 0.2, kExact);
    const HullLineObservation far_turn{{-4.0, 0.0},
                                       {std::cos(kHalfPi + 1.0), std::sin(kHalfPi + 1.0)}};
    EXPECT_NEAR(clamped.adapt(far_turn, {-4, -1, -2}, 1).turn_rad, 10.0 * std::numbers::pi / 180.0,
                kExact);
}

// A hull that curves away (a circle of 20 m radius touching y = 0 at x = 0, its centre on the
// hull's side): the vehicle moves 0.25 m along its adapted leg per 5 Hz scan and sees the true
// hull line each time; it keeps the stand-off within 5 cm once the filter has settled, where
// the straight slice planned at y = −1 would be 2.5 m off at its ends.
TEST(HullRelativeAdapter, FollowsACurvedHullAtTheStandOff) {
    const Eigen::Vector2d centre(0.0, 20.0);
    const double radius = 20.0;
    WaypointPath path;
    path.waypoints.push_back({{-8.0, -1.0 + 20.0 - std::sqrt(400.0 - 64.0), -2.0}, kHalfPi});
    path.waypoints.push_back({{8.0, -1.0, -2.0}, kHalfPi});
    HullRelativeAdapter adapter(path);
    Eigen::Vector3d p = path.waypoints[0].p_world_m;
    double worst_after_settling = 0.0;
    for (int scan = 0; scan < 64; ++scan) {
        const Eigen::Vector2d to_centre = centre - p.head<2>();
        const Eigen::Vector2d q = centre - radius * to_centre.normalized();  // nearest hull point
        const Eigen::Vector2d n = (q - p.head<2>()).normalized();
        const AdaptationStep step = adapter.adapt({q, n}, p, 1);
        if (scan >= 10)
            worst_after_settling =
                std::max(worst_after_settling, std::abs(step.stand_off_measured_m - 1.0));
        // Fly 0.25 m along the adapted line (through the next waypoint, along its hull).
        const Waypoint& w = adapter.path().waypoints[1];
        const Eigen::Vector2d t(-std::sin(*w.yaw_rad), std::cos(*w.yaw_rad));
        const Eigen::Vector2d b = w.p_world_m.head<2>();
        p.head<2>() = b + t * (p.head<2>() - b).dot(t) + 0.25 * t;
    }
    EXPECT_LT(worst_after_settling, 0.05);
}

TEST(HullRelativeAdapter, BadInputIsRefusedNamingIt) {
    WaypointPath no_yaw = slice();
    no_yaw.waypoints[1].yaw_rad.reset();
    SCANTLING_EXPECT_ERROR(HullRelativeAdapter{no_yaw}, ConfigError, "waypoints[1].yaw_rad");
    HullRelativeAdapterConfig bad;
    bad.gain = 0.0;
    SCANTLING_EXPECT_ERROR((HullRelativeAdapter{slice(), bad}), ConfigError, "hull_adapter.gain");
    HullRelativeAdapter adapter(slice());
    const double nan = std::nan("");
    SCANTLING_EXPECT_ERROR(adapter.adapt({{0, nan}, {0, 1}}, {0, -1, -2}, 1), InputError,
                           "observation");
    SCANTLING_EXPECT_ERROR(adapter.adapt({{0, 0}, {0, 2}}, {0, -1, -2}, 1), InputError,
                           "unit normal");
    SCANTLING_EXPECT_ERROR(adapter.adapt(hull_at_y(0), {nan, -1, -2}, 1), InputError,
                           "p_vehicle_world_m");
    EXPECT_EQ(adapter.adapt(hull_at_y(0.5), {0, -1, -2}, 3).waypoints_moved, 0u);  // finished
    SCANTLING_EXPECT_ERROR(hull_line_in_world(-1.0, 0.0, {0, 0}, 0.0), InputError, "distance");
}

TEST(HullRelativeAdapter, ASonarLineBecomesAWorldLine) {
    const HullLineObservation o = hull_line_in_world(1.5, 0.1, {1.0, 2.0}, kHalfPi);
    EXPECT_NEAR(o.normal_world.x(), std::cos(kHalfPi + 0.1), kExact);
    EXPECT_NEAR(o.normal_world.y(), std::sin(kHalfPi + 0.1), kExact);
    EXPECT_LT((o.point_world_m - (Eigen::Vector2d(1.0, 2.0) + 1.5 * o.normal_world)).norm(),
              kExact);
}

}  // namespace
}  // namespace scantling::planning
