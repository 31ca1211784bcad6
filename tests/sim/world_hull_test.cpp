// Parametric hull section, the real hull in a dry dock or at a quay, and the Möbius strip.
#include <scantling/core/error.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/world_hull.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>
#include <set>
#include <string>

#include "world_test_support.hpp"

namespace scantling::sim {
namespace {

namespace fs = std::filesystem;

// Built from exact arithmetic: only rounding separates the mesh from the formulas.
constexpr double kExactTol_m = 1e-9;
// Ray ranges are refined on the hit plane (ray_caster.hpp); 1 µm is far below any sensor noise.
constexpr double kRayTol_m = 1e-6;
constexpr double kPi = std::numbers::pi;
// The defaults must leave room for surroundings and sensors: the issue asks for < ~200k.
constexpr std::size_t kMaxTriangles = 200000;
const std::set<std::string> kHullParts{"keel", "bottom",      "bilge", "side_shell",
                                       "deck", "section_end", "hull"};

std::string config_error(const std::function<void()>& build) {
    try {
        build();
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "no ConfigError";
}

bool is_hull(const World& w, std::size_t triangle) {
    return kHullParts.count(w.metadata.surfaces[w.surface_tags[triangle]].name) > 0;
}

Aabb bounds_where(const World& w, const std::function<bool(std::size_t)>& keep) {
    Aabb b;
    for (std::size_t i = 0; i < w.mesh.num_triangles(); ++i) {
        if (!keep(i)) continue;
        for (int k = 0; k < 3; ++k) b.extend(w.mesh.vertices[w.mesh.triangles[i][k]]);
    }
    return b;
}

Aabb hull_bounds(const World& w) {
    return bounds_where(w, [&](std::size_t i) { return is_hull(w, i); });
}

Aabb surface_bounds(const World& w, std::string_view name) {
    const int tag = find_surface(w.metadata, name);
    return bounds_where(w, [&](std::size_t i) { return w.surface_tags[i] == tag; });
}

ShipHullConfig prismatic() {  // no longitudinal curvature: a closed-form volume
    ShipHullConfig c;
    c.flare_rad = 0.0;
    c.side_curvature_m = 0.0;
    return c;
}

TEST(ShipHull, DefaultSectionIsThirtyByEightMetresWithTheFlaredSideAsWidest) {
    const ShipHullConfig c;
    const World w = build_ship_hull(c);
    check_valid(w, "ship_hull");
    const Aabb b = hull_bounds(w);
    const double widest =
        c.half_breadth_m + std::tan(c.flare_rad) * (c.depth_m - c.keel_height_m - c.bilge_radius_m);
    EXPECT_NEAR((b.min - Eigen::Vector3d(0.0, -widest, 0.0)).norm(), 0.0, kExactTol_m);
    EXPECT_NEAR((b.max - Eigen::Vector3d(30.0, widest, 8.0)).norm(), 0.0, kExactTol_m);
    EXPECT_LT(w.mesh.num_triangles(), kMaxTriangles);
    EXPECT_EQ(w.metadata.frames.size(), 38u);        // x = 0, 0.8, ..., 29.6
    EXPECT_EQ(w.metadata.longitudinals.size(), 8u);  // 1.9 m + k 0.7 m < 8 m
    EXPECT_EQ(w.metadata.landmarks.size(), 38u * 8u);
}

TEST(ShipHull, KeelIsTheLowestHullPointAndTheDockFloorIsBelowIt) {
    const ShipHullConfig c;
    const World w = build_ship_hull(c);
    EXPECT_NEAR(surface_bounds(w, "keel").min.z(), 0.0, kExactTol_m);
    EXPECT_NEAR(surface_bounds(w, "bottom").min.z(), c.keel_height_m, kExactTol_m);
    EXPECT_NEAR(surface_bounds(w, "bilge").min.z(), c.keel_height_m, kExactTol_m);
    EXPECT_NEAR(surface_bounds(w, "dock_floor").max.z(), -c.surroundings.keel_block_height_m,
                kExactTol_m);
    const Aabb blocks = surface_bounds(w, "keel_blocks");
    EXPECT_NEAR(blocks.max.z(), 0.0, kExactTol_m);  // the hull rests on them
    EXPECT_NEAR(blocks.max.y(), 0.5 * c.surroundings.keel_block_width_m, kExactTol_m);
}

TEST(ShipHull, ClosedSectionEnclosesTheProfileAreaTimesLength) {
    const ShipHullConfig c = prismatic();
    const World w = build_ship_hull(c);
    double volume = 0.0;
    for (const auto& name : kHullParts)
        volume += testing::volume_of(w, name) * (find_surface(w.metadata, name) >= 0);
    const double r = c.bilge_radius_m;
    // Each bilge is a fan of bilge_segments chords, not a true quarter circle.
    const double corner_cut =
        r * r - 0.5 * r * r * c.bilge_segments * std::sin(0.5 * kPi / c.bilge_segments);
    const double area = c.keel_width_m * c.keel_height_m +
                        2.0 * c.half_breadth_m * (c.depth_m - c.keel_height_m) - 2.0 * corner_cut;
    EXPECT_NEAR(volume, area * c.length_m, 1e-6);
}

TEST(ShipHull, HorizontalRayFromBesideTheHullHitsTheSideShellAtTheFlaredOffset) {
    const ShipHullConfig c;
    const World w = build_ship_hull(c);
    const RayCaster caster(w.mesh, w.surface_tags);
    const int side = find_surface(w.metadata, "side_shell");
    const double step = c.length_m / 60.0;  // station spacing 0.5 m
    for (const double x : {15.0, 0.25, 7.3}) {
        for (const double z : {3.0, 6.5}) {
            const int i = static_cast<int>(std::floor(x / step));
            const auto s2 = [&](double xx) { return std::pow(2.0 * xx / c.length_m - 1.0, 2); };
            const double t = (x - i * step) / step;
            const double inward =
                c.side_curvature_m * ((1 - t) * s2(i * step) + t * s2((i + 1) * step));
            const double y = c.half_breadth_m - inward +
                             std::tan(c.flare_rad) * (z - c.keel_height_m - c.bilge_radius_m);
            const RayHit hit = caster.cast({x, 12.0, z}, -Eigen::Vector3d::UnitY(), 20.0);
            ASSERT_TRUE(hit.hit) << x << " " << z;
            EXPECT_EQ(hit.surface_tag, side);
            EXPECT_NEAR(hit.range_m, 12.0 - y, kRayTol_m) << x << " " << z;
        }
    }
}

TEST(ShipHull, LandmarksAndDefectsLieOnTheShell) {
    const World w = build_ship_hull();
    ASSERT_EQ(w.metadata.defects.size(), 8u);
    testing::expect_defects_on_surfaces(w, kRayTol_m);
    const std::set<std::string> shell{"side_shell", "bilge", "bottom"};
    for (const Defect& d : w.metadata.defects) {
        EXPECT_EQ(shell.count(w.metadata.surfaces[d.surface_tag].name), 1u) << d.id;
    }
    for (std::size_t k = 0; k < w.metadata.landmarks.size(); k += 7) {
        const auto& p = w.metadata.landmarks[k].position;
        EXPECT_LT(closest_point_on_mesh(w.mesh, p).distance_m, kRayTol_m) << k;
    }
}

TEST(ShipHull, SurroundingsFollowTheEnvironment) {
    ShipHullConfig c;
    c.surroundings.environment = HullEnvironment::kNone;
    const World bare = build_ship_hull(c);
    for (std::size_t i = 0; i < bare.mesh.num_triangles(); ++i) ASSERT_TRUE(is_hull(bare, i));
    EXPECT_EQ(find_surface(bare.metadata, "dock_floor"), -1);

    c.surroundings.environment = HullEnvironment::kQuay;
    const World quay = build_ship_hull(c);
    check_valid(quay, "quay");
    EXPECT_EQ(find_surface(quay.metadata, "keel_blocks"), -1);
    EXPECT_NEAR(surface_bounds(quay, "water").max.z(), c.surroundings.draught_m, kExactTol_m);
    EXPECT_NEAR(surface_bounds(quay, "seabed").max.z(),
                c.surroundings.draught_m - c.surroundings.water_depth_m, kExactTol_m);
    const Aabb bollards = surface_bounds(quay, "bollards");
    EXPECT_NEAR(bollards.max.z(), c.surroundings.draught_m + 3.0 + 0.7, kExactTol_m);
    const RayCaster caster(quay.mesh, quay.surface_tags);
    const RayHit wall = caster.cast({15.0, 0.0, 7.5}, Eigen::Vector3d::UnitY(), 100.0);
    ASSERT_TRUE(wall.hit);  // from inside the hull: the side shell first
    const double widest = 8.0 + std::tan(0.05) * (8.0 - 1.9);
    const RayHit quay_wall =
        caster.cast({15.0, widest + 0.5, 4.0}, Eigen::Vector3d::UnitY(), 100.0);
    ASSERT_TRUE(quay_wall.hit);
    EXPECT_EQ(quay.metadata.surfaces[quay_wall.surface_tag].name, "quay_wall");
    EXPECT_NEAR(quay_wall.range_m, 2.0 - 0.5, kRayTol_m);
}

TEST(ShipHull, SameConfigGivesTheSameWorld) {
    testing::expect_identical(build_ship_hull(), build_ship_hull());
}

TEST(ShipHull, BadConfigNamesTheField) {
    ShipHullConfig c;
    c.bilge_radius_m = 8.0;
    EXPECT_NE(config_error([&] { build_ship_hull(c); }).find("ship_hull.bilge_radius_m"),
              std::string::npos);
    c = {};
    c.surroundings.water_depth_m = 1.0;
    EXPECT_NE(
        config_error([&] { build_ship_hull(c); }).find("ship_hull.surroundings.water_depth_m"),
        std::string::npos);
    c = {};
    c.side_curvature_m = 10.0;
    EXPECT_THROW(build_ship_hull(c), ConfigError);
    c = {};
    c.station_spacing_m = 0.0;
    EXPECT_THROW(build_ship_hull(c), ConfigError);
    EXPECT_NE(config_error([] { build_hull_mesh_in_dock({}); }).find("ship_hull_mesh.path"),
              std::string::npos);
}

TEST(ShipHullMesh, DtcHullStandsFullSizeOnKeelBlocksInTheDryDock) {
    const fs::path path =
        fs::path(SCANTLING_SHARED_DATA_DIR) / "meshes" / "dtc-container-ship-hull-model-scale.stl";
    if (!fs::exists(path)) GTEST_SKIP() << "shared data not found at " << path;
    HullMeshDockConfig c;
    c.path = path.string();
    const World w = build_hull_mesh_in_dock(c);
    check_valid(w, "dtc");
    const Aabb hull = surface_bounds(w, "hull");
    // Lpp is 355 m; the mesh runs from the transom to the bulb tip, a little beyond.
    EXPECT_GT(hull.max.x() - hull.min.x(), 355.0);
    EXPECT_LT(hull.max.x() - hull.min.x(), 375.0);
    EXPECT_NEAR(hull.max.y() - hull.min.y(), 51.0, 0.1);  // DTC beam 51 m
    EXPECT_NEAR(hull.min.z(), 0.0, kExactTol_m);
    EXPECT_LT(w.mesh.num_triangles(), kMaxTriangles);
    const Aabb blocks = surface_bounds(w, "keel_blocks");
    EXPECT_NEAR(blocks.max.z(), 0.0, kExactTol_m);
    EXPECT_GT(blocks.max.x() - blocks.min.x(), 150.0);  // the flat keel is most of the length
    EXPECT_NEAR(surface_bounds(w, "dock_floor").max.z(), -1.5, kExactTol_m);
    EXPECT_EQ(w.metadata.frames.size(),
              static_cast<std::size_t>(std::floor((hull.max.x() - hull.min.x()) / 10.0)) + 1);
}

TEST(Moebius, SheetHasOneVertexPerGridNodeWithinHalfTheWidthOfTheCentreCircle) {
    MoebiusConfig c;
    c.thickness_m = 0.0;
    const World w = build_moebius(c);
    check_valid(w, "moebius");
    EXPECT_EQ(w.mesh.num_vertices(), 256u * 17u);
    EXPECT_EQ(w.mesh.num_triangles(), 2u * 256u * 16u);
    EXPECT_EQ(find_surface(w.metadata, "rim"), -1);
    double farthest = 0.0;
    for (const auto& p : w.mesh.vertices) {
        farthest = std::max(farthest, std::hypot(std::hypot(p.x(), p.y()) - c.radius_m, p.z()));
    }
    EXPECT_NEAR(farthest, 0.5 * c.width_m, kExactTol_m);
}

TEST(Moebius, ThickStripIsOneClosedOutwardSurfaceOfItsVolume) {
    const MoebiusConfig c;
    const World w = build_moebius(c);
    check_valid(w, "moebius");
    EXPECT_EQ(w.mesh.num_vertices(), 2u * 256u * 17u);
    const double volume = testing::volume_of(w, "strip") + testing::volume_of(w, "rim");
    // The mid-surface area is 2πR w up to O((w/R)²) terms and the chordal facets: 2 %.
    EXPECT_NEAR(volume, 2.0 * kPi * c.radius_m * c.width_m * c.thickness_m,
                0.02 * 2.0 * kPi * c.radius_m * c.width_m * c.thickness_m);
    const double reach = std::hypot(0.5 * c.width_m, 0.5 * c.thickness_m);
    for (const auto& p : w.mesh.vertices) {
        ASSERT_LE(std::hypot(std::hypot(p.x(), p.y()) - c.radius_m, p.z()), reach + kExactTol_m);
    }
    testing::expect_identical(w, build_moebius(c));
}

TEST(Moebius, BadConfigNamesTheField) {
    MoebiusConfig c;
    c.width_m = 3.0;
    EXPECT_NE(config_error([&] { build_moebius(c); }).find("moebius.width_m"), std::string::npos);
    c = {};
    c.segments_around = 2;
    EXPECT_NE(config_error([&] { build_moebius(c); }).find("moebius.segments_around"),
              std::string::npos);
    c = {};
    c.thickness_m = -0.1;
    EXPECT_THROW(build_moebius(c), ConfigError);
}

}  // namespace
}  // namespace scantling::sim
