// Issue 16 items 2 and 5: the receding-horizon next-best-view planner (planning::NbvPlanner,
// SPEC §8). A closed 10 × 6 × 4 m tank with two baffles (a serpentine), ray cast exactly;
// the map after a look-around and four depth frames from the first bay (most of the tank
// unknown: mid-exploration).
//   plan_…/vanilla/<n>thr   plan() with uniform sampling (RH-NBVP as published)
//   plan_…/ours/<n>thr      plan() with frontier-guided sampling (the improvement)
// at N_T = 180 (table G.2) on 0.1 and 0.05 m maps, 32 × 24 and 16 × 12 gain rays, 1 and 2
// threads. Counters: gain evaluations, nodes, best Q, frontier points.
//   frontiers_…/cell<k>     OccupancyOctree::frontier_points alone, cells of k voxels.
// Then (printed, not timed by google benchmark) exploration loops: teleport to each plan's
// next goal, insert the exact depth frame there, until exhausted; plans to reach 90 / 95 /
// 99 % of the free volume known, plans until exhausted, mean plan time; several seeds.
// Results in docs/benchmarks.md, "Next-best-view planner (issue 16)".
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <scantling/mapping/occupancy_octree.hpp>
#include <scantling/planning/nbv_planner.hpp>

#include "bench_support.hpp"

namespace scantling::bench {
namespace {

using Eigen::AlignedBox3d;
using Eigen::Vector3d;
using planning::NbvPlan;
using planning::NbvPlanner;
using planning::NbvPlannerConfig;
using planning::NbvSampling;
using planning::NbvState;

const AlignedBox3d kTank(Vector3d(-4.975, -2.975, -1.975), Vector3d(5.025, 3.025, 2.025));
const std::vector<AlignedBox3d> kBaffles = {
    {Vector3d(-1.625, -2.975, -1.975), Vector3d(-1.425, 1.025, 2.025)},
    {Vector3d(1.925, -1.025, -1.975), Vector3d(2.125, 3.025, 2.025)}};
const Vector3d kStart(-3.5, 0.0, 0.0);

double entry(const AlignedBox3d& box, const Vector3d& o, const Vector3d& d) {
    double t_near = 0.0, t_far = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
        if (d[i] == 0.0) {
            if (o[i] < box.min()[i] || o[i] > box.max()[i]) return t_far;
            continue;
        }
        double t0 = (box.min()[i] - o[i]) / d[i], t1 = (box.max()[i] - o[i]) / d[i];
        if (t0 > t1) std::swap(t0, t1);
        t_near = std::max(t_near, t0);
        t_far = std::min(t_far, t1);
    }
    return t_near <= t_far ? t_near : std::numeric_limits<double>::infinity();
}

double range(const Vector3d& o, const Vector3d& d) {
    double t = 50.0;
    for (int i = 0; i < 3; ++i) {
        if (d[i] > 0.0) t = std::min(t, (kTank.max()[i] - o[i]) / d[i]);
        if (d[i] < 0.0) t = std::min(t, (kTank.min()[i] - o[i]) / d[i]);
    }
    for (const AlignedBox3d& b : kBaffles) t = std::min(t, entry(b, o, d));
    return t;
}

/// The planner's camera at `state`: a 96 × 72 depth frame over its FOV, inserted.
void observe(const NbvPlannerConfig& config, const NbvState& state, mapping::OccupancyOctree& map) {
    const Eigen::Isometry3d T = planning::nbv_camera_pose(config, state);
    const double tx = std::tan(config.camera.horizontal_fov_rad / 2.0);
    const double ty = std::tan(config.camera.vertical_fov_rad / 2.0);
    PointCloud cloud;
    for (int v = 0; v < 72; ++v) {
        for (int u = 0; u < 96; ++u) {
            const Vector3d d =
                Vector3d(1.0, tx * ((u + 0.5) / 48.0 - 1.0), ty * ((v + 0.5) / 36.0 - 1.0))
                    .normalized();
            cloud.points.push_back(d * range(T.translation(), T.linear() * d));
        }
    }
    map.insert_depth_frame(cloud, T);
}

/// A 1° full-sphere scan from `p`: the vehicle looking around before exploring.
void look_around(const Vector3d& p, mapping::OccupancyOctree& map) {
    constexpr double kDeg = std::numbers::pi / 180.0;
    PointCloud cloud;
    for (int e = -89; e <= 89; ++e)
        for (int a = 0; a < 360; ++a) {
            const Vector3d d(std::cos(e * kDeg) * std::cos(a * kDeg),
                             std::cos(e * kDeg) * std::sin(a * kDeg), std::sin(e * kDeg));
            cloud.points.push_back(d * range(p, d));
        }
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = p;
    map.insert_depth_frame(cloud, T);
}

NbvPlannerConfig tank_config(NbvSampling sampling, int rays_h, int threads) {
    NbvPlannerConfig config;
    config.bounds_min_world_m = kTank.min();
    config.bounds_max_world_m = kTank.max();
    config.sampling = sampling;
    config.camera.rays_horizontal = rays_h;
    config.camera.rays_vertical = rays_h * 3 / 4;
    config.parallel.num_threads = threads;
    return config;
}

mapping::OccupancyOctree first_bay_map(double res_m) {
    mapping::OccupancyOctreeConfig map_config;
    map_config.resolution_m = res_m;
    mapping::OccupancyOctree map(map_config);
    look_around(kStart, map);
    for (int k = 0; k < 4; ++k)
        observe(NbvPlannerConfig{}, {kStart, k * std::numbers::pi / 2.0}, map);
    return map;
}

void bench_plan(benchmark::State& state, const mapping::OccupancyOctree* map,
                NbvPlannerConfig config) {
    NbvPlan plan;
    for (auto _ : state) {
        NbvPlanner planner(config);
        plan = planner.plan(*map, {kStart, 0.0});
        benchmark::DoNotOptimize(plan);
    }
    state.counters["gain_evals"] = static_cast<double>(plan.stats.gain_evaluations);
    state.counters["nodes"] = static_cast<double>(plan.tree.size());
    state.counters["best_m3"] = plan.best_value;
    state.counters["frontier_pts"] = static_cast<double>(plan.stats.frontier_points);
}

void bench_frontiers(benchmark::State& state, const mapping::OccupancyOctree* map, int levels) {
    std::size_t points = 0;
    for (auto _ : state) {
        points = map->frontier_points(kTank, levels).size();
        benchmark::DoNotOptimize(points);
    }
    state.counters["frontier_pts"] = static_cast<double>(points);
}

double free_volume_m3() {
    double v = kTank.volume();
    for (const auto& b : kBaffles) v -= b.volume();
    return v;
}

struct LoopResult {
    int plans_to[3] = {-1, -1, -1};  // 90, 95, 99 %
    int plans = 0;
    bool exhausted = false;
    double mean_plan_ms = 0.0;
    double final_fraction = 0.0;
};

LoopResult explore(const NbvPlannerConfig& config, double res_m, int max_plans) {
    mapping::OccupancyOctreeConfig map_config;
    map_config.resolution_m = res_m;
    mapping::OccupancyOctree map(map_config);
    look_around(kStart, map);
    NbvPlanner planner(config);
    NbvState state{kStart, 0.0};
    LoopResult r;
    double total_ms = 0.0;
    const double cell_m3 = res_m * res_m * res_m;
    const double fractions[3] = {0.90, 0.95, 0.99};
    while (r.plans < max_plans) {
        const auto t0 = std::chrono::steady_clock::now();
        const NbvPlan plan = planner.plan(map, state);
        total_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count();
        ++r.plans;
        if (plan.status != planning::NbvStatus::kOk) {
            r.exhausted = plan.status == planning::NbvStatus::kExhausted;
            break;
        }
        state = plan.next_goal;
        observe(config, state, map);
        const double unknown = map.unknown_volume_in_m3(kTank);
        const double cells = std::round(kTank.volume() / cell_m3);
        r.final_fraction = (cells * cell_m3 - unknown) / free_volume_m3();
        for (int i = 0; i < 3; ++i)
            if (r.plans_to[i] < 0 && r.final_fraction >= fractions[i]) r.plans_to[i] = r.plans;
    }
    r.mean_plan_ms = total_ms / r.plans;
    return r;
}

void print_loops(double res_m, int max_nodes, double lambda, int rays_h, int threads, int seeds,
                 int max_plans) {
    for (const NbvSampling sampling : {NbvSampling::kUniform, NbvSampling::kFrontier}) {
        NbvPlannerConfig config = tank_config(sampling, rays_h, threads);
        config.max_nodes = max_nodes;
        config.lambda_per_m = lambda;
        for (int seed = 1; seed <= seeds; ++seed) {
            config.seed = static_cast<std::uint64_t>(seed);
            const LoopResult r = explore(config, res_m, max_plans);
            fmt::print(
                "loop res {:.2f} N_T {} lambda {} rays {}x{} {} seed {}: to 90/95/99 %: {} / {} / "
                "{} plans; {} plans, exhausted {}, final {:.3f}, {:.1f} ms/plan\n",
                res_m, max_nodes, lambda, rays_h, rays_h * 3 / 4,
                sampling == NbvSampling::kUniform ? "uniform " : "frontier", seed, r.plans_to[0],
                r.plans_to[1], r.plans_to[2], r.plans, r.exhausted, r.final_fraction,
                r.mean_plan_ms);
        }
    }
}

}  // namespace
}  // namespace scantling::bench

int main(int argc, char** argv) {
    using namespace scantling::bench;
    const std::vector<double> resolutions = {0.1, 0.05};
    std::vector<scantling::mapping::OccupancyOctree> maps;
    for (double res_m : resolutions) maps.push_back(first_bay_map(res_m));
    for (std::size_t m = 0; m < maps.size(); ++m) {
        for (const int rays_h : {32, 16}) {
            for (const int threads : {1, 2}) {
                for (const NbvSampling s : {NbvSampling::kUniform, NbvSampling::kFrontier}) {
                    NbvPlannerConfig config = tank_config(s, rays_h, threads);
                    config.max_nodes = 180;
                    config.lambda_per_m = 1.0;  // table G.2
                    const std::string name = fmt::format(
                        "plan_res{:.2f}_rays{}x{}/{}/{}thr", resolutions[m], rays_h, rays_h * 3 / 4,
                        s == NbvSampling::kUniform ? "vanilla" : "ours", threads);
                    benchmark::RegisterBenchmark(name.c_str(), bench_plan, &maps[m], config)
                        ->Unit(benchmark::kMillisecond)
                        ->UseRealTime()
                        ->Iterations(3);
                }
            }
        }
    }
    for (std::size_t m = 0; m < maps.size(); ++m) {
        for (const int levels : {0, 1, 2}) {
            // Own case names: no ours / baseline pair.
            benchmark::RegisterBenchmark(
                fmt::format("frontiers_res{:.2f}/cell{}/1thr", resolutions[m], 1 << levels).c_str(),
                bench_frontiers, &maps[m], levels)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime()
                ->Iterations(3);
        }
    }
    const int status = run_all(argc, argv);
    if (std::getenv("SCANTLING_NBV_NO_LOOPS") != nullptr) return status;  // plan() times only
    print_loops(0.1, 30, 0.2, 32, 2, 5, 60);                              // table G.1
    print_loops(0.1, 30, 0.2, 16, 2, 5, 60);                              // fewer gain rays
    print_loops(0.05, 180, 1.0, 16, 2, 1, 40);  // table G.2 at the speed target's rays
    return status;
}
