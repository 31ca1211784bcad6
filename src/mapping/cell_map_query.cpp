// CellMap::gather_near: the adaptive local map's cell retrieval (SPEC §2, D4.2 §II.2).
#include <scantling/core/error.hpp>
#include <scantling/mapping/cell_map.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

namespace scantling::mapping {
namespace {

/// Cells whose centre lies within `radius_m` of the centre of cell `center`. The distance
/// between two centres is |Δkey ⊙ size|, computed in the same way for every caller.
struct Ball {
    CellKey center;
    double radius_sq_m2 = 0.0;
    double size_xy_m = 0.0;
    double size_z_m = 0.0;

    bool contains(std::int64_t dx, std::int64_t dy, std::int64_t dz) const {
        const double x = static_cast<double>(dx) * size_xy_m;
        const double y = static_cast<double>(dy) * size_xy_m;
        const double z = static_cast<double>(dz) * size_z_m;
        return x * x + y * y + z * z <= radius_sq_m2;
    }
    bool contains(const CellKey& key) const {
        return contains(std::int64_t{key.x} - center.x, std::int64_t{key.y} - center.y,
                        std::int64_t{key.z} - center.z);
    }
};

bool fits_int32(std::int64_t v) {
    return v >= std::numeric_limits<std::int32_t>::min() &&
           v <= std::numeric_limits<std::int32_t>::max();
}

/// Probes every key of the ball's bounding box that lies in the ball, in lexicographic order.
template <typename Table, typename Visit>
void visit_by_probing(const Table& cells, const Ball& ball, std::int64_t nxy, std::int64_t nz,
                      Visit&& visit) {
    for (std::int64_t dx = -nxy; dx <= nxy; ++dx) {
        for (std::int64_t dy = -nxy; dy <= nxy; ++dy) {
            for (std::int64_t dz = -nz; dz <= nz; ++dz) {
                const std::int64_t x = ball.center.x + dx;
                const std::int64_t y = ball.center.y + dy;
                const std::int64_t z = ball.center.z + dz;
                if (!ball.contains(dx, dy, dz) || !fits_int32(x) || !fits_int32(y) ||
                    !fits_int32(z)) {
                    continue;
                }
                const CellKey key{static_cast<std::int32_t>(x), static_cast<std::int32_t>(y),
                                  static_cast<std::int32_t>(z)};
                const auto it = cells.find(key);
                if (it != cells.end()) visit(it->first, it->second);
            }
        }
    }
}

/// Scans the whole table, then visits the cells in the ball sorted by key: cheaper than
/// probing when the ball holds more keys than the map has cells.
template <typename Table, typename Visit>
void visit_by_scanning(const Table& cells, const Ball& ball, Visit&& visit) {
    std::vector<const typename Table::value_type*> inside;
    for (const auto& entry : cells) {
        if (ball.contains(entry.first)) inside.push_back(&entry);
    }
    std::sort(inside.begin(), inside.end(),
              [](const auto* a, const auto* b) { return a->first < b->first; });
    for (const auto* entry : inside) visit(entry->first, entry->second);
}

}  // namespace

void CellMap::gather_near(const Eigen::Vector3d& position, double radius_m,
                          std::vector<Eigen::Vector3d>& out) const {
    if (!(radius_m >= 0.0) || !std::isfinite(radius_m)) {
        throw InputError(
            fmt::format("cell_map.gather_near: radius_m = {}, expected finite >= 0", radius_m));
    }
    const Ball ball{key_of(position), radius_m * radius_m, config_.cell_size_xy_m,
                    config_.cell_size_z_m};
    const double nxy = std::floor(radius_m / config_.cell_size_xy_m);
    const double nz = std::floor(radius_m / config_.cell_size_z_m);
    const double box_keys = (2.0 * nxy + 1.0) * (2.0 * nxy + 1.0) * (2.0 * nz + 1.0);
    const auto append = [&](const CellKey& key, const Cell& cell) { append_cell(key, cell, out); };
    if (box_keys > static_cast<double>(cells_.size())) {
        visit_by_scanning(cells_, ball, append);
    } else {
        // box_keys <= num_cells here, so both half-widths fit int64 comfortably.
        visit_by_probing(cells_, ball, static_cast<std::int64_t>(nxy),
                         static_cast<std::int64_t>(nz), append);
    }
}

}  // namespace scantling::mapping
