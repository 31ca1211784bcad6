#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/mapping/cell_map.hpp>
#include <scantling/mapping/cell_thinning.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

namespace scantling::mapping {
namespace {

constexpr double kMaxVoxelsPerCellEdge = 1 << 20;  // voxel codes of 3 axes fit 64 bits

enum class KeyStatus { kOk, kNonFinite, kOutOfRange };

/// floor(v / size) as an int32 index; kOutOfRange when it does not fit.
KeyStatus axis_index(double v, double size_m, std::int32_t& out) {
    if (!std::isfinite(v)) return KeyStatus::kNonFinite;
    // Division, not multiplication by the inverse, so boundaries are exactly k · size.
    const double q = std::floor(v / size_m);
    if (q < std::numeric_limits<std::int32_t>::min() ||
        q > std::numeric_limits<std::int32_t>::max()) {
        return KeyStatus::kOutOfRange;
    }
    out = static_cast<std::int32_t>(q);
    return KeyStatus::kOk;
}

KeyStatus compute_key(const Eigen::Vector3d& p, const CellMapConfig& c, CellKey& key) {
    if (!p.allFinite()) return KeyStatus::kNonFinite;
    for (const KeyStatus s :
         {axis_index(p.x(), c.cell_size_xy_m, key.x), axis_index(p.y(), c.cell_size_xy_m, key.y),
          axis_index(p.z(), c.cell_size_z_m, key.z)}) {
        if (s != KeyStatus::kOk) return s;
    }
    return KeyStatus::kOk;
}

using config_checks::require_positive;

/// glibc malloc: 8-byte header, 16-byte granularity, 32-byte minimum chunk.
std::size_t heap_block_bytes(std::size_t bytes) {
    if (bytes == 0) return 0;
    return std::max<std::size_t>(32, (bytes + 8 + 15) / 16 * 16);
}

}  // namespace

void CellMapConfig::validate(std::string_view prefix) const {
    require_positive(cell_size_xy_m, prefix, "cell_size_xy_m");
    require_positive(cell_size_z_m, prefix, "cell_size_z_m");
    if (max_points_per_cell < 1) {
        throw ConfigError(
            fmt::format("{}.max_points_per_cell = {}, expected >= 1", prefix, max_points_per_cell));
    }
    require_positive(thinning_voxel_m, prefix, "thinning_voxel_m");
    const double smallest_cell_m = std::min(cell_size_xy_m, cell_size_z_m);
    const double largest_cell_m = std::max(cell_size_xy_m, cell_size_z_m);
    if (thinning_voxel_m > smallest_cell_m ||
        largest_cell_m / thinning_voxel_m > kMaxVoxelsPerCellEdge) {
        throw ConfigError(fmt::format(
            "{}.thinning_voxel_m = {}, expected <= the smaller cell size ({} m) and >= the "
            "larger cell size / 2^20 ({} m)",
            prefix, thinning_voxel_m, smallest_cell_m, largest_cell_m / kMaxVoxelsPerCellEdge));
    }
    if (hash != CellHashKind::kSourceXor && hash != CellHashKind::kMixed) {
        throw ConfigError(fmt::format("{}.hash = {}, expected source_xor or mixed", prefix,
                                      static_cast<int>(hash)));
    }
}

CellMap::CellMap(const CellMapConfig& config)
    : config_((config.validate(), config)), cells_(0, CellKeyHash{config.hash}) {}

CellKey CellMap::key_of(const Eigen::Vector3d& point) const {
    CellKey key;
    switch (compute_key(point, config_, key)) {
        case KeyStatus::kOk:
            return key;
        case KeyStatus::kNonFinite:
            throw InputError(fmt::format("cell_map: non-finite point ({}, {}, {})", point.x(),
                                         point.y(), point.z()));
        case KeyStatus::kOutOfRange:
            break;
    }
    throw InputError(fmt::format(
        "cell_map: point ({}, {}, {}) lies beyond the int32 cell index range for cells of {} m "
        "x {} m",
        point.x(), point.y(), point.z(), config_.cell_size_xy_m, config_.cell_size_z_m));
}

Eigen::Vector3d CellMap::cell_center(const CellKey& key) const {
    return {(key.x + 0.5) * config_.cell_size_xy_m, (key.y + 0.5) * config_.cell_size_xy_m,
            (key.z + 0.5) * config_.cell_size_z_m};
}

CellMap::Cell& CellMap::cell_for(const CellKey& key, InsertStats& stats) {
    auto [it, created] = cells_.try_emplace(key);
    stats.cells_created += created;
    return it->second;
}

InsertStats CellMap::insert(std::span<const Eigen::Vector3d> world_points) {
    InsertStats stats;
    ++insert_count_;
    std::vector<Cell*> modified;
    // Consecutive points of a sweep often fall into the same cell: skip the table for them.
    CellKey last_key;
    Cell* last_cell = nullptr;
    for (const Eigen::Vector3d& p : world_points) {
        CellKey key;
        const KeyStatus status = compute_key(p, config_, key);
        if (status != KeyStatus::kOk) {
            ++(status == KeyStatus::kNonFinite ? stats.non_finite_skipped
                                               : stats.out_of_range_skipped);
            continue;
        }
        if (last_cell == nullptr || !(key == last_key)) {
            last_cell = &cell_for(key, stats);
            last_key = key;
        }
        Cell& cell = *last_cell;
        if (cell.touched_in != insert_count_) {
            cell.touched_in = insert_count_;
            modified.push_back(&cell);
        }
        cell.offsets.push_back((p - cell_center(key)).cast<float>());
        ++stats.points_added;
    }
    num_points_ += stats.points_added;
    stats.cells_modified = modified.size();
    // Cells are independent and each is thinned from its own points in a fixed order, so the
    // order of `modified` (input order of first touch) does not affect the result.
    for (Cell* cell : modified) {
        if (cell->offsets.size() <= config_.max_points_per_cell) continue;
        const std::size_t before = cell->offsets.size();
        thin(*cell);
        num_points_ -= before - cell->offsets.size();
        ++stats.cells_thinned;
    }
    return stats;
}

void CellMap::thin(Cell& cell) const {
    const Eigen::Vector3d size_m(config_.cell_size_xy_m, config_.cell_size_xy_m,
                                 config_.cell_size_z_m);
    thin_cell(cell.offsets, size_m, config_.thinning_voxel_m, config_.max_points_per_cell);
}

void CellMap::append_cell(const CellKey& key, const Cell& cell,
                          std::vector<Eigen::Vector3d>& out) const {
    const Eigen::Vector3d center = cell_center(key);
    for (const Eigen::Vector3f& o : cell.offsets) out.push_back(center + o.cast<double>());
}

std::size_t CellMap::num_points_in(const CellKey& key) const {
    const auto it = cells_.find(key);
    return it == cells_.end() ? 0 : it->second.offsets.size();
}

std::vector<CellKey> CellMap::keys() const {
    std::vector<CellKey> out;
    out.reserve(cells_.size());
    for (const auto& entry : cells_) out.push_back(entry.first);
    std::sort(out.begin(), out.end());
    return out;
}

void CellMap::all_points(std::vector<Eigen::Vector3d>& out) const {
    out.reserve(out.size() + num_points_);
    for (const CellKey& key : keys()) append_cell(key, cells_.find(key)->second, out);
}

std::size_t CellMap::memory_bytes() const {
    // libstdc++ node: next pointer + value; the hash code is not cached because CellKeyHash is
    // noexcept (libstdc++ recomputes it instead).
    const std::size_t node_bytes = sizeof(void*) + sizeof(Table::value_type);
    std::size_t bytes = sizeof(*this) + heap_block_bytes(cells_.bucket_count() * sizeof(void*));
    bytes += cells_.size() * heap_block_bytes(node_bytes);
    for (const auto& entry : cells_) {
        bytes += heap_block_bytes(entry.second.offsets.capacity() * sizeof(Eigen::Vector3f));
    }
    return bytes;
}

HashStats CellMap::hash_stats() const {
    const std::vector<CellKey> all = keys();
    HashStats stats = hash_value_stats(all, config_.hash);
    stats.bucket_count = cells_.bucket_count();
    stats.load_factor = cells_.load_factor();
    double sum_sq = 0.0;
    for (std::size_t b = 0; b < cells_.bucket_count(); ++b) {
        const std::size_t n = cells_.bucket_size(b);
        stats.empty_buckets += n == 0;
        stats.max_bucket_occupancy = std::max(stats.max_bucket_occupancy, n);
        sum_sq += static_cast<double>(n) * static_cast<double>(n);
    }
    const std::size_t occupied = stats.bucket_count - stats.empty_buckets;
    if (occupied > 0) {
        stats.mean_bucket_occupancy = static_cast<double>(all.size()) / occupied;
        stats.mean_chain_seen = sum_sq / static_cast<double>(all.size());
    }
    return stats;
}

void CellMap::clear() {
    cells_.clear();
    num_points_ = 0;
}

}  // namespace scantling::mapping
