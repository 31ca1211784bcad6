// The LiODOM hashed cell map (SPEC §2, issue 4 item 1 "map"): the source's xor hash against a
// well-mixing one as the real std::unordered_map hash, on maps from real sweeps and simulated
// worlds. Prints hash-spread and bucket statistics per map, then times lookups of existing and
// missing cells, gather_near (the local-map retrieval) and building the map. Paired names
// "<case>/ours/1thr" (kMixed) and "<case>/source_xor/1thr" give the ratio table.
// Also: per-cell voxel thinning through core::voxel_downsample (ours) against a per-cell
// std::sort routine.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <string>
#include <utility>

#include <fmt/format.h>

#include <scantling/core/random.hpp>
#include <scantling/mapping/cell_thinning.hpp>

#include "bench_support.hpp"
#include "mapping_bench.hpp"

namespace scantling::bench {
namespace {

using mapping::CellHashKind;
using mapping::CellKey;
using mapping::CellMap;

// Small batches: with the source's hash one lookup in the town walks ~300 nodes (~30 us).
constexpr std::size_t kLookups = 10000;  // keys per timed batch
constexpr std::size_t kGathers = 5;      // gather_near positions per timed batch
constexpr std::uint64_t kSeed = 2024;

struct BuiltMap {
    const MapInput* input = nullptr;
    CellHashKind kind = CellHashKind::kMixed;
    CellMap map;
    std::vector<CellKey> present;            ///< existing keys, random order with repeats
    std::vector<CellKey> missing;            ///< absent keys inside the map's key box (+-2 cells)
    std::vector<Eigen::Vector3d> positions;  ///< centres of random existing cells
};

std::deque<MapInput>& inputs() {
    static std::deque<MapInput> in;
    return in;
}

std::deque<BuiltMap>& built() {
    static std::deque<BuiltMap> maps;
    return maps;
}

std::string kind_label(CellHashKind kind) {
    return kind == CellHashKind::kMixed ? "ours" : "source_xor";
}

CellMap build_map(const MapInput& in, CellHashKind kind) {
    mapping::CellMapConfig config = in.config;
    config.hash = kind;
    CellMap map(config);
    for (const auto& batch : in.batches) map.insert(batch);
    return map;
}

void sample_queries(BuiltMap& b) {
    const std::vector<CellKey> keys = b.map.keys();
    Rng rng(kSeed);
    CellKey lo = keys.front(), hi = keys.front();
    for (const CellKey& k : keys) {
        lo = {std::min(lo.x, k.x), std::min(lo.y, k.y), std::min(lo.z, k.z)};
        hi = {std::max(hi.x, k.x), std::max(hi.y, k.y), std::max(hi.z, k.z)};
    }
    const auto in_box = [&](std::int32_t a, std::int32_t c) {
        return static_cast<std::int32_t>(
            a - 2 +
            static_cast<std::int32_t>(rng.uniform_index(static_cast<std::size_t>(c - a + 5))));
    };
    while (b.present.size() < kLookups) b.present.push_back(keys[rng.uniform_index(keys.size())]);
    while (b.missing.size() < kLookups) {
        const CellKey k{in_box(lo.x, hi.x), in_box(lo.y, hi.y), in_box(lo.z, hi.z)};
        if (!b.map.contains(k)) b.missing.push_back(k);
    }
    for (std::size_t i = 0; i < kGathers; ++i) {
        b.positions.push_back(b.map.cell_center(keys[rng.uniform_index(keys.size())]));
    }
}

void print_stats_table() {
    std::printf("\n%-16s %-10s %8s %9s %9s %9s %7s %9s %6s %7s %7s %8s\n", "map", "hash", "cells",
                "points", "distinct", "sharing", "group", "buckets", "max_b", "mean_b", "chain",
                "mem_MB");
    for (const BuiltMap& b : built()) {
        const mapping::HashStats s = b.map.hash_stats();
        std::printf("%-16s %-10s %8zu %9zu %9zu %9zu %7zu %9zu %6zu %7.2f %7.1f %8.1f\n",
                    b.input->name.c_str(), std::string(to_string(b.kind)).c_str(), s.num_cells,
                    b.map.num_points(), s.distinct_hashes, s.cells_sharing_hash,
                    s.largest_hash_group, s.bucket_count, s.max_bucket_occupancy,
                    s.mean_bucket_occupancy, s.mean_chain_seen, b.map.memory_bytes() / 1e6);
    }
    std::printf(
        "distinct: distinct full 64-bit hashes; sharing: cells whose hash equals another cell's;\n"
        "group: most cells on one hash value; max_b / mean_b: cells in the fullest / an average\n"
        "non-empty bucket; chain: mean cells in the bucket of an existing key (1 = ideal)\n\n");
}

void find_bench(benchmark::State& state, const BuiltMap* b, bool existing) {
    const std::vector<CellKey>& keys = existing ? b->present : b->missing;
    std::size_t found = 0;
    for (auto _ : state) {
        found = 0;
        for (const CellKey& k : keys) found += b->map.num_points_in(k);
        benchmark::DoNotOptimize(found);
    }
    state.counters["per_find"] = benchmark::Counter(
        static_cast<double>(keys.size()),
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void gather_bench(benchmark::State& state, const BuiltMap* b) {
    std::vector<Eigen::Vector3d> out;
    std::size_t total = 0;
    for (auto _ : state) {
        total = 0;
        for (const Eigen::Vector3d& p : b->positions) {
            out.clear();
            b->map.gather_near(p, b->input->gather_radius_m, out);
            total += out.size();
        }
        benchmark::DoNotOptimize(out.data());
    }
    state.counters["per_gather"] = benchmark::Counter(
        static_cast<double>(b->positions.size()),
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["points_per_gather"] =
        static_cast<double>(total) / static_cast<double>(b->positions.size());
}

void build_bench(benchmark::State& state, const BuiltMap* b) {
    std::size_t points = 0;
    for (const auto& batch : b->input->batches) points += batch.size();
    for (auto _ : state) {
        const CellMap map = build_map(*b->input, b->kind);
        benchmark::DoNotOptimize(map.num_points());
    }
    state.counters["per_point"] = benchmark::Counter(
        static_cast<double>(points),
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

/// A cell over budget as it appears in the map: 1000 points on three planes through a 4 m cell.
std::vector<Eigen::Vector3f> over_budget_cell() {
    Rng rng(kSeed);
    std::vector<Eigen::Vector3f> offsets;
    for (int i = 0; i < 1000; ++i) {
        Eigen::Vector3d p(rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0));
        p[i % 3] = 0.7 * (i % 3) - 0.7 + rng.normal(0.0, 0.01);
        offsets.push_back(p.cast<float>());
    }
    return offsets;
}

constexpr double kThinVoxelM = 0.2;
constexpr std::size_t kNoBudget = 1000000;  // one pass at kThinVoxelM for both routines

void thin_ours(benchmark::State& state) {
    const std::vector<Eigen::Vector3f> cell = over_budget_cell();
    std::vector<Eigen::Vector3f> work;
    for (auto _ : state) {
        work = cell;
        mapping::thin_cell(work, Eigen::Vector3d::Constant(4.0), kThinVoxelM, kNoBudget);
        benchmark::DoNotOptimize(work.data());
    }
    state.counters["points_out"] = static_cast<double>(work.size());
}

/// The alternative to reusing core::voxel_downsample: a per-cell routine that sorts
/// (voxel code, index) pairs with std::sort and averages each run.
std::vector<Eigen::Vector3f> thin_by_std_sort(const std::vector<Eigen::Vector3f>& offsets,
                                              double cell_m, double voxel_m) {
    const auto n = static_cast<std::uint64_t>(std::ceil(cell_m / voxel_m));
    std::vector<std::pair<std::uint64_t, std::uint32_t>> items(offsets.size());
    for (std::size_t i = 0; i < offsets.size(); ++i) {
        std::uint64_t code = 0;
        for (int a = 0; a < 3; ++a) {
            const double q = std::floor((double{offsets[i][a]} + 0.5 * cell_m) / voxel_m);
            code = code * n + static_cast<std::uint64_t>(std::clamp(q, 0.0, n - 1.0));
        }
        items[i] = {code, static_cast<std::uint32_t>(i)};
    }
    std::sort(items.begin(), items.end());
    std::vector<Eigen::Vector3f> out;
    for (std::size_t i = 0; i < items.size();) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        std::size_t j = i;
        for (; j < items.size() && items[j].first == items[i].first; ++j) {
            sum += offsets[items[j].second].cast<double>();
        }
        out.push_back((sum / static_cast<double>(j - i)).cast<float>());
        i = j;
    }
    return out;
}

void thin_std_sort(benchmark::State& state) {
    const std::vector<Eigen::Vector3f> cell = over_budget_cell();
    std::vector<Eigen::Vector3f> work;
    for (auto _ : state) {
        work = thin_by_std_sort(cell, 4.0, kThinVoxelM);
        benchmark::DoNotOptimize(work.data());
    }
    state.counters["points_out"] = static_cast<double>(work.size());
}

template <typename Fn, typename... Args>
void add(const std::string& name, benchmark::TimeUnit unit, Fn fn, Args... args) {
    benchmark::RegisterBenchmark(name.c_str(), fn, args...)->Unit(unit)->UseRealTime();
}

void register_all() {
    for (const BuiltMap& b : built()) {
        if (!b.input->timed) continue;
        const std::string tail = fmt::format("/{}/1thr", kind_label(b.kind));
        const std::string& n = b.input->name;
        add("find_hit_" + n + tail, benchmark::kMillisecond, find_bench, &b, true);
        add("find_miss_" + n + tail, benchmark::kMillisecond, find_bench, &b, false);
        add(fmt::format("gather_{:.0f}m_{}{}", b.input->gather_radius_m, n, tail),
            benchmark::kMillisecond, gather_bench, &b);
        add("build_" + n + tail, benchmark::kMillisecond, build_bench, &b);
    }
    add("thin_cell_1000pts/ours/1thr", benchmark::kMicrosecond, thin_ours);
    add("thin_cell_1000pts/std_sort_routine/1thr", benchmark::kMicrosecond, thin_std_sort);
}

MapInput input_with(std::string name, double cell_m, double voxel_m, double radius_m,
                    Batches batches) {
    MapInput in;
    in.name = std::move(name);
    in.config.cell_size_xy_m = cell_m;
    in.config.cell_size_z_m = cell_m;
    in.config.thinning_voxel_m = voxel_m;
    in.gather_radius_m = radius_m;
    in.batches = std::move(batches);
    return in;
}

/// The 16 real sweeps, each with an identity pose (no poses are available; consecutive frames
/// are ~1 m apart, so the cells are those of a short street), all points as they are.
Batches real_sweeps() {
    Batches batches;
    for (int i = 0; i < 16; ++i) {
        auto cloud =
            load_shared_cloud(SCANTLING_SHARED_DATA_DIR, fmt::format("lidar-scans/{:06d}.pcd", i));
        if (!cloud) return {};
        batches.push_back(std::move(cloud->points));
    }
    return batches;
}

Batches real_pair() {
    Batches batches;
    for (const char* f : {"lidar-pair/source.ply", "lidar-pair/target.ply"}) {
        auto cloud = load_shared_cloud(SCANTLING_SHARED_DATA_DIR, f);
        if (!cloud) return {};
        batches.push_back(std::move(cloud->points));
    }
    return batches;
}

void make_inputs() {
    const Batches sweeps = real_sweeps();
    if (!sweeps.empty()) {
        inputs().push_back(input_with("real_scans_4m", 4.0, 0.2, 50.0, sweeps));
        inputs().push_back(input_with("real_scans_1m", 1.0, 0.1, 50.0, sweeps));
    }
    if (Batches pair = real_pair(); !pair.empty()) {
        inputs().push_back(input_with("real_pair_4m", 4.0, 0.2, 50.0, std::move(pair)));
    }
    const Batches town = road_network_map(kSeed);
    inputs().push_back(input_with("town_8m", 8.0, 0.2, 50.0, town));
    inputs().push_back(input_with("town_4m", 4.0, 0.2, 50.0, town));
    inputs().push_back(input_with("town_2m", 2.0, 0.2, 50.0, town));
    inputs().back().timed = false;  // statistics only: the xor hash's gathers take minutes
    inputs().push_back(input_with("tank_0.5m", 0.5, 0.05, 5.0, ballast_tank_map(kSeed)));
}

}  // namespace
}  // namespace scantling::bench

int main(int argc, char** argv) {
    using namespace scantling::bench;
    make_inputs();
    for (const MapInput& in : inputs()) {
        std::size_t points = 0;
        for (const auto& batch : in.batches) points += batch.size();
        std::printf("input %-14s %2zu batches, %8zu points, cells %.1f x %.1f m, voxel %.2f m\n",
                    in.name.c_str(), in.batches.size(), points, in.config.cell_size_xy_m,
                    in.config.cell_size_z_m, in.config.thinning_voxel_m);
        for (const CellHashKind kind : {CellHashKind::kMixed, CellHashKind::kSourceXor}) {
            BuiltMap& b =
                built().emplace_back(BuiltMap{&in, kind, build_map(in, kind), {}, {}, {}});
            sample_queries(b);
        }
    }
    print_stats_table();
    register_all();
    return run_all(argc, argv);
}
