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
constexpr double kHalfTray_m = 0.005;
const DistillationColumnConfig kConfig{};

const World& column() {
    static const World world = build_distillation_column();
    return world;
}

TEST(DistillationColumn, BoundsMatchTheConfig) {
    const Aabb b = compute_bounds(column().mesh);
    EXPECT_NEAR(b.max.x(), 1.5, kExactTol_m);  // a vertex of the 96-gon lies on +x
    EXPECT_NEAR(b.min.x(), -1.5, kExactTol_m);
    EXPECT_NEAR(b.max.y(), 1.5, kExactTol_m);
    EXPECT_NEAR(b.min.z(), 0.0, kExactTol_m);
    EXPECT_NEAR(b.max.z(), 8.0, kExactTol_m);  // floor + 3 trays + roof, 2 m apart
    EXPECT_NO_THROW(check_valid(column(), "column"));
}

TEST(DistillationColumn, EachTrayHasOneDowncomerOnAlternatingSides) {
    const RayCaster caster(column().mesh, column().surface_tags);
    const double in_downcomer = 1.5 - 0.5 * kConfig.downcomer_width_m;  // |x| inside the segment
    for (int k = 1; k <= 3; ++k) {
        const double side = k % 2 == 1 ? 1.0 : -1.0;
        const double z = 2.0 * k + 0.3;
        // Down through the downcomer opening of tray k onto the tray (or floor) below.
        const RayHit open = caster.cast({side * in_downcomer, 0, z}, -Eigen::Vector3d::UnitZ(), 9);
        ASSERT_TRUE(open.hit);
        EXPECT_NEAR(open.point.z(), k == 1 ? 0.0 : 2.0 * (k - 1) + kHalfTray_m, kExactTol_m);
        // The deck on the other side is solid.
        const RayHit deck = caster.cast({-side * in_downcomer, 0, z}, -Eigen::Vector3d::UnitZ(), 9);
        ASSERT_TRUE(deck.hit);
        EXPECT_NEAR(deck.point.z(), 2.0 * k + kHalfTray_m, kExactTol_m);
        EXPECT_EQ(deck.surface_tag, find_surface(column().metadata, "tray_" + std::to_string(k)));
        // Looking sideways just above the deck: the weir/downcomer plate on the chord.
        const RayHit weir =
            caster.cast({0, 0.1, 2.0 * k + 0.03}, side * Eigen::Vector3d::UnitX(), 3);
        ASSERT_TRUE(weir.hit);
        EXPECT_NEAR(weir.range_m, 1.5 - kConfig.downcomer_width_m - kHalfTray_m, kExactTol_m);
        EXPECT_EQ(weir.surface_tag,
                  find_surface(column().metadata, "downcomer_" + std::to_string(k)));
    }
}

TEST(DistillationColumn, WallFacesTheAxisAndIsClosedExceptForTheManway) {
    const World& w = column();
    const int shell = find_surface(w.metadata, "shell");
    for (std::size_t i = 0; i < w.mesh.num_triangles(); ++i) {
        if (w.surface_tags[i] != shell) continue;
        const Eigen::Vector3d& v = w.mesh.vertices[w.mesh.triangles[i][0]];
        EXPECT_LT(triangle_normal(w.mesh, i).head<2>().dot(v.head<2>()), 0.0);
    }
    const RayCaster caster(w.mesh, w.surface_tags);
    const double z = kConfig.manway_sill_m + 0.5 * kConfig.manway_height_m;
    for (int i = 0; i < 360; ++i) {
        const double a = 2.0 * std::numbers::pi * (i + 0.5) / 360;
        const RayHit hit = caster.cast({0, 0, z}, {std::cos(a), std::sin(a), 0}, 5.0);
        // The 0.6 m man-way at +y spans about ±0.2 rad (whole wall segments).
        const double off = std::abs(a - 0.5 * std::numbers::pi);
        if (off < 0.17) {
            EXPECT_FALSE(hit.hit) << a;
        } else if (off > 0.25) {
            EXPECT_TRUE(hit.hit) << a;
        }
    }
}

TEST(DistillationColumn, MetadataListsTraySpacesAndTheManway) {
    const auto& m = column().metadata;
    ASSERT_EQ(m.compartments.size(), 4u);
    EXPECT_NEAR(m.compartments[1].bounds.min.z(), 2.0, kExactTol_m);
    ASSERT_EQ(m.frames.size(), 3u);
    EXPECT_NEAR(m.frames[2].point.z(), 6.0, kExactTol_m);
    ASSERT_EQ(m.connections.size(), 1u);
    const Connection& manway = m.connections[0];
    EXPECT_EQ(manway.kind, ConnectionKind::Entry);
    EXPECT_NEAR(manway.normal.dot(Eigen::Vector3d::UnitY()), 1.0, 1e-12);
    EXPECT_NEAR(manway.width_m, 0.6, 0.1);  // rounded to whole wall segments
    EXPECT_EQ(m.landmarks.size(), 1u);
    testing::expect_defects_on_surfaces(column(), kOnSurfaceTol_m);
}

TEST(DistillationColumn, SameConfigGivesIdenticalWorldsAndBadValuesNameTheField) {
    testing::expect_identical(column(), build_distillation_column());
    DistillationColumnConfig c;
    c.manway_sill_m = 1.5;  // the man-way would reach the beams of tray 1
    try {
        build_distillation_column(c);
        ADD_FAILURE() << "no ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("distillation_column.manway_sill_m = 1.5"),
                  std::string::npos)
            << e.what();
    }
    c = {};
    c.downcomer_width_m = 2.0;
    EXPECT_THROW(build_distillation_column(c), ConfigError);
    c = {};
    c.num_trays = 0;
    EXPECT_EQ(build_distillation_column(c).metadata.compartments.size(), 1u);
}

}  // namespace
}  // namespace scantling::sim
