#pragma once
/// @file
/// Seeded random numbers whose streams are identical on every platform.
///
/// The engine is std::mt19937_64, whose output sequence the C++ standard specifies exactly.
/// The conversions to doubles are our own (std::uniform_real_distribution and
/// std::normal_distribution differ between standard libraries):
/// - `uniform()`  = (next_u64() >> 11) · 2⁻⁵³, exact and portable;
/// - `normal()`   = Marsaglia's polar method, which uses only +, ·, sqrt (all exactly rounded by
///   IEEE 754) and std::log, so normals are bit-identical wherever std::log is correctly rounded
///   (glibc and most modern libms in practice);
/// - `uniform_index(n)` rejects the biased tail of the 2⁶⁴ range, so it is exactly uniform.
///
/// Thread-safety: an Rng is a mutable engine; give each thread its own via `split()`.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <random>
#include <span>
#include <utility>
#include <vector>

namespace scantling {

/// The splitmix64 finaliser (Steele, Lea & Flood 2014): a bijective 64-bit mixer.
std::uint64_t splitmix64(std::uint64_t x);

class Rng {
  public:
    /// Same seed ⇒ same stream of values on every platform.
    explicit Rng(std::uint64_t seed);

    /// The seed this generator was constructed from.
    std::uint64_t seed() const { return seed_; }

    /// Next raw 64-bit output of mt19937_64.
    std::uint64_t next_u64();

    /// Uniform double in [0, 1) on the grid k · 2⁻⁵³.
    double uniform();

    /// Uniform double in [a, b). Throws InputError unless a and b are finite and a <= b.
    double uniform(double a, double b);

    /// Standard normal N(0, 1) (polar method; values come in pairs, the second is cached).
    double normal();

    /// N(mean, sigma²). Throws InputError unless sigma is finite and >= 0.
    double normal(double mean, double sigma);

    /// Three independent N(0, sigma²) components. Throws InputError unless sigma is finite and
    /// >= 0.
    Eigen::Vector3d normal3(double sigma);

    /// Uniform integer in [0, n), exactly unbiased. Throws InputError when n == 0.
    std::size_t uniform_index(std::size_t n);

    /// An independent generator for sub-stream `stream_id` (per thread, per sensor, ...),
    /// seeded by splitmix64 mixing of this generator's seed and `stream_id`. Depends only on
    /// `seed()` and `stream_id`, not on how many values this generator has produced.
    Rng split(std::uint64_t stream_id) const;

    /// Fisher–Yates shuffle, in place. O(n).
    template <typename T>
    void shuffle(std::span<T> values) {
        for (std::size_t i = values.size(); i > 1; --i) {
            std::swap(values[i - 1], values[uniform_index(i)]);
        }
    }

    /// `k` distinct indices drawn uniformly from [0, n), sorted ascending. Throws InputError
    /// when k > n. O(k log k) memory and time for k ≪ n (Floyd's algorithm), O(n) otherwise.
    std::vector<std::size_t> sample_indices(std::size_t n, std::size_t k);

  private:
    std::uint64_t seed_;
    std::mt19937_64 engine_;
    double cached_normal_ = 0.0;
    bool has_cached_normal_ = false;
};

}  // namespace scantling
