#include <scantling/core/error.hpp>
#include <scantling/core/parallel.hpp>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

namespace scantling {
namespace {

/// The arena a call with `config` runs in is the caller's own when that one has the requested
/// number of threads (or any number, for 0 = all available): building a task arena costs its
/// initialisation and the wake-up of its workers on every call, and an arena built inside
/// another one competes with it for the same workers (measured: docs/benchmarks.md, "Parallel
/// scaling").
bool reuse_current_arena(const ParallelConfig& config) {
    return config.num_threads == 0 || config.num_threads == tbb::this_task_arena::max_concurrency();
}

template <typename Fn>
void run_with(const ParallelConfig& config, Fn&& fn) {
    if (reuse_current_arena(config)) {
        fn();
        return;
    }
    tbb::task_arena arena(config.num_threads);
    arena.execute(fn);
}

}  // namespace

void ParallelConfig::validate(std::string_view prefix) const {
    if (num_threads < 0) {
        throw ConfigError(
            fmt::format("{}.num_threads = {}, expected >= 0 (0 = all cores)", prefix, num_threads));
    }
}

void with_threads(const ParallelConfig& config, const std::function<void()>& fn) {
    config.validate();
    run_with(config, fn);
}

void parallel_for(const ParallelConfig& config, std::size_t n, std::size_t grain,
                  const std::function<void(std::size_t, std::size_t)>& body) {
    config.validate();
    if (n == 0) return;
    if (grain == 0) grain = 1;
    // Serial fast path: no scheduling cost for one thread or a single chunk.
    if (config.num_threads == 1 || n <= grain) {
        body(0, n);
        return;
    }
    run_with(config, [&] {
        // Isolated: while this thread waits for the last chunks of this loop it may only run
        // chunks of this loop, never an unrelated task of the same arena (the odometry's next
        // pipeline stage, say), which would hold this call's return for that task's length.
        tbb::this_task_arena::isolate([&] {
            // simple_partitioner honours the documented "at most grain indices" per call (the
            // default auto_partitioner hands out larger ranges) and splits at fixed boundaries.
            tbb::parallel_for(
                tbb::blocked_range<std::size_t>(0, n, grain),
                [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); },
                tbb::simple_partitioner());
        });
    });
}

}  // namespace scantling
