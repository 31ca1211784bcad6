#pragma once
// Shape of the parametric hull section (world_hull.hpp), shared by its builder and the
// appendages welded onto it (private to the simulator).

#include <scantling/sim/world_hull.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace scantling::sim::detail {

// Number of equal steps of at most max_step_m covering length_m (at least one).
inline int steps(double length_m, double max_step_m) {
    return std::max(1, static_cast<int>(std::ceil(length_m / max_step_m - 1e-9)));
}

// s², s = 2x/L − 1: the longitudinal shape factor of the side curvature and the sheer.
inline double s_squared(const ShipHullConfig& c, double x) {
    const double s = 2.0 * x / c.length_m - 1.0;
    return s * s;
}

// y of the +y side shell at (x, z): the swept side is planar between stations, so the
// inward offset is interpolated linearly between them.
inline double side_y(const ShipHullConfig& c, double x, double z) {
    const int n = steps(c.length_m, c.station_spacing_m);
    const double dx = c.length_m / n;
    const int i = std::min(n - 1, static_cast<int>(std::floor(x / dx)));
    const double x0 = i * dx, x1 = (i + 1) * dx, t = (x - x0) / dx;
    const double inward =
        c.side_curvature_m * ((1.0 - t) * s_squared(c, x0) + t * s_squared(c, x1));
    const double side_z0 = c.keel_height_m + c.bilge_radius_m;
    return c.half_breadth_m - inward + std::tan(c.flare_rad) * (z - side_z0);
}

}  // namespace scantling::sim::detail
