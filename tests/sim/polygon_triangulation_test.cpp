// Private helper of the simulator, tested directly for shapes the worlds do not cover yet.
#include "../../src/sim/detail/polygon_triangulation.hpp"

#include <scantling/core/error.hpp>

#include <gtest/gtest.h>

#include <set>

namespace scantling::sim::detail {
namespace {

constexpr double kAreaTol = 1e-12;

using V2 = Eigen::Vector2d;

// Checks every triangle is counter-clockwise and returns the total area; the caller compares
// it with the polygon's area, so overlaps or gaps show up.
double checked_area(const std::vector<std::array<int, 3>>& triangles, const Loop2& points,
                    std::size_t expected_vertices) {
    double area = 0.0;
    std::set<int> used;
    for (const auto& t : triangles) {
        const double a = signed_area(Loop2{points[t[0]], points[t[1]], points[t[2]]});
        EXPECT_GT(a, 0.0);
        area += a;
        used.insert(t.begin(), t.end());
    }
    EXPECT_EQ(used.size(), expected_vertices);  // no input vertex is dropped
    return area;
}

Loop2 concat(const Loop2& outer, const std::vector<Loop2>& holes) {
    Loop2 all = outer;
    for (const auto& h : holes) all.insert(all.end(), h.begin(), h.end());
    return all;
}

TEST(PolygonTriangulation, NonConvexOutlineIsCoveredExactly) {
    const Loop2 l_shape{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    const auto triangles = triangulate_polygon(l_shape);
    EXPECT_EQ(triangles.size(), 4u);
    EXPECT_NEAR(checked_area(triangles, l_shape, 6), 3.0, kAreaTol);
}

TEST(PolygonTriangulation, HolesAreCutOutWhateverTheirOrientation) {
    const Loop2 outer{{0, 0}, {0, 3}, {6, 3}, {6, 0}};  // clockwise input
    const std::vector<Loop2> holes{{{1, 1}, {2, 1}, {2, 2}, {1, 2}},
                                   {{4, 1}, {4, 2}, {5.5, 2}, {5.5, 1}},
                                   {{3, 0.5}, {3.5, 0.5}, {3.25, 2.5}}};
    const auto triangles = triangulate_polygon(outer, holes);
    EXPECT_NEAR(checked_area(triangles, concat(outer, holes), 15), 18.0 - 1.0 - 1.5 - 0.5,
                kAreaTol);
}

TEST(PolygonTriangulation, CollinearOutlineVerticesAreKept) {
    const Loop2 square{{0, 0}, {1, 0}, {2, 0}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
    const std::vector<Loop2> hole{{{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}}};
    const auto triangles = triangulate_polygon(square, hole);
    EXPECT_NEAR(checked_area(triangles, concat(square, hole), 11), 3.0, kAreaTol);
}

TEST(PolygonTriangulation, RejectsDegenerateLoops) {
    EXPECT_THROW(triangulate_polygon(Loop2{{0, 0}, {1, 0}}), InputError);
    EXPECT_THROW(triangulate_polygon(Loop2{{0, 0}, {1, 0}, {0, 1}}, {Loop2{{0.1, 0.1}}}),
                 InputError);
}

}  // namespace
}  // namespace scantling::sim::detail
