// The sonar hull line (perception/sonar_hull_line.hpp) on the simulator's own multibeam sonar:
// a flat hull plate at known range and angle, speckle on, through io::SonarPing as the robot
// receives it (sim::to_sonar_ping). Issue 14 item 2: angle within 2°, range within 5 cm.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <scantling/core/random.hpp>
#include <scantling/perception/sonar_hull_line.hpp>
#include <scantling/sim/multibeam_sonar.hpp>

#include "../sim/sensor_test_support.hpp"

namespace scantling::mission {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A 40 × 10 m plate whose nearest point to the sonar (at the origin, looking along +x) is at
// `range_m` on bearing `bearing_rad` (positive to the left).
sim::World plate(double range_m, double bearing_rad) {
    const Eigen::Vector3d n(std::cos(bearing_rad), std::sin(bearing_rad), 0.0);
    const Eigen::Vector3d along(-n.y(), n.x(), 0.0);
    const Eigen::Vector3d c = range_m * n;
    const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    sim::World world;
    const int tag = sim::testing::add_surface(world, "hull");
    sim::testing::add_quad(world, c - 20 * along - 5 * up, c + 20 * along - 5 * up,
                           c + 20 * along + 5 * up, c - 20 * along + 5 * up, tag);
    return world;
}

TEST(SonarHullLineOnTheSimulator, FindsAPlateAtKnownRangeAndAngle) {
    sim::MultibeamSonarConfig sonar_config;
    sonar_config.max_range_m = 5.0;  // an ROV's hull-following setting
    const sim::MultibeamSonar sonar(sonar_config);
    for (const double range_m : {1.0, 1.3, 3.0}) {
        for (const double bearing_deg : {-20.0, 0.0, 15.0}) {
            const sim::testing::TestScene scene(plate(range_m, bearing_deg * kDeg));
            Rng rng(7);
            const io::SonarPing ping = sim::to_sonar_ping(
                sonar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng, 1.5));
            EXPECT_EQ(ping.stamp_s, 1.5);
            const perception::SonarHullLine line = perception::detect_hull_line(ping);
            ASSERT_TRUE(line.ok()) << range_m << " m, " << bearing_deg << "°: " << line.message;
            EXPECT_NEAR(line.distance_m, range_m, 0.05) << bearing_deg << "°";
            EXPECT_NEAR(line.angle_rad / kDeg, bearing_deg, 2.0) << range_m << " m";
        }
    }
}

TEST(SonarHullLineOnTheSimulator, OpenWaterHasNoReturn) {
    const sim::MultibeamSonar sonar{sim::MultibeamSonarConfig{}};
    const sim::testing::TestScene scene(sim::World{});
    Rng rng(3);
    const io::SonarPing ping =
        sim::to_sonar_ping(sonar.scan(scene.view(), Eigen::Isometry3d::Identity(), rng, 0.0));
    EXPECT_EQ(perception::detect_hull_line(ping).status,
              perception::SonarHullLineStatus::kNoReturn);
}

}  // namespace
}  // namespace scantling::mission
