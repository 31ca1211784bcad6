#include <scantling/core/error.hpp>
#include <scantling/core/parallel.hpp>
#include <scantling/core/random.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <string>
#include <thread>
#include <vector>

namespace scantling {
namespace {

// Counts how often each index of [0, n) is visited; checks every range respects the grain.
std::vector<int> visit_counts(int num_threads, std::size_t n, std::size_t grain) {
    std::vector<std::atomic<int>> counts(n);
    std::atomic<bool> range_ok{true};
    parallel_for(ParallelConfig{num_threads}, n, grain, [&](std::size_t begin, std::size_t end) {
        const bool serial = num_threads == 1 || n <= std::max<std::size_t>(grain, 1);
        if (begin >= end || end > n) range_ok = false;
        if (!serial && end - begin > std::max<std::size_t>(grain, 1)) range_ok = false;
        for (std::size_t i = begin; i < end; ++i) counts[i].fetch_add(1);
    });
    EXPECT_TRUE(range_ok.load()) << "empty, out-of-range or larger-than-grain sub-range";
    std::vector<int> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = counts[i].load();
    return out;
}

TEST(Parallel, ForCoversEachIndexExactlyOnce) {
    for (const int threads : {1, 2, 0}) {
        for (const auto& [n, grain] :
             std::vector<std::pair<std::size_t, std::size_t>>{{0, 1},
                                                              {1, 1},
                                                              {1, 100},
                                                              {5, 0},
                                                              {7, 7},
                                                              {8, 7},
                                                              {1000, 1},
                                                              {1000, 33},
                                                              {10007, 256}}) {
            const std::vector<int> counts = visit_counts(threads, n, grain);
            ASSERT_EQ(counts.size(), n);
            for (std::size_t i = 0; i < n; ++i) {
                ASSERT_EQ(counts[i], 1)
                    << "threads " << threads << " n " << n << " grain " << grain << " index " << i;
            }
        }
    }
}

TEST(Parallel, ForWithZeroItemsNeverCallsTheBody) {
    int calls = 0;
    parallel_for(ParallelConfig{2}, 0, 10, [&](std::size_t, std::size_t) { ++calls; });
    EXPECT_EQ(calls, 0);
}

TEST(Parallel, ForWithOneThreadRunsASingleRange) {
    std::vector<std::pair<std::size_t, std::size_t>> ranges;
    parallel_for(ParallelConfig{1}, 100, 10,
                 [&](std::size_t b, std::size_t e) { ranges.emplace_back(b, e); });
    ASSERT_EQ(ranges.size(), 1U);
    EXPECT_EQ(ranges[0], (std::pair<std::size_t, std::size_t>{0, 100}));
}

TEST(Parallel, ReduceOrderedGivesBitIdenticalSumsForAnyThreadCount) {
    constexpr std::size_t kValues = 1000000;
    Rng rng(31);
    std::vector<double> values(kValues);
    // Mixed magnitudes make floating-point addition order visible in the last bits.
    for (double& v : values) v = rng.normal() * (rng.uniform() < 0.5 ? 1e8 : 1e-3);
    const auto sum_with = [&](int threads) {
        return parallel_reduce_ordered(
            ParallelConfig{threads}, values.size(), 4096, 0.0,
            [&](std::size_t b, std::size_t e) {
                double s = 0.0;
                for (std::size_t i = b; i < e; ++i) s += values[i];
                return s;
            },
            [](double a, double b) { return a + b; });
    };
    const double serial = sum_with(1);
    EXPECT_EQ(serial, sum_with(2));
    EXPECT_EQ(serial, sum_with(0));
    // Same chunking computed by hand: proves the combination is in chunk order.
    double expected = 0.0;
    for (std::size_t c = 0; c < kValues; c += 4096) {
        double s = 0.0;
        for (std::size_t i = c; i < std::min(c + 4096, kValues); ++i) s += values[i];
        expected += s;
    }
    EXPECT_EQ(serial, expected);
}

TEST(Parallel, ReduceOrderedHandlesEmptyAndPartialLastChunk) {
    const auto count = [](std::size_t n, std::size_t grain) {
        return parallel_reduce_ordered(
            ParallelConfig{2}, n, grain, std::size_t{0},
            [](std::size_t b, std::size_t e) { return e - b; },
            [](std::size_t a, std::size_t b) { return a + b; });
    };
    EXPECT_EQ(count(0, 10), 0U);
    EXPECT_EQ(count(1, 10), 1U);
    EXPECT_EQ(count(1001, 10), 1001U);
    EXPECT_EQ(count(1001, 0), 1001U);
}

// "0 = all the caller has": inside with_threads({1}) a loop asking for every thread stays on
// the calling thread (before, each loop built an arena of all hardware threads of its own).
TEST(Parallel, LoopsInsideWithThreadsShareItsThreadCount) {
    for (const int threads : {0, 1}) {
        std::vector<std::thread::id> ids(2000);
        with_threads(ParallelConfig{1}, [&] {
            parallel_for(ParallelConfig{threads}, ids.size(), 10,
                         [&](std::size_t b, std::size_t e) {
                             for (std::size_t i = b; i < e; ++i)
                                 ids[i] = std::this_thread::get_id();
                         });
        });
        for (const auto& id : ids) ASSERT_EQ(id, std::this_thread::get_id()) << threads;
    }
    // Nested in a 2-thread run, loops of 2 (or 0) threads still cover every index once.
    std::vector<std::atomic<int>> counts(5000);
    with_threads(ParallelConfig{2}, [&] {
        parallel_for(ParallelConfig{2}, 4, 1, [&](std::size_t b, std::size_t e) {
            for (std::size_t part = b; part < e; ++part) {
                parallel_for(ParallelConfig{part % 2 == 0 ? 2 : 0}, 1250, 16,
                             [&](std::size_t ib, std::size_t ie) {
                                 for (std::size_t i = ib; i < ie; ++i) {
                                     counts[part * 1250 + i].fetch_add(1);
                                 }
                             });
            }
        });
    });
    for (const auto& c : counts) ASSERT_EQ(c.load(), 1);
}

TEST(Parallel, WithThreadsRunsOnceAndPassesExceptionsOn) {
    int runs = 0;
    with_threads(ParallelConfig{2}, [&] { ++runs; });
    with_threads(ParallelConfig{3}, [&] { ++runs; });  // not the machine's count: an arena
    EXPECT_EQ(runs, 2);
    EXPECT_THROW(with_threads(ParallelConfig{2}, [] { throw InputError("inside"); }), InputError);
    EXPECT_THROW(with_threads(ParallelConfig{-1}, [] {}), ConfigError);
}

TEST(Parallel, NegativeThreadCountIsAConfigError) {
    try {
        ParallelConfig{-1}.validate();
        FAIL() << "expected ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("num_threads"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("-1"), std::string::npos) << e.what();
    }
    EXPECT_THROW(ParallelConfig{-1}.validate("icp.parallel"), ConfigError);
    EXPECT_THROW(parallel_for(ParallelConfig{-2}, 10, 1, [](std::size_t, std::size_t) {}),
                 ConfigError);
    EXPECT_NO_THROW(ParallelConfig{0}.validate());
}

}  // namespace
}  // namespace scantling
