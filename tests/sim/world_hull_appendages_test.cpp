// Hull appendages of the parametric ship hull (issue 14, item 6): bilge keels, anodes and a
// sea-chest grating, seen by rays cast from 1 m off the shell.
#include <scantling/core/error.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/world_hull.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "world_test_support.hpp"

namespace scantling::sim {
namespace {

// Ray ranges are refined on the hit plane (ray_caster.hpp); the pieces are built from the same
// shell points the tests compute, so only rounding separates them.
constexpr double kRayTol_m = 1e-6;
// Hit normals come from single triangles of exact geometry.
constexpr double kAngleTol_rad = 1e-9;
// The default hull (dry dock) and the hull alone as built before appendages existed, measured
// with `scantling info` on the recorded world/mesh.ply: adding the feature must not move them.
constexpr std::size_t kDefaultTriangles = 14714, kDefaultVertices = 7376;
constexpr std::size_t kBareHullTriangles = 14636;
constexpr double kInfoTol_m = 1e-6;  // `scantling info` prints bounds with 6 decimals
const double kFlare_rad = ShipHullConfig{}.flare_rad;
const double kCos45 = std::sqrt(0.5);
const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();

std::string error_of(const std::function<void()>& run) {
    try {
        run();
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

std::string surface_name(const World& w, const RayHit& hit) {
    return hit.hit ? w.metadata.surfaces[hit.surface_tag].name : "(miss)";
}

// Hull alone, with a bilge keel over x in [7.5, 22.5], an anode on the port side and a
// grating on the starboard side, both at midship where the side is symmetric along x.
ShipHullConfig with_appendages() {
    ShipHullConfig c;
    c.surroundings.environment = HullEnvironment::kNone;
    c.appendages.bilge_keels.push_back({});
    c.appendages.anodes.push_back({.side = HullSide::kPort, .x_m = 15.0, .z_m = 3.0});
    c.appendages.gratings.push_back({.side = HullSide::kStarboard, .x_m = 15.0, .z_m = 4.5});
    return c;
}

// Midship side-shell point at height z and its outward unit normal (the flare tilts it down).
Eigen::Vector3d midship_shell(double z, double side) {
    const double y = 8.0 + std::tan(kFlare_rad) * (z - 1.9);
    return {15.0, side * y, z};
}
Eigen::Vector3d midship_normal(double side) {
    return {0.0, side * std::cos(kFlare_rad), -std::sin(kFlare_rad)};
}

// Inward offset of the side at x (0 at midship): 0.3 s², s = 2x/30 − 1, interpolated linearly
// between the 0.5 m stations as the swept shell is.
double inward_m(double x) {
    const auto at = [](double xs) { return 0.3 * std::pow(2.0 * xs / 30.0 - 1.0, 2); };
    const double x0 = 0.5 * std::floor(x / 0.5), t = (x - x0) / 0.5;
    return (1.0 - t) * at(x0) + t * at(x0 + 0.5);
}

// Range along −n from 1 m off the shell at `p` (normal n).
RayHit cast_from_one_metre(const RayCaster& caster, const Eigen::Vector3d& p,
                           const Eigen::Vector3d& n) {
    return caster.cast(p + 1.0 * n, -n, 5.0);
}

TEST(HullAppendages, WithoutThemTheHullIsTheOneMeasuredBeforeTheyExisted) {
    const World w = build_ship_hull();
    EXPECT_EQ(w.mesh.num_triangles(), kDefaultTriangles);
    EXPECT_EQ(w.mesh.num_vertices(), kDefaultVertices);
    const Aabb b = compute_bounds(w.mesh);
    EXPECT_NEAR((b.min - Eigen::Vector3d(-15.0, -16.305254, -1.5)).norm(), 0.0, kInfoTol_m);
    EXPECT_NEAR((b.max - Eigen::Vector3d(45.0, 16.305254, 12.5)).norm(), 0.0, kInfoTol_m);
    for (const char* name : {"bilge_keel", "anode", "sea_chest_grating"}) {
        EXPECT_EQ(find_surface(w.metadata, name), -1) << name;
    }
    const Scenario s = parse_scenario(
        "world:\n  type: ship_hull\n  ship_hull:\n    appendages: {bilge_keels: [], anodes: []}\n");
    testing::expect_identical(build_world(s.world), w);
}

TEST(HullAppendages, EachKindIsItsOwnSurfaceAndTheHullKeepsItsTriangles) {
    const World w = build_ship_hull(with_appendages());
    check_valid(w, "appendages");
    std::size_t hull_triangles = 0;
    for (const char* name : {"bilge_keel", "anode", "sea_chest_grating"}) {
        EXPECT_GT(testing::area_of(w, name), 0.0) << name;
        // Closed solids facing outward enclose a positive volume.
        EXPECT_GT(testing::volume_of(w, name), 0.0) << name;
    }
    const int first_appendage = find_surface(w.metadata, "bilge_keel");
    for (const int tag : w.surface_tags) hull_triangles += tag < first_appendage ? 1 : 0;
    EXPECT_EQ(hull_triangles, kBareHullTriangles);
    // Anode 0.6 × 0.15 × (0.10 + 1 cm weld), 9 bars 0.02 × 0.6 × (0.05 + 1 cm weld).
    EXPECT_NEAR(testing::volume_of(w, "anode"), 0.6 * 0.15 * 0.11, 1e-9);
    EXPECT_NEAR(testing::volume_of(w, "sea_chest_grating"), 9 * 0.02 * 0.6 * 0.06, 1e-9);
}

TEST(HullAppendages, AnodeStandsItsThicknessOutOfThePortSideShell) {
    const World w = build_ship_hull(with_appendages());
    const RayCaster caster(w.mesh, w.surface_tags);
    const Eigen::Vector3d n = midship_normal(-1.0);
    const RayHit anode = cast_from_one_metre(caster, midship_shell(3.0, -1.0), n);
    EXPECT_EQ(surface_name(w, anode), "anode");
    EXPECT_NEAR(anode.range_m, 1.0 - 0.10, kRayTol_m);
    for (const double z : {3.0 + 0.1, 3.0 - 0.1}) {  // just above and below the 0.15 m box
        const RayHit shell = cast_from_one_metre(caster, midship_shell(z, -1.0), n);
        EXPECT_EQ(surface_name(w, shell), "side_shell") << z;
        EXPECT_NEAR(shell.range_m, 1.0, kRayTol_m) << z;
    }
}

TEST(HullAppendages, GratingBarsStandOffTheStarboardShellWithGapsBetweenThem) {
    const World w = build_ship_hull(with_appendages());
    const RayCaster caster(w.mesh, w.surface_tags);
    const Eigen::Vector3d n = midship_normal(1.0), p = midship_shell(4.5, 1.0);
    for (const double u : {0.0, 0.1, -0.4}) {  // the centre bar, the next, the last
        const RayHit bar = cast_from_one_metre(caster, p + u * kX, n);
        EXPECT_EQ(surface_name(w, bar), "sea_chest_grating") << u;
        EXPECT_NEAR(bar.range_m, 1.0 - 0.05, kRayTol_m) << u;
    }
    for (const double u : {0.05, -0.35, 0.45}) {  // between bars, and beyond the last one
        const RayHit gap = cast_from_one_metre(caster, p + u * kX, n);
        EXPECT_EQ(surface_name(w, gap), "side_shell") << u;
        // Off midship the side has curved inward; along n that adds inward · cos(flare).
        EXPECT_NEAR(gap.range_m, 1.0 + inward_m(15.0 + u) * std::cos(kFlare_rad), kRayTol_m) << u;
    }
}

TEST(HullAppendages, BilgeKeelStandsOutNormalToTheBilgeAtFortyFiveDegrees) {
    const World w = build_ship_hull(with_appendages());
    const RayCaster caster(w.mesh, w.surface_tags);
    // Bilge centre (y = 8 − 1.5 − inward, z = 1.9); inward = 0.3 s², s = 2x/30 − 1.
    for (const double x : {15.0, 10.0, 5.0}) {
        const double s = 2.0 * x / 30.0 - 1.0, centre_y = 6.5 - 0.3 * s * s;
        for (const double side : {1.0, -1.0}) {
            const Eigen::Vector3d n(0.0, side * kCos45, -kCos45);
            const Eigen::Vector3d bilge = Eigen::Vector3d(x, side * centre_y, 1.9) + 1.5 * n;
            const RayHit hit = cast_from_one_metre(caster, bilge, n);
            const bool on_keel = x > 7.5;  // the keel spans x in [7.5, 22.5]
            EXPECT_EQ(surface_name(w, hit), on_keel ? "bilge_keel" : "bilge") << x << " " << side;
            EXPECT_NEAR(hit.range_m, on_keel ? 1.0 - 0.4 : 1.0, kRayTol_m) << x << " " << side;
        }
    }
    // Horizontal rays meet the keel's upper face: it falls 1 m per metre outward, and faces
    // up and out at 45°.
    std::array<double, 2> face_y{};
    const std::array<double, 2> z{0.65, 0.75};
    for (int k = 0; k < 2; ++k) {
        const RayHit hit = caster.cast({15.0, 12.0, z[k]}, -Eigen::Vector3d::UnitY(), 20.0);
        ASSERT_EQ(surface_name(w, hit), "bilge_keel") << z[k];
        face_y[k] = hit.point.y();
        EXPECT_NEAR(std::atan2(hit.normal.z(), hit.normal.y()), std::numbers::pi / 4,
                    kAngleTol_rad);
    }
    EXPECT_NEAR(std::atan2(face_y[0] - face_y[1], z[1] - z[0]), std::numbers::pi / 4,
                kAngleTol_rad * 1e3);  // from two 1e-6 m ranges 0.1 m apart
}

void expect_message(const std::string& yaml, const std::string& key) {
    const std::string what = error_of([&] { parse_scenario(yaml, "bad.yaml"); });
    EXPECT_NE(what.find(key), std::string::npos) << what;
}

TEST(HullAppendages, ScenarioReadsThemAndRefusesBadKeysAndValuesNamingThem) {
    const std::string head = "world:\n  type: ship_hull\n  ship_hull:\n    appendages:\n";
    const Scenario s = parse_scenario(
        head +
        "      bilge_keels: [{x_start_m: 5, x_end_m: 25, depth_m: 0.3, thickness_m: 0.05}]\n"
        "      anodes: [{side: starboard, x_m: 12, z_m: 2.5}, {x_m: 20, z_m: 4, length_m: 0.8}]\n"
        "      gratings: [{x_m: 8, z_m: 3, bar_count: 5, stand_off_m: 0.08}]\n");
    const HullAppendagesConfig& a = s.world.ship_hull.appendages;
    ASSERT_EQ(a.bilge_keels.size(), 1u);
    EXPECT_DOUBLE_EQ(a.bilge_keels[0].x_end_m, 25.0);
    EXPECT_DOUBLE_EQ(a.bilge_keels[0].thickness_m, 0.05);
    ASSERT_EQ(a.anodes.size(), 2u);
    EXPECT_EQ(a.anodes[0].side, HullSide::kStarboard);
    EXPECT_EQ(a.anodes[1].side, HullSide::kPort);     // the default
    EXPECT_DOUBLE_EQ(a.anodes[1].thickness_m, 0.10);  // the default
    EXPECT_DOUBLE_EQ(a.anodes[1].length_m, 0.8);
    ASSERT_EQ(a.gratings.size(), 1u);
    EXPECT_EQ(a.gratings[0].bar_count, 5);
    EXPECT_NE(find_surface(build_world(s.world).metadata, "sea_chest_grating"), -1);

    const std::string appendages = "world.ship_hull.appendages.";
    expect_message(head + "      bilge_keel: []\n", appendages + "bilge_keel'");
    expect_message(head + "      anodes: [{radius_m: 1}]\n", appendages + "anodes[0].radius_m");
    expect_message(head + "      anodes: [{length_m: -0.1}]\n", appendages + "anodes[0].length_m");
    expect_message(head + "      gratings: [{side: middle}]\n", appendages + "gratings[0].side");
    expect_message(head + "      bilge_keels: [{x_end_m: 40}]\n",
                   appendages + "bilge_keels[0].x_end_m = 40");
    expect_message(head + "      bilge_keels: [{depth_m: 2}]\n",
                   appendages + "bilge_keels[0].depth_m = 2");
    expect_message(head + "      gratings: [{bar_width_m: 0.2}]\n",
                   appendages + "gratings[0].bar_width_m = 0.2");
    expect_message(head + "      gratings: [{x_m: 0.1}]\n", appendages + "gratings[0].x_m = 0.1");
    // At a quay the world knows the draught (5 m): an anode at 6 m is above the water line;
    // in the dry dock it is not checked against any water line.
    const std::string high_anode = "      anodes: [{z_m: 6}]\n";
    expect_message(head + high_anode + "    surroundings: {environment: quay}\n",
                   appendages + "anodes[0].z_m = 6");
    EXPECT_EQ(parse_scenario(head + high_anode).world.ship_hull.appendages.anodes.at(0).z_m, 6.0);
}

TEST(HullAppendages, BadPlacementInCodeNamesTheField) {
    ShipHullConfig c = with_appendages();
    c.appendages.anodes[0].z_m = 1.0;  // down on the bilge
    EXPECT_NE(error_of([&] { build_ship_hull(c); }).find("ship_hull.appendages.anodes[0].z_m"),
              std::string::npos);
    c = with_appendages();
    c.appendages.bilge_keels[0].thickness_m = -0.02;
    EXPECT_NE(error_of([&] {
                  build_ship_hull(c);
              }).find("ship_hull.appendages.bilge_keels[0].thickness_m"),
              std::string::npos);
    c = with_appendages();
    c.appendages.gratings[0].bar_count = 0;
    EXPECT_NE(
        error_of([&] { build_ship_hull(c); }).find("ship_hull.appendages.gratings[0].bar_count"),
        std::string::npos);
    c = with_appendages();
    c.appendages.bilge_keels[0].x_start_m = std::nan("");
    EXPECT_THROW(build_ship_hull(c), ConfigError);
}

}  // namespace
}  // namespace scantling::sim
