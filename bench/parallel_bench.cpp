// Issue 11, item 1: why a second thread made LiODOM slower, measured on a workload of its shape
// without the odometry around it. A "frame" is an extraction stage (a parallel loop over 64
// rings) and a registration stage (4 iterations of a parallel loop over 3,500 edges plus a
// short serial solve), run either one after the other ("loops") or as LiODOM's two-token
// pipeline ("pipeline"). `ours` is scantling::parallel_for / with_threads; `arena_per_call`
// reproduces the implementation before issue 11, which built a task arena in every
// parallel_for call. Results in docs/benchmarks.md, "Parallel scaling".
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <scantling/core/parallel.hpp>

#include "bench_support.hpp"

namespace scantling::bench {
namespace {

constexpr int kFrames = 40;
constexpr std::size_t kRings = 64, kEdges = 3500, kEdgeGrain = 256;
constexpr int kRingCost = 1800, kEdgeCost = 300, kSolveCost = 50000;  // sqrt steps per item

/// Per-item work with a result that cannot be optimised away.
double work(std::size_t item, int cost) {
    double s = static_cast<double>(item);
    for (int k = 0; k < cost; ++k) s = std::sqrt(s + k);
    return s;
}

/// One parallel loop, the way each implementation runs it.
using Loop = void (*)(int threads, std::size_t n, std::size_t grain, int cost,
                      std::vector<double>& out);

void loop_ours(int threads, std::size_t n, std::size_t grain, int cost, std::vector<double>& out) {
    parallel_for(ParallelConfig{threads}, n, grain, [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) out[i] = work(i, cost);
    });
}

void loop_arena_per_call(int threads, std::size_t n, std::size_t grain, int cost,
                         std::vector<double>& out) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, n, grain),
            [&](const tbb::blocked_range<std::size_t>& r) {
                for (std::size_t i = r.begin(); i < r.end(); ++i) out[i] = work(i, cost);
            },
            tbb::simple_partitioner());
    });
}

struct Stages {
    Loop loop;
    int threads;
    std::vector<double> rings = std::vector<double>(kRings);
    std::vector<double> edges = std::vector<double>(kEdges);
    double solved = 0.0;

    void extract() { loop(threads, kRings, 1, kRingCost, rings); }
    void register_edges() {
        for (int iteration = 0; iteration < 4; ++iteration) {
            loop(threads, kEdges, kEdgeGrain, kEdgeCost, edges);
            solved += work(static_cast<std::size_t>(edges[0]), kSolveCost);
        }
    }
};

void run_frames(Stages& stages, bool pipelined) {
    if (!pipelined || stages.threads == 1) {
        for (int f = 0; f < kFrames; ++f) {
            stages.extract();
            stages.register_edges();
        }
        return;
    }
    int next = 0;
    with_threads(ParallelConfig{stages.threads}, [&] {
        tbb::parallel_pipeline(
            2, tbb::make_filter<void, int>(tbb::filter_mode::serial_in_order,
                                           [&](tbb::flow_control& fc) {
                                               if (next >= kFrames) {
                                                   fc.stop();
                                                   return 0;
                                               }
                                               stages.extract();
                                               return next++;
                                           }) &
                   tbb::make_filter<int, void>(tbb::filter_mode::serial_in_order,
                                               [&](int) { stages.register_edges(); }));
    });
}

void frames(benchmark::State& state, Loop loop, int threads, bool pipelined) {
    Stages stages{loop, threads};
    for (auto _ : state) {
        run_frames(stages, pipelined);
        benchmark::DoNotOptimize(stages.solved);
    }
    state.counters["frames"] = kFrames;  // the time is for all of them
}

void add(const std::string& name, Loop loop, int threads, bool pipelined) {
    benchmark::RegisterBenchmark(name.c_str(), frames, loop, threads, pipelined)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}

}  // namespace
}  // namespace scantling::bench

int main(int argc, char** argv) {
    using namespace scantling::bench;
    for (const bool pipelined : {false, true}) {
        const char* shape = pipelined ? "liodom_shaped_pipeline" : "liodom_shaped_loops";
        for (const int threads : {1, 2}) {
            add(fmt::format("{}/ours/{}thr", shape, threads), loop_ours, threads, pipelined);
        }
        add(fmt::format("{}/arena_per_call/2thr", shape), loop_arena_per_call, 2, pipelined);
    }
    return run_all(argc, argv);
}
