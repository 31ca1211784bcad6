// Missing returns as negative obstacles (detail/missing_returns.hpp).
#include "detail/missing_returns.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace scantling::perception::detail {
namespace {

bool expected(const Eigen::Vector3d& p_body, const ExpectedView& view,
              const Eigen::Isometry3d& T_sensor_body) {
    const Eigen::Vector3d d = T_sensor_body * p_body;
    const double range_m = d.norm();
    if (!(range_m > 0.0) || range_m > view.max_range_m) return false;
    const double polar = std::acos(std::clamp(d.x() / range_m, -1.0, 1.0));
    return polar <= view.half_fov_rad - view.margin_rad;
}

/// True when the straight line from `from` to `to` (x-y) crosses a positive cell of `before`.
bool shadowed(const SurfaceGrid& grid, const std::vector<SurfaceLabel>& before,
              const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
    const double step_m = 0.5 * grid.cell_size_m;
    const int n = static_cast<int>(std::ceil((to - from).norm() / step_m));
    const int side = grid.cells_per_side;
    for (int i = 1; i < n; ++i) {
        const Eigen::Vector2d p = from + (to - from) * (static_cast<double>(i) / n);
        const Eigen::Vector2d q = (p - grid.origin_xy_m) / grid.cell_size_m;
        const int ix = static_cast<int>(std::floor(q.x()));
        const int iy = static_cast<int>(std::floor(q.y()));
        if (ix < 0 || iy < 0 || ix >= side || iy >= side) continue;
        const SurfaceLabel l = before[static_cast<std::size_t>(iy * side + ix)];
        if (l == SurfaceLabel::kPositive) return true;
    }
    return false;
}

}  // namespace

void mark_missing_returns(SurfaceGrid& grid, const QuadricSurface& surface,
                          const ExpectedView& view) {
    const Eigen::Isometry3d T_sensor_body = view.T_body_sensor.inverse();
    const Eigen::Vector2d foot = view.T_body_sensor.translation().head<2>();
    const std::vector<SurfaceLabel> before = grid.cells;
    const int side = grid.cells_per_side;
    for (int iy = 0; iy < side; ++iy) {
        for (int ix = 0; ix < side; ++ix) {
            const std::size_t c = static_cast<std::size_t>(iy * side + ix);
            if (before[c] != SurfaceLabel::kUnknown) continue;
            const Eigen::Vector2d xy = grid.cell_centre(ix, iy);
            const Eigen::Vector3d p(xy.x(), xy.y(), surface.height_m(xy));
            if (!expected(p, view, T_sensor_body) || shadowed(grid, before, foot, xy)) continue;
            grid.cells[c] = SurfaceLabel::kNegative;
        }
    }
}

}  // namespace scantling::perception::detail
