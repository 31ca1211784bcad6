#pragma once
// Ear-clipping triangulation of a simple polygon with holes (private to the simulator).

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

namespace scantling::sim::detail {

using Loop2 = std::vector<Eigen::Vector2d>;

/// Signed area of a closed loop (> 0 counter-clockwise).
double signed_area(std::span<const Eigen::Vector2d> loop);

/// Triangulates the polygon `outer` minus `holes` (each a simple loop, either orientation;
/// holes strictly inside `outer` and disjoint). Returns counter-clockwise triangles indexing
/// the concatenation outer ++ holes[0] ++ holes[1] ++ ...; every input vertex is used and no
/// vertex is added, so edges shared with neighbouring geometry stay watertight.
/// Holes are joined to the outline by bridge edges, then ears are clipped in a fixed order:
/// deterministic, O(n²) for n vertices. Throws InputError when no ear can be found (the
/// polygon self-intersects or a hole crosses the outline).
std::vector<std::array<int, 3>> triangulate_polygon(std::span<const Eigen::Vector2d> outer,
                                                    const std::vector<Loop2>& holes = {});

}  // namespace scantling::sim::detail
