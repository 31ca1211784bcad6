#include <scantling/core/error.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/world_builders.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "world_test_support.hpp"

namespace scantling::sim {
namespace {

constexpr double kExactTol_m = 1e-9;
constexpr double kOnSurfaceTol_m = 1e-6;
constexpr double kHalfPlate_m = 0.005;  // half the default 0.01 m plate

const World& large() {
    static const World world = build_ballast_tank_large();
    return world;
}

TEST(BallastTankLarge, BoundsAreEighteenByTwoByNine) {
    const Aabb b = compute_bounds(large().mesh);
    EXPECT_NEAR(b.min.norm(), 0.0, kExactTol_m);
    EXPECT_NEAR((b.max - Eigen::Vector3d(18, 2, 9)).norm(), 0.0, kExactTol_m);
    EXPECT_NO_THROW(check_valid(large(), "large"));
}

TEST(BallastTankLarge, HasFiveLowerAndThreeUpperCompartmentsJoinedAsSpecified) {
    const auto& m = large().metadata;
    ASSERT_EQ(m.compartments.size(), 8u);
    for (int k = 0; k < 5; ++k) {
        EXPECT_EQ(m.compartments[k].level, 0);
        EXPECT_NEAR(m.compartments[k].bounds.size().x(), 3.6, kExactTol_m);
        EXPECT_NEAR(m.compartments[k].bounds.max.z(), 6.0, kExactTol_m);
    }
    for (int k = 5; k < 8; ++k) {
        EXPECT_EQ(m.compartments[k].level, 1);
        EXPECT_NEAR(m.compartments[k].bounds.size().x(), 6.0, kExactTol_m);
    }
    int manholes = 0, transitions = 0, entries = 0;
    for (const Connection& c : m.connections) {
        manholes += c.kind == ConnectionKind::Manhole;
        transitions += c.kind == ConnectionKind::LevelTransition;
        entries += c.kind == ConnectionKind::Entry;
        if (c.kind == ConnectionKind::Manhole) {
            EXPECT_EQ(c.compartment_b, c.compartment_a + 1);
            EXPECT_NEAR(c.centre.z() - 0.4 - 0.3,
                        m.compartments[c.compartment_a].bounds.min.z() +
                            (c.compartment_a >= 5 ? kHalfPlate_m : 0.0),
                        kExactTol_m);  // passage bottom 0.3 m above the floor
        }
    }
    EXPECT_EQ(manholes, 4 + 2);
    EXPECT_EQ(transitions, 2);
    EXPECT_EQ(entries, 1);
    // Transitions above lower compartments 0 and 4 lead into upper compartments 0 and 2.
    EXPECT_EQ(m.connections[6].compartment_a, 0);
    EXPECT_EQ(m.connections[6].compartment_b, 5);
    EXPECT_EQ(m.connections[7].compartment_a, 4);
    EXPECT_EQ(m.connections[7].compartment_b, 7);
    EXPECT_EQ(m.frames.size(), 8u);  // ends + 4 lower + 2 upper bulkheads
    EXPECT_EQ(m.longitudinals.size(), 20u);
}

TEST(BallastTankLarge, PassagesLetRaysThroughAndTheBulkheadAroundThemBlocks) {
    const RayCaster caster(large().mesh, large().surface_tags);
    for (const Connection& c : large().metadata.connections) {
        if (c.kind != ConnectionKind::Manhole) continue;
        const Eigen::Vector3d start = c.centre - Eigen::Vector3d(1.0, 0, 0);
        const RayHit through = caster.cast(start, Eigen::Vector3d::UnitX(), 30.0);
        ASSERT_TRUE(through.hit);
        EXPECT_GT(through.range_m, 2.0);
        const Eigen::Vector3d above = start + Eigen::Vector3d(0, 0, 0.5 * c.height_m + 0.1);
        const RayHit blocked = caster.cast(above, Eigen::Vector3d::UnitX(), 30.0);
        ASSERT_TRUE(blocked.hit);
        EXPECT_NEAR(blocked.range_m, 1.0 - kHalfPlate_m, kExactTol_m);
    }
}

TEST(BallastTankLarge, LevelTransitionsOpenTheDeck) {
    const RayCaster caster(large().mesh, large().surface_tags);
    for (const double x : {1.8, 16.2}) {
        const RayHit up = caster.cast({x, 1.0, 1.0}, Eigen::Vector3d::UnitZ(), 20.0);
        ASSERT_TRUE(up.hit);
        EXPECT_NEAR(up.point.z(), 9.0, kExactTol_m);
        const RayHit beside = caster.cast({x + 0.7, 1.0, 1.0}, Eigen::Vector3d::UnitZ(), 20.0);
        ASSERT_TRUE(beside.hit);
        EXPECT_NEAR(beside.point.z(), 6.0 - kHalfPlate_m, kExactTol_m);
    }
    const RayHit middle = caster.cast({9.0, 1.0, 1.0}, Eigen::Vector3d::UnitZ(), 20.0);
    EXPECT_NEAR(middle.point.z(), 6.0 - kHalfPlate_m, kExactTol_m);
    // Two faces of 18 x 2 m minus two 1.2 x 1.0 m openings, plus the openings' rims.
    const double rims = 2.0 * 2.0 * (1.2 + 1.0) * 2.0 * kHalfPlate_m;
    EXPECT_NEAR(testing::area_of(large(), "deck"), 2.0 * (36.0 - 2.0 * 1.2) + rims, kExactTol_m);
}

TEST(BallastTankLarge, RaysFromInsideLeaveOnlyThroughTheEntry) {
    const RayCaster caster(large().mesh, large().surface_tags);
    constexpr int kRays = 20000;
    int escaped = 0;
    for (int i = 0; i < kRays; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / kRays;
        const double phi = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
        const Eigen::Vector3d d(std::sqrt(1 - z * z) * std::cos(phi),
                                std::sqrt(1 - z * z) * std::sin(phi), z);
        const Eigen::Vector3d origin(1.0 + 2.0 * (i % 8), 1.0, i % 2 == 0 ? 2.0 : 6.5);
        if (caster.cast(origin, d, 100.0).hit) continue;
        ++escaped;
        const Eigen::Vector3d at_top = origin + ((9.0 - origin.z()) / d.z()) * d;
        EXPECT_LE(std::abs(at_top.x() - 3.0), 0.4 + kExactTol_m);
        EXPECT_LE(std::abs(at_top.y() - 1.0), 0.3 + kExactTol_m);
    }
    EXPECT_GT(escaped, 0);
}

TEST(BallastTankLarge, LandmarksAndDefectsLieOnSurfaces) {
    int checked = 0;
    for (const Landmark& l : large().metadata.landmarks) {
        if (l.kind != LandmarkKind::FrameLongitudinal) continue;
        EXPECT_LT(closest_point_on_mesh(large().mesh, l.position).distance_m, kOnSurfaceTol_m);
        ++checked;
    }
    // Per compartment and side: the longitudinals 0.75 m apart (7 in the 6 m lower level, 3 in
    // the 3 m upper one) meet both of its end frames.
    EXPECT_EQ(checked, (5 * 7 + 3 * 3) * 2 * 2);
    EXPECT_EQ(large().metadata.defects.size(), 8u);
    testing::expect_defects_on_surfaces(large(), kOnSurfaceTol_m);
}

TEST(BallastTankLarge, SameConfigGivesIdenticalWorlds) {
    testing::expect_identical(large(), build_ballast_tank_large());
}

TEST(BallastTankLarge, BadConfigValuesNameTheField) {
    auto message = [](const BallastTankLargeConfig& c) -> std::string {
        try {
            build_ballast_tank_large(c);
        } catch (const ConfigError& e) {
            return e.what();
        }
        return "no error";
    };
    BallastTankLargeConfig c;
    c.transition_compartments = {1};  // its centre x = 5.4 is 0.6 m from the upper bulkhead
    EXPECT_NE(message(c).find("ballast_tank_large.transition_compartments[0] = 1"),
              std::string::npos)
        << message(c);
    c = {};
    c.transition_compartments = {0, 5};
    EXPECT_NE(message(c).find("transition_compartments[1] = 5"), std::string::npos);
    c = {};
    c.level_height_m = 9.5;
    EXPECT_NE(message(c).find("ballast_tank_large.level_height_m"), std::string::npos);
    c = {};
    c.lower_compartments = 0;
    EXPECT_NE(message(c).find("ballast_tank_large.lower_compartments = 0"), std::string::npos);
}

}  // namespace
}  // namespace scantling::sim
