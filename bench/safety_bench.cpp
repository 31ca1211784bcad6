// Issue 13 item 3: SPEC §3 collision prevention on one 64 × 1024 sweep, one thread. The sweep
// is an OS1-64 (±22.5° elevation, 1024 columns) ray-cast analytically inside a 6 × 4 × 3 m
// box tank, 0.7 m from its side wall (inside d_min, so the repulsion runs too), with 1 cm
// range noise and 2 % no-returns (NaN), seeded. `ours` is safety::prevent_collision;
// `naive_spec` transcribes SPEC §3 literally: per point the two frustum angles by atan2 and
// the range, every in-frustum range and every repulsion vector stored in a vector, then the
// min and the mean. Both must agree (checked before timing). Target: ≤ 1 ms per sweep.
// `gather` is safety::gather_obstacle_points, run once per sweep by the drone stack, and
// `gathered` prevent_collision on its output, run once per command (obstacle_points.hpp).
// Results in docs/benchmarks.md, "Safety: collision prevention (issue 13 item 3)".
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <numeric>
#include <vector>

#include <fmt/format.h>

#include <scantling/core/random.hpp>
#include <scantling/safety/collision_prevention.hpp>
#include <scantling/safety/obstacle_points.hpp>

#include "bench_support.hpp"

namespace scantling::bench {
namespace {

using Eigen::Vector3d;

constexpr int kRings = 64, kColumns = 1024;
constexpr std::uint64_t kSeed = 13;
const Vector3d kTankMin(-0.7, -2.0, -1.2), kTankMax(5.3, 2.0, 1.8);  // body at the origin
const Vector3d kDesired(-0.8, 0.5, 0.1);  // towards the near wall (x = −0.7), m/s

/// Range along unit `d` from the origin to the inside of the box.
double box_range(const Vector3d& d) {
    double range = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
        if (d[i] > 0.0) range = std::min(range, kTankMax[i] / d[i]);
        if (d[i] < 0.0) range = std::min(range, kTankMin[i] / d[i]);
    }
    return range;
}

PointCloud tank_sweep() {
    Rng rng(kSeed);
    PointCloud cloud;
    cloud.points.reserve(std::size_t{kRings} * kColumns);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int ring = 0; ring < kRings; ++ring) {
        const double elevation = (-22.5 + 45.0 * ring / (kRings - 1)) * std::numbers::pi / 180.0;
        for (int column = 0; column < kColumns; ++column) {
            const double azimuth = 2.0 * std::numbers::pi * column / kColumns;
            const Vector3d d(std::cos(elevation) * std::cos(azimuth),
                             std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
            const bool no_return = rng.uniform() < 0.02;
            cloud.points.push_back(no_return ? Vector3d(nan, nan, nan)
                                             : d * (box_range(d) + rng.normal(0.0, 0.01)));
        }
    }
    return cloud;
}

struct NaiveResult {
    Vector3d v_cmd = Vector3d::Zero();
    std::size_t in_frustum = 0, repelling = 0;
};

/// SPEC §3 as written, a statement per sentence.
NaiveResult naive_spec(const Vector3d& v, const PointCloud& cloud,
                       const safety::CollisionPreventionConfig& c) {
    const auto frustum = safety::make_frustum(v, c);  // the same axes as ours
    const double half_h = c.half_fov_horizontal_deg * std::numbers::pi / 180.0;
    const double half_v = c.half_fov_vertical_deg * std::numbers::pi / 180.0;
    std::vector<double> frustum_ranges;
    std::vector<Vector3d> repulsions;
    for (const Vector3d& p : cloud.points) {
        if (!p.allFinite() || p.squaredNorm() == 0.0) continue;
        const double range = p.norm();
        const double a = p.dot(frustum->axis_f);
        const double angle_h = std::atan2(p.dot(frustum->horizontal_h), a);
        const double angle_v = std::atan2(p.dot(frustum->vertical_u), a);
        if (a >= c.robot_radius_m && a <= c.d_att_m && std::abs(angle_h) <= half_h &&
            std::abs(angle_v) <= half_v) {
            frustum_ranges.push_back(range);
        }
        if (range < c.d_min_m)
            repulsions.push_back(-p / range * c.repulsion_gain_per_s * (c.d_min_m - range));
    }
    NaiveResult r{Vector3d::Zero(), frustum_ranges.size(), repulsions.size()};
    double lambda = 1.0;
    if (!frustum_ranges.empty()) {
        const double d_o = *std::min_element(frustum_ranges.begin(), frustum_ranges.end());
        lambda = std::clamp((d_o - c.d_min_m) / (c.d_att_m - c.d_min_m), 0.0, 1.0);
    }
    Vector3d v_rep = Vector3d::Zero();
    if (!repulsions.empty()) {
        v_rep = std::accumulate(repulsions.begin(), repulsions.end(), Vector3d::Zero().eval()) /
                static_cast<double>(repulsions.size());
        if (v_rep.norm() > c.max_speed_mps) v_rep *= c.max_speed_mps / v_rep.norm();
    }
    r.v_cmd = lambda * v + v_rep;
    return r;
}

/// Both implementations must give the same command on the sweep before either is timed.
void check_agreement(const PointCloud& sweep) {
    const safety::CollisionPreventionConfig config;
    const auto ours = safety::prevent_collision(kDesired, sweep, config);
    const auto naive = naive_spec(kDesired, sweep, config);
    fmt::print("sweep: {} points, {} valid, {} in the frustum, {} closer than d_min; {}\n",
               sweep.size(), ours.num_valid_points, ours.num_frustum_points,
               ours.num_points_within_d_min, safety::describe(ours, config));
    const double gap = (ours.v_cmd_body_mps - naive.v_cmd).norm();
    const auto obstacles = safety::gather_obstacle_points(sweep, config);
    const auto gathered = safety::prevent_collision(kDesired, obstacles, config);
    fmt::print("gathered once per sweep: {} of {} points within {:.2f} m\n",
               obstacles.points_body.size(), sweep.size(), obstacles.reach_m);
    if (gap > 1e-9 || ours.num_frustum_points != naive.in_frustum ||
        ours.num_points_within_d_min != naive.repelling ||
        gathered.v_cmd_body_mps != ours.v_cmd_body_mps) {
        fmt::print(stderr, "safety_bench: ours and naive_spec disagree ({} m/s)\n", gap);
        std::exit(1);
    }
}

void bench_ours(benchmark::State& state, const PointCloud* sweep) {
    const safety::CollisionPreventionConfig config;
    for (auto _ : state) {
        auto result = safety::prevent_collision(kDesired, *sweep, config);
        benchmark::DoNotOptimize(result);
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(sweep->size()));
}

void bench_gather(benchmark::State& state, const PointCloud* sweep) {
    const safety::CollisionPreventionConfig config;
    for (auto _ : state) {
        auto obstacles = safety::gather_obstacle_points(*sweep, config);
        benchmark::DoNotOptimize(obstacles);
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(sweep->size()));
}

void bench_gathered(benchmark::State& state, const PointCloud* sweep) {
    const safety::CollisionPreventionConfig config;
    const auto obstacles = safety::gather_obstacle_points(*sweep, config);
    for (auto _ : state) {
        auto result = safety::prevent_collision(kDesired, obstacles, config);
        benchmark::DoNotOptimize(result);
    }
    state.SetItemsProcessed(state.iterations() *
                            static_cast<std::int64_t>(obstacles.points_body.size()));
}

void bench_naive(benchmark::State& state, const PointCloud* sweep) {
    const safety::CollisionPreventionConfig config;
    for (auto _ : state) {
        auto result = naive_spec(kDesired, *sweep, config);
        benchmark::DoNotOptimize(result);
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(sweep->size()));
}

}  // namespace
}  // namespace scantling::bench

int main(int argc, char** argv) {
    using namespace scantling::bench;
    const scantling::PointCloud sweep = tank_sweep();  // outlives the benchmarks: run_all below
    check_agreement(sweep);
    benchmark::RegisterBenchmark("sweep_64x1024/ours/1thr", bench_ours, &sweep)
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark("sweep_64x1024/gather/1thr", bench_gather, &sweep)
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark("sweep_64x1024/gathered/1thr", bench_gathered, &sweep)
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark("sweep_64x1024/naive_spec/1thr", bench_naive, &sweep)
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime();
    return run_all(argc, argv);
}
