#include <scantling/core/error.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/world_builders.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "world_test_support.hpp"

namespace scantling::sim {
namespace {

using testing::area_of;
using testing::volume_of;

// Vertices are sums of config values: exact up to a few ulps of metres.
constexpr double kExactTol_m = 1e-9;
// closest_point_on_mesh works in double on exact geometry.
constexpr double kOnSurfaceTol_m = 1e-6;

const BallastTankMockupConfig kConfig{};
const World& mockup() {
    static const World world = build_ballast_tank_mockup();
    return world;
}

TEST(BallastTankMockup, BoundsMatchTheConfig) {
    const Aabb b = compute_bounds(mockup().mesh);
    EXPECT_NEAR(b.min.norm(), 0.0, kExactTol_m);
    EXPECT_NEAR(b.max.x(), 5.3, kExactTol_m);
    EXPECT_NEAR(b.max.y(), 2.9, kExactTol_m);
    EXPECT_NEAR(b.max.z(), 1.75, kExactTol_m);
    EXPECT_NO_THROW(check_valid(mockup(), "mockup"));
}

TEST(BallastTankMockup, RayThroughTheManholeCentrePassesAndOneJustOutsideItsEdgeIsBlocked) {
    const RayCaster caster(mockup().mesh, mockup().surface_tags);
    const double yc = kConfig.manhole_centre_y_m, zc = kConfig.manhole_centre_z_m;
    const RayHit through = caster.cast({1.0, yc, zc}, Eigen::Vector3d::UnitX(), 10.0);
    ASSERT_TRUE(through.hit);
    EXPECT_NEAR(through.range_m, 5.3 - 1.0, kExactTol_m);
    EXPECT_EQ(through.surface_tag, find_surface(mockup().metadata, "fore_bulkhead"));
    const double web_face_x = 0.5 * 5.3 - 0.5 * kConfig.plate_thickness_m;
    for (const Eigen::Vector3d& offset :
         {Eigen::Vector3d(0, 0.4, 0), Eigen::Vector3d(0, -0.4, 0), Eigen::Vector3d(0, 0, 0.5),
          Eigen::Vector3d(0, 0, -0.5)}) {
        // 0.1 m beyond the 0.6 x 0.8 m opening's edge.
        const RayHit blocked =
            caster.cast(Eigen::Vector3d(1.0, yc, zc) + offset, Eigen::Vector3d::UnitX(), 10.0);
        ASSERT_TRUE(blocked.hit);
        EXPECT_NEAR(blocked.range_m, web_face_x - 1.0, kExactTol_m);
        EXPECT_EQ(blocked.surface_tag, find_surface(mockup().metadata, "web_frame"));
    }
}

// Rays from inside escape only through the entry manhole: no gaps at joints.
TEST(BallastTankMockup, ShellIsClosedExceptForTheEntryManhole) {
    const RayCaster caster(mockup().mesh, mockup().surface_tags);
    int escaped = 0;
    constexpr int kRays = 20000;
    for (int i = 0; i < kRays; ++i) {
        // Fibonacci sphere directions from a point in each compartment.
        const double z = 1.0 - 2.0 * (i + 0.5) / kRays;
        const double phi = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
        const Eigen::Vector3d d(std::sqrt(1 - z * z) * std::cos(phi),
                                std::sqrt(1 - z * z) * std::sin(phi), z);
        const Eigen::Vector3d origin =
            i % 2 == 0 ? Eigen::Vector3d(1.2, 2.0, 1.0) : Eigen::Vector3d(4.0, 2.0, 0.9);
        const RayHit hit = caster.cast(origin, d, 100.0);
        if (hit.hit) continue;
        ++escaped;
        ASSERT_GT(d.z(), 0.0);
        const Eigen::Vector3d at_deck = origin + ((1.75 - origin.z()) / d.z()) * d;
        EXPECT_LE(std::abs(at_deck.x() - kConfig.entry_centre_x_m), 0.4 + kExactTol_m);
        EXPECT_LE(std::abs(at_deck.y() - kConfig.entry_centre_y_m), 0.3 + kExactTol_m);
    }
    EXPECT_GT(escaped, 0);  // the entry is open
}

// Stiffener faces lie on the walls (coplanar overlaps): the reported triangle must still not
// depend on the thread count.
TEST(BallastTankMockup, BatchCastsAreIdenticalForOneAndTwoThreads) {
    const RayCaster caster(mockup().mesh, mockup().surface_tags);
    std::vector<Ray> rays;
    for (int i = 0; i < 4000; ++i) {
        const double a = 0.01 * i, b = 0.37 * i;
        rays.push_back(
            {{2.0, 1.8, 0.9},
             Eigen::Vector3d(std::cos(a) * std::cos(b), std::cos(a) * std::sin(b), std::sin(a))
                 .normalized(),
             20.0,
             0.0});
    }
    const auto one = caster.cast_batch(rays, ParallelConfig{1});
    const auto two = caster.cast_batch(rays, ParallelConfig{2});
    for (std::size_t i = 0; i < rays.size(); ++i) {
        EXPECT_EQ(one[i].hit, two[i].hit);
        EXPECT_EQ(one[i].triangle, two[i].triangle);
        EXPECT_EQ(one[i].surface_tag, two[i].surface_tag);
        EXPECT_EQ(one[i].range_m, two[i].range_m);
    }
}

TEST(BallastTankMockup, WebFrameIsTheSectionMinusTheManhole) {
    const double section_area = 1.75 * 2.9 - 0.5 * 1.3 * 0.9;
    const double hole_area = 0.6 * 0.8;
    const double rim_area = 2.0 * (0.6 + 0.8) * kConfig.plate_thickness_m;
    EXPECT_NEAR(area_of(mockup(), "web_frame"), 2.0 * (section_area - hole_area) + rim_area,
                kExactTol_m);
    EXPECT_NEAR(area_of(mockup(), "aft_bulkhead"), section_area, kExactTol_m);
    EXPECT_NEAR(area_of(mockup(), "deck"), 5.3 * 2.9 - 0.6 * 0.8, kExactTol_m);
}

TEST(BallastTankMockup, StiffenersAreClosedOutwardFacingFlatBars) {
    const auto& m = mockup().metadata;
    ASSERT_EQ(m.longitudinals.size(), 13u);  // 2 bottom, 3 side, 5 deck, 1 inboard, 2 hopper
    const double section = kConfig.stiffener.height_m * kConfig.stiffener.thickness_m;
    for (const FrameLine& l : m.longitudinals) {
        const std::string name = "longitudinal_" + std::to_string(l.number);
        // Deck longitudinals crossing the entry are cut around it: 0.9 m shorter.
        const bool cut = l.surface == "deck" && std::abs(l.point.y() - 2.1) < 0.45;
        const double length = cut ? 5.3 - 0.9 : 5.3;
        EXPECT_NEAR(volume_of(mockup(), name), length * section, kExactTol_m) << name;
    }
}

TEST(BallastTankMockup, ShellNormalsPointIntoTheTank) {
    const World& w = mockup();
    const std::set<std::string> shell{"bottom", "side_shell",   "deck",         "inboard_side",
                                      "hopper", "aft_bulkhead", "fore_bulkhead"};
    int checked = 0;
    for (std::size_t i = 0; i < w.mesh.num_triangles(); ++i) {
        if (shell.count(w.metadata.surfaces[w.surface_tags[i]].name) == 0) continue;
        ++checked;
        const auto& t = w.mesh.triangles[i];
        const Eigen::Vector3d centroid =
            (w.mesh.vertices[t[0]] + w.mesh.vertices[t[1]] + w.mesh.vertices[t[2]]) / 3.0;
        const Eigen::Vector3d q = centroid + 1e-4 * triangle_normal(w.mesh, i);
        // Inside the box and above the hopper plane through (1.3, 0) and (0, 0.9).
        EXPECT_TRUE(q.x() > 0 && q.x() < 5.3 && q.y() > 0 && q.y() < 2.9 && q.z() > 0 &&
                    q.z() < 1.75 && 0.9 * q.y() + 1.3 * q.z() > 0.9 * 1.3)
            << "triangle " << i << " of " << w.metadata.surfaces[w.surface_tags[i]].name;
    }
    EXPECT_EQ(checked, 4 * 2 + 8 + 2 * 3);  // walls, deck around the entry, bulkheads
}

TEST(BallastTankMockup, MetadataDescribesTwoCompartmentsJoinedByTheManhole) {
    const auto& m = mockup().metadata;
    EXPECT_EQ(m.name, "ballast_tank_mockup");
    ASSERT_EQ(m.compartments.size(), 2u);
    EXPECT_NEAR(m.compartments[0].bounds.max.x(), 2.65, kExactTol_m);
    ASSERT_EQ(m.connections.size(), 2u);
    EXPECT_EQ(m.connections[0].kind, ConnectionKind::Manhole);
    EXPECT_EQ(m.connections[0].compartment_a, 0);
    EXPECT_EQ(m.connections[0].compartment_b, 1);
    EXPECT_NEAR((m.connections[0].centre - Eigen::Vector3d(2.65, 2.1, 0.85)).norm(), 0.0,
                kExactTol_m);
    EXPECT_EQ(m.connections[1].kind, ConnectionKind::Entry);
    EXPECT_EQ(m.connections[1].compartment_b, Connection::kOutside);
    ASSERT_EQ(m.frames.size(), 3u);
    EXPECT_NEAR(m.frames[1].point.x(), 2.65, kExactTol_m);
    // 13 longitudinals x 2 frames x 2 compartments, plus the manhole centre in each
    // compartment and the entry in the first.
    EXPECT_EQ(m.landmarks.size(), 13u * 4u + 3u);
    EXPECT_EQ(m.defects.size(), 4u);
}

TEST(BallastTankMockup, FrameLongitudinalLandmarksLieOnSurfaces) {
    const World& w = mockup();
    int checked = 0;
    for (const Landmark& l : w.metadata.landmarks) {
        EXPECT_TRUE(io::compartment_at(w.metadata, l.position).has_value());
        if (l.kind != LandmarkKind::FrameLongitudinal) continue;
        EXPECT_LT(closest_point_on_mesh(w.mesh, l.position).distance_m, kOnSurfaceTol_m)
            << "landmark " << l.id;
        const Aabb& box = w.metadata.compartments[l.compartment].bounds;
        EXPECT_TRUE(l.position.x() >= box.min.x() && l.position.x() <= box.max.x());
        ++checked;
    }
    EXPECT_EQ(checked, 52);
}

TEST(BallastTankMockup, DefectsLieOnVisibleWalls) {
    testing::expect_defects_on_surfaces(mockup(), kOnSurfaceTol_m);
}

TEST(BallastTankMockup, SameConfigGivesIdenticalWorlds) {
    testing::expect_identical(mockup(), build_ballast_tank_mockup());
    BallastTankMockupConfig other;
    other.defects.seed = 2;
    EXPECT_NE(build_ballast_tank_mockup(other).metadata.defects[0].centre,
              mockup().metadata.defects[0].centre);
}

TEST(BallastTankMockup, AngleProfilesAddAFlange) {
    BallastTankMockupConfig config;
    config.stiffener.profile = ProfileKind::Angle;
    const World w = build_ballast_tank_mockup(config);
    const double t = config.stiffener.thickness_m, h = config.stiffener.height_m;
    // Web and flange are two closed boxes (their t x t overlap counts twice).
    const double flange_section = (t + config.stiffener.flange_width_m) * t;
    EXPECT_NEAR(volume_of(w, "longitudinal_1"), 5.3 * (h * t + flange_section), kExactTol_m);
}

void expect_config_error(const BallastTankMockupConfig& config, const std::string& field) {
    try {
        build_ballast_tank_mockup(config);
        ADD_FAILURE() << "no ConfigError for " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("ballast_tank_mockup." + field), std::string::npos)
            << e.what();
    }
}

TEST(BallastTankMockup, BadConfigValuesNameTheField) {
    BallastTankMockupConfig c;
    c.length_m = -1.0;
    expect_config_error(c, "length_m");
    c = {};
    c.hopper_width_m = 3.0;
    expect_config_error(c, "hopper_width_m");
    c = {};
    c.manhole_centre_z_m = 0.3;  // the manhole would cut the bottom longitudinals
    expect_config_error(c, "manhole_centre_y_m");
    c = {};
    c.entry_centre_x_m = 4.0;  // in the second compartment
    expect_config_error(c, "entry_centre_x_m");
    c = {};
    c.stiffener.thickness_m = 0.0;
    expect_config_error(c, "stiffener.thickness_m");
    c = {};
    c.defects.count = 100000;
    expect_config_error(c, "defects.count");
    c = {};
    c.defects.crack_fraction = 1.5;
    expect_config_error(c, "defects.crack_fraction");
}

}  // namespace
}  // namespace scantling::sim
