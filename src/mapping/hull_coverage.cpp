#include <scantling/mapping/hull_coverage.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::mapping {
namespace {

// How far the surface axes may be from unit length and orthogonal (unit vectors).
constexpr double kAxisTolerance = 1e-6;
// An extent a hair over a multiple of the cell (5.000000001 / 0.2) adds no cell.
constexpr double kRelativeSlack = 1e-9;

void require_unit(const Eigen::Vector3d& axis, std::string_view prefix, std::string_view field) {
    if (!axis.allFinite() || std::abs(axis.norm() - 1.0) > kAxisTolerance) {
        throw ConfigError(fmt::format("{}.{} = ({}, {}, {}), expected a finite unit vector", prefix,
                                      field, axis.x(), axis.y(), axis.z()));
    }
}

}  // namespace

void InspectedSurface::validate(std::string_view prefix) const {
    using namespace config_checks;
    if (!origin_world_m.allFinite()) {
        throw ConfigError(fmt::format("{}.origin_world_m = ({}, {}, {}), expected finite", prefix,
                                      origin_world_m.x(), origin_world_m.y(), origin_world_m.z()));
    }
    require_unit(axis_u_world, prefix, "axis_u_world");
    require_unit(axis_v_world, prefix, "axis_v_world");
    const double dot = axis_u_world.dot(axis_v_world);
    require(std::abs(dot) <= kAxisTolerance, prefix, "axis_v_world·axis_u_world", dot,
            "0 (orthogonal axes)");
    require_positive(extent_u_m, prefix, "extent_u_m");
    require_positive(extent_v_m, prefix, "extent_v_m");
    require_non_negative(tolerance_m, prefix, "tolerance_m");
}

void HullCoverageConfig::validate(std::string_view prefix) const {
    config_checks::require_non_negative(min_hole_area_m2, prefix, "min_hole_area_m2");
    config_checks::require_count_at_least(max_cells, 1, prefix, "max_cells");
}

namespace {

/// The rectangle's cells; the last column and row are clipped to the extents.
struct SurfaceGrid {
    double cell_m = 0.0;
    double extent_u_m = 0.0, extent_v_m = 0.0;
    std::size_t nu = 0, nv = 0;

    std::size_t index(std::size_t iu, std::size_t iv) const { return iv * nu + iu; }
    double u0(std::size_t iu) const { return static_cast<double>(iu) * cell_m; }
    double v0(std::size_t iv) const { return static_cast<double>(iv) * cell_m; }
    double u1(std::size_t iu) const { return std::min(u0(iu) + cell_m, extent_u_m); }
    double v1(std::size_t iv) const { return std::min(v0(iv) + cell_m, extent_v_m); }
    double area_m2(std::size_t iu, std::size_t iv) const {
        return (u1(iu) - u0(iu)) * (v1(iv) - v0(iv));
    }
};

double cells_along(double extent_m, double cell_m) {
    return std::max(1.0, std::ceil(extent_m / cell_m * (1.0 - kRelativeSlack)));
}

SurfaceGrid make_grid(const InspectedSurface& surface, double cell_m,
                      const HullCoverageConfig& config) {
    const double nu = cells_along(surface.extent_u_m, cell_m);
    const double nv = cells_along(surface.extent_v_m, cell_m);
    if (nu * nv > static_cast<double>(config.max_cells)) {  // before allocating
        throw ConfigError(
            fmt::format("surface: {} x {} m at cells of {} m needs {} cells, expected at most "
                        "coverage.max_cells = {} (a unit mistake?)",
                        surface.extent_u_m, surface.extent_v_m, cell_m, nu * nv, config.max_cells));
    }
    return {cell_m, surface.extent_u_m, surface.extent_v_m, static_cast<std::size_t>(nu),
            static_cast<std::size_t>(nv)};
}

/// Marks the cells whose centres lie within half a face diagonal of (u, v), which always
/// includes the cell (u, v) falls in: on a surface aligned with the voxels that is the only one;
/// on a tilted or offset one the means fall anywhere in their cells, and the disc closes the gaps
/// one mean per cell would leave.
void cover_disc(double u, double v, const SurfaceGrid& grid, std::vector<char>& covered) {
    const double s = grid.cell_m;
    const double r = s * std::numbers::sqrt2 / 2.0 * (1.0 + 1e-9);
    const auto first = [&](double x) { return static_cast<long>(std::floor((x - r) / s - 0.5)); };
    for (long iv = std::max(first(v), 0L); iv < static_cast<long>(grid.nv); ++iv) {
        const double dv = (static_cast<double>(iv) + 0.5) * s - v;
        if (dv > r) break;
        for (long iu = std::max(first(u), 0L); iu < static_cast<long>(grid.nu); ++iu) {
            const double du = (static_cast<double>(iu) + 0.5) * s - u;
            if (du > r) break;
            if (du * du + dv * dv <= r * r) {
                covered[grid.index(static_cast<std::size_t>(iu), static_cast<std::size_t>(iv))] = 1;
            }
        }
    }
}

std::vector<char> covered_mask(const SonarInspectionMap& map, const InspectedSurface& surface,
                               const SurfaceGrid& grid) {
    std::vector<char> covered(grid.nu * grid.nv, 0);
    const Eigen::Vector3d normal = surface.axis_u_world.cross(surface.axis_v_world);
    for (const SonarVoxel& voxel : map.voxels()) {
        const Eigen::Vector3d d = voxel.mean_world_m - surface.origin_world_m;
        const double u = d.dot(surface.axis_u_world);
        const double v = d.dot(surface.axis_v_world);
        if (std::abs(d.dot(normal)) > surface.tolerance_m || u < 0.0 || v < 0.0 ||
            u > grid.extent_u_m || v > grid.extent_v_m) {
            continue;
        }
        // An extent a hair over the last cell's edge (kRelativeSlack) belongs to that cell.
        const double n_u = static_cast<double>(grid.nu), n_v = static_cast<double>(grid.nv);
        cover_disc(std::min(u, n_u * grid.cell_m), std::min(v, n_v * grid.cell_m), grid, covered);
    }
    return covered;
}

/// Breadth-first over the 4-connected uncovered cells from `start`; marks them in `seen`.
CoverageHole flood_hole(const SurfaceGrid& grid, const std::vector<char>& covered,
                        std::vector<char>& seen, SurfaceCell start) {
    CoverageHole hole;
    hole.box_min_plane_m = {grid.extent_u_m, grid.extent_v_m};
    std::vector<SurfaceCell> queue{start};
    seen[grid.index(start.iu, start.iv)] = 1;
    const auto visit = [&](std::size_t iu, std::size_t iv) {
        const std::size_t i = grid.index(iu, iv);
        if (covered[i] || seen[i]) return;
        seen[i] = 1;
        queue.push_back({iu, iv});
    };
    for (std::size_t q = 0; q < queue.size(); ++q) {
        const auto [iu, iv] = queue[q];
        const double a = grid.area_m2(iu, iv);
        hole.area_m2 += a;
        hole.centroid_plane_m +=
            a * Eigen::Vector2d(grid.u0(iu) + grid.u1(iu), grid.v0(iv) + grid.v1(iv)) / 2.0;
        hole.box_min_plane_m =
            hole.box_min_plane_m.cwiseMin(Eigen::Vector2d(grid.u0(iu), grid.v0(iv)));
        hole.box_max_plane_m =
            hole.box_max_plane_m.cwiseMax(Eigen::Vector2d(grid.u1(iu), grid.v1(iv)));
        if (iu > 0) visit(iu - 1, iv);
        if (iu + 1 < grid.nu) visit(iu + 1, iv);
        if (iv > 0) visit(iu, iv - 1);
        if (iv + 1 < grid.nv) visit(iu, iv + 1);
    }
    hole.num_cells = queue.size();
    hole.centroid_plane_m /= hole.area_m2;
    return hole;
}

}  // namespace

HullCoverage coverage_of(const SonarInspectionMap& map, const InspectedSurface& surface,
                         const HullCoverageConfig& config) {
    surface.validate("surface");
    config.validate("coverage");
    const SurfaceGrid grid = make_grid(surface, map.config().voxel_size_m, config);
    const std::vector<char> covered = covered_mask(map, surface, grid);
    HullCoverage result;
    result.cell_size_m = grid.cell_m;
    result.num_cells_u = grid.nu;
    result.num_cells_v = grid.nv;
    result.total_area_m2 = surface.extent_u_m * surface.extent_v_m;
    std::vector<char> seen(covered.size(), 0);
    for (std::size_t iv = 0; iv < grid.nv; ++iv) {
        for (std::size_t iu = 0; iu < grid.nu; ++iu) {
            const std::size_t i = grid.index(iu, iv);
            if (covered[i]) {
                result.covered_area_m2 += grid.area_m2(iu, iv);
                continue;
            }
            result.uncovered_cells.push_back({iu, iv});
            if (seen[i]) continue;
            CoverageHole hole = flood_hole(grid, covered, seen, {iu, iv});
            if (hole.area_m2 < config.min_hole_area_m2) {
                ++result.num_ignored_holes;
                continue;
            }
            const Eigen::Vector2d c = hole.centroid_plane_m;
            hole.centroid_world_m = surface.origin_world_m + c.x() * surface.axis_u_world +
                                    c.y() * surface.axis_v_world;
            result.holes.push_back(hole);
        }
    }
    result.covered_fraction = result.covered_area_m2 / result.total_area_m2;
    // Stable: equal areas keep the row-major order of their first cell.
    std::stable_sort(
        result.holes.begin(), result.holes.end(),
        [](const CoverageHole& a, const CoverageHole& b) { return a.area_m2 > b.area_m2; });
    return result;
}

}  // namespace scantling::mapping
