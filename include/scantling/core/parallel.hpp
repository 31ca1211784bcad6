#pragma once
/// @file
/// Thread configuration applied through TBB task arenas (no process-global thread state).
/// TBB stays out of public headers: bodies are passed as std::function over index ranges, so
/// the call overhead is per chunk, not per element.

#include <cstddef>
#include <functional>
#include <string_view>
#include <vector>

namespace scantling {

struct ParallelConfig {
    /// Worker threads; 1 = run serially; 0 = all the caller has: every hardware thread, or
    /// the count of an enclosing with_threads().
    int num_threads = 0;

    /// Throws ConfigError("<prefix>.num_threads = -1, expected >= 0").
    void validate(std::string_view prefix = "parallel") const;
};

/// Runs `fn` with `config.num_threads` threads: in the caller's task arena when it has that
/// many (or for 0), otherwise in a new arena of that size for the whole call. Every
/// parallel_for inside `fn` asking for the same count then shares that one arena instead of
/// building its own (the odometry's pipeline, a CLI command's whole run).
void with_threads(const ParallelConfig& config, const std::function<void()>& fn);

/// Calls `body(begin, end)` over disjoint sub-ranges covering [0, n), at most `grain`
/// indices each when run in parallel. Runs in the caller's task arena when it has
/// `config.num_threads` threads (or for 0 = all threads the caller has), otherwise in an arena
/// of that size built for this call; isolated, so that while the caller waits for its chunks
/// it runs nothing else. `body` must only write to per-index state: the split depends on
/// scheduling.
void parallel_for(const ParallelConfig& config, std::size_t n, std::size_t grain,
                  const std::function<void(std::size_t begin, std::size_t end)>& body);

/// Deterministic reduction: [0, n) is cut into fixed chunks of `grain` indices (independent of
/// the thread count), `chunk_fn(begin, end)` reduces each chunk, and the partial results are
/// combined in chunk order. Serial and parallel runs give bit-identical results.
template <typename T, typename ChunkFn, typename Combine>
T parallel_reduce_ordered(const ParallelConfig& config, std::size_t n, std::size_t grain,
                          T identity, ChunkFn&& chunk_fn, Combine&& combine) {
    if (grain == 0) grain = 1;
    const std::size_t chunks = (n + grain - 1) / grain;
    std::vector<T> partial(chunks, identity);
    parallel_for(config, chunks, 1, [&](std::size_t c_begin, std::size_t c_end) {
        for (std::size_t c = c_begin; c < c_end; ++c) {
            const std::size_t end = (c + 1) * grain < n ? (c + 1) * grain : n;
            partial[c] = chunk_fn(c * grain, end);
        }
    });
    T result = identity;
    for (const T& p : partial) result = combine(result, p);
    return result;
}

}  // namespace scantling
