// The reachable free volume (reachable_volume.hpp).
#include "reachable_volume.hpp"

#include <array>
#include <cmath>
#include <deque>

namespace scantling::mission::detail {
namespace {

struct Grid {
    Eigen::Vector3d origin;
    double resolution_m;
    Eigen::Vector3i dims;
    std::vector<std::uint8_t> blocked;

    std::size_t index(const Eigen::Vector3i& v) const {
        return (static_cast<std::size_t>(v.z()) * dims.y() + v.y()) * dims.x() + v.x();
    }
    bool inside(const Eigen::Vector3i& v) const {
        return (v.array() >= 0).all() && (v.array() < dims.array()).all();
    }
    Eigen::Vector3i voxel_of(const Eigen::Vector3d& p) const {
        return ((p - origin) / resolution_m).array().floor().cast<int>();
    }
    Eigen::Vector3d centre(const Eigen::Vector3i& v) const {
        return origin + (v.cast<double>().array() + 0.5).matrix() * resolution_m;
    }
};

/// Marks the voxel of every surface the line of voxel centres `v0` + t·axis crosses.
void mark_line(const sim::RayCaster& caster, Grid& grid, const Eigen::Vector3i& v0, int axis) {
    constexpr double kStep_m = 1e-4;  // past a hit, so the next cast finds the next surface
    Eigen::Vector3d direction = Eigen::Vector3d::Zero();
    direction[axis] = 1.0;
    Eigen::Vector3d origin = grid.centre(v0);
    origin[axis] = grid.origin[axis];
    const double length = grid.dims[axis] * grid.resolution_m;
    double travelled = 0.0;
    while (travelled < length) {
        const sim::RayHit hit = caster.cast(origin, direction, length - travelled + kStep_m);
        if (!hit.hit) return;
        const Eigen::Vector3i v = grid.voxel_of(hit.point);
        if (grid.inside(v)) grid.blocked[grid.index(v)] = 1;
        origin = hit.point + kStep_m * direction;
        travelled += hit.range_m + kStep_m;
    }
}

void mark_surfaces(const sim::RayCaster& caster, Grid& grid) {
    for (int axis = 0; axis < 3; ++axis) {
        const int a = (axis + 1) % 3;
        const int b = (axis + 2) % 3;
        for (int i = 0; i < grid.dims[a]; ++i) {
            for (int j = 0; j < grid.dims[b]; ++j) {
                Eigen::Vector3i v = Eigen::Vector3i::Zero();
                v[a] = i;
                v[b] = j;
                mark_line(caster, grid, v, axis);
            }
        }
    }
}

std::vector<Eigen::Vector3d> flood(const Grid& grid, const Eigen::Vector3i& start) {
    std::vector<Eigen::Vector3d> centres;
    if (!grid.inside(start) || grid.blocked[grid.index(start)]) return centres;
    std::vector<std::uint8_t> seen(grid.blocked.size(), 0);
    std::deque<Eigen::Vector3i> queue{start};
    seen[grid.index(start)] = 1;
    static const std::array<Eigen::Vector3i, 6> kSteps{
        Eigen::Vector3i(1, 0, 0),  Eigen::Vector3i(-1, 0, 0), Eigen::Vector3i(0, 1, 0),
        Eigen::Vector3i(0, -1, 0), Eigen::Vector3i(0, 0, 1),  Eigen::Vector3i(0, 0, -1)};
    while (!queue.empty()) {
        const Eigen::Vector3i v = queue.front();
        queue.pop_front();
        centres.push_back(grid.centre(v));
        for (const Eigen::Vector3i& step : kSteps) {
            const Eigen::Vector3i n = v + step;
            if (!grid.inside(n) || seen[grid.index(n)] || grid.blocked[grid.index(n)]) continue;
            seen[grid.index(n)] = 1;
            queue.push_back(n);
        }
    }
    return centres;
}

}  // namespace

ReachableVolume reachable_free_volume(const sim::RayCaster& caster,
                                      const Eigen::AlignedBox3d& bounds_world, double resolution_m,
                                      const Eigen::Vector3d& start_world) {
    Grid grid{.origin = bounds_world.min(),
              .resolution_m = resolution_m,
              .dims = (bounds_world.sizes() / resolution_m).array().round().cast<int>().max(1),
              .blocked = {}};
    grid.blocked.assign(static_cast<std::size_t>(grid.dims.prod()), 0);
    mark_surfaces(caster, grid);
    return {.resolution_m = resolution_m, .centres_world = flood(grid, grid.voxel_of(start_world))};
}

}  // namespace scantling::mission::detail
