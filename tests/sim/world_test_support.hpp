#pragma once
// Helpers shared by the world tests.

#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/world.hpp>

#include <gtest/gtest.h>

#include <string_view>

namespace scantling::sim::testing {

/// Total area of the triangles of surface `name`, m².
inline double area_of(const World& world, std::string_view name) {
    const int tag = find_surface(world.metadata, name);
    double area = 0.0;
    for (std::size_t i = 0; i < world.mesh.num_triangles(); ++i) {
        if (world.surface_tags[i] == tag) area += triangle_area(world.mesh, i);
    }
    return area;
}

/// Signed volume enclosed by the triangles of surface `name` (> 0 when they face outward).
inline double volume_of(const World& world, std::string_view name) {
    const int tag = find_surface(world.metadata, name);
    double six_volume = 0.0;
    for (std::size_t i = 0; i < world.mesh.num_triangles(); ++i) {
        if (world.surface_tags[i] != tag) continue;
        const auto& t = world.mesh.triangles[i];
        six_volume += world.mesh.vertices[t[0]].dot(
            world.mesh.vertices[t[1]].cross(world.mesh.vertices[t[2]]));
    }
    return six_volume / 6.0;
}

/// Worlds built twice from one config must agree bit for bit.
inline void expect_identical(const World& a, const World& b) {
    ASSERT_EQ(a.mesh.num_vertices(), b.mesh.num_vertices());
    ASSERT_EQ(a.mesh.num_triangles(), b.mesh.num_triangles());
    for (std::size_t i = 0; i < a.mesh.num_vertices(); ++i) {
        ASSERT_EQ(a.mesh.vertices[i], b.mesh.vertices[i]) << "vertex " << i;
    }
    for (std::size_t i = 0; i < a.mesh.num_triangles(); ++i) {
        ASSERT_EQ(a.mesh.triangles[i], b.mesh.triangles[i]) << "triangle " << i;
    }
    EXPECT_EQ(a.surface_tags, b.surface_tags);
    ASSERT_EQ(a.metadata.defects.size(), b.metadata.defects.size());
    for (std::size_t i = 0; i < a.metadata.defects.size(); ++i) {
        EXPECT_EQ(a.metadata.defects[i].centre, b.metadata.defects[i].centre);
        EXPECT_EQ(a.metadata.defects[i].radius_m, b.metadata.defects[i].radius_m);
    }
    EXPECT_EQ(a.metadata.landmarks.size(), b.metadata.landmarks.size());
}

/// Every defect lies on a triangle of its own surface and is seen from 5 cm in front.
inline void expect_defects_on_surfaces(const World& world, double tolerance_m) {
    const RayCaster caster(world.mesh, world.surface_tags);
    for (const Defect& d : world.metadata.defects) {
        const MeshClosestPoint closest = closest_point_on_mesh(world.mesh, d.centre);
        EXPECT_LT(closest.distance_m, tolerance_m) << "defect " << d.id;
        const RayHit hit = caster.cast(d.centre + 0.05 * d.normal, -d.normal, 0.1);
        ASSERT_TRUE(hit.hit) << "defect " << d.id;
        EXPECT_NEAR(hit.range_m, 0.05, tolerance_m) << "defect " << d.id;
        EXPECT_EQ(defect_at(world.metadata, hit.point, d.surface_tag), d.id);
        EXPECT_NEAR(d.normal.norm(), 1.0, 1e-12);
        EXPECT_NEAR(d.normal.dot(d.direction), 0.0, 1e-12);
    }
}

}  // namespace scantling::sim::testing
