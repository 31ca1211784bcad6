#pragma once
// Small analytic triangle meshes for the surface tests (core) and the crawler tests (sim).

#include <scantling/core/triangle_mesh.hpp>

#include <cmath>
#include <numbers>

namespace scantling::testing {

/// Flat square grid mesh in z = 0, [-half, half]², `cells` × `cells` squares, normal +z.
inline TriangleMesh grid_plate(double half_m, int cells) {
    TriangleMesh mesh;
    for (int j = 0; j <= cells; ++j) {
        for (int i = 0; i <= cells; ++i) {
            mesh.vertices.emplace_back(-half_m + 2.0 * half_m * i / cells,
                                       -half_m + 2.0 * half_m * j / cells, 0.0);
        }
    }
    const auto id = [cells](int i, int j) { return j * (cells + 1) + i; };
    for (int j = 0; j < cells; ++j) {
        for (int i = 0; i < cells; ++i) {
            mesh.triangles.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
            mesh.triangles.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    }
    return mesh;
}

/// Open vertical cylinder (axis z, z in [0, height]), `segments` facets around, `rings`
/// bands; triangles face outward.
inline TriangleMesh open_cylinder(double radius_m, double height_m, int segments, int rings) {
    TriangleMesh mesh;
    for (int k = 0; k <= rings; ++k) {
        for (int i = 0; i < segments; ++i) {
            const double a = 2.0 * std::numbers::pi * i / segments;
            mesh.vertices.emplace_back(radius_m * std::cos(a), radius_m * std::sin(a),
                                       height_m * k / rings);
        }
    }
    const auto id = [segments](int i, int k) { return k * segments + (i % segments); };
    for (int k = 0; k < rings; ++k) {
        for (int i = 0; i < segments; ++i) {
            mesh.triangles.emplace_back(id(i, k), id(i + 1, k), id(i + 1, k + 1));
            mesh.triangles.emplace_back(id(i, k), id(i + 1, k + 1), id(i, k + 1));
        }
    }
    return mesh;
}

}  // namespace scantling::testing
