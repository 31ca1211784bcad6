#pragma once
// Cells where the LiDAR should have seen the surface and saw nothing (surface_obstacles.hpp,
// ExpectedView).
#include <scantling/perception/surface_obstacles.hpp>

namespace scantling::perception::detail {

/// Marks kNegative every kUnknown cell of `grid` that `view` expects on `surface` and that no
/// positive cell shadows from the sensor's foot. O(cells · cells along a shadow ray).
void mark_missing_returns(SurfaceGrid& grid, const QuadricSurface& surface,
                          const ExpectedView& view);

}  // namespace scantling::perception::detail
