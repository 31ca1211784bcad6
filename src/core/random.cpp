#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_set>

namespace scantling {
namespace {

constexpr double kTwoToMinus53 = 1.0 / 9007199254740992.0;
constexpr std::uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ULL;
// Distinguishes split() seeds from a plain Rng(seed) built with a nearby seed.
constexpr std::uint64_t kSplitSalt = 0xA0761D6478BD642FULL;

void check_sigma(double sigma, const char* what) {
    if (!std::isfinite(sigma) || sigma < 0.0) {
        throw InputError(fmt::format("{}: sigma = {}, expected finite >= 0", what, sigma));
    }
}

// Floyd's algorithm: k distinct values with one draw each, without an n-sized array.
std::vector<std::size_t> floyd_sample(Rng& rng, std::size_t n, std::size_t k) {
    std::unordered_set<std::size_t> chosen;
    chosen.reserve(2 * k);
    std::vector<std::size_t> out;
    out.reserve(k);
    for (std::size_t j = n - k; j < n; ++j) {
        const std::size_t t = rng.uniform_index(j + 1);
        const std::size_t pick = chosen.contains(t) ? j : t;
        chosen.insert(pick);
        out.push_back(pick);
    }
    return out;
}

// Partial Fisher–Yates over [0, n): the first k entries are a uniform k-subset.
std::vector<std::size_t> partial_shuffle_sample(Rng& rng, std::size_t n, std::size_t k) {
    std::vector<std::size_t> all(n);
    std::iota(all.begin(), all.end(), std::size_t{0});
    for (std::size_t i = 0; i < k; ++i) std::swap(all[i], all[i + rng.uniform_index(n - i)]);
    all.resize(k);
    return all;
}

}  // namespace

std::uint64_t splitmix64(std::uint64_t x) {
    std::uint64_t z = x + kGoldenGamma;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

Rng::Rng(std::uint64_t seed) : seed_(seed), engine_(seed) {}

std::uint64_t Rng::next_u64() { return engine_(); }

double Rng::uniform() { return static_cast<double>(next_u64() >> 11) * kTwoToMinus53; }

double Rng::uniform(double a, double b) {
    if (!std::isfinite(a) || !std::isfinite(b) || a > b) {
        throw InputError(fmt::format("Rng::uniform: range [{}, {}), expected finite a <= b", a, b));
    }
    const double value = a + (b - a) * uniform();
    // a + (b - a)·u can round up to b; keep the half-open promise.
    return value < b ? value : a;
}

double Rng::normal() {
    if (has_cached_normal_) {
        has_cached_normal_ = false;
        return cached_normal_;
    }
    double u = 0.0;
    double v = 0.0;
    double s = 0.0;
    do {
        u = 2.0 * uniform() - 1.0;
        v = 2.0 * uniform() - 1.0;
        s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double scale = std::sqrt(-2.0 * std::log(s) / s);
    cached_normal_ = v * scale;
    has_cached_normal_ = true;
    return u * scale;
}

double Rng::normal(double mean, double sigma) {
    check_sigma(sigma, "Rng::normal");
    return mean + sigma * normal();
}

Eigen::Vector3d Rng::normal3(double sigma) {
    check_sigma(sigma, "Rng::normal3");
    // Named draws: the order of evaluation of constructor arguments is unspecified.
    const double x = normal();
    const double y = normal();
    const double z = normal();
    return sigma * Eigen::Vector3d(x, y, z);
}

std::size_t Rng::uniform_index(std::size_t n) {
    if (n == 0) throw InputError("Rng::uniform_index: n = 0, expected n >= 1");
    const std::uint64_t range = n;
    // 2⁶⁴ mod n: draws below it belong to an incomplete last block and are rejected.
    const std::uint64_t threshold = (0 - range) % range;
    std::uint64_t x = next_u64();
    while (x < threshold) x = next_u64();
    return static_cast<std::size_t>(x % range);
}

Rng Rng::split(std::uint64_t stream_id) const {
    return Rng(splitmix64(splitmix64(seed_ ^ kSplitSalt) + kGoldenGamma * (stream_id + 1)));
}

std::vector<std::size_t> Rng::sample_indices(std::size_t n, std::size_t k) {
    if (k > n) {
        throw InputError(fmt::format("Rng::sample_indices: k = {}, expected k <= n = {}", k, n));
    }
    // Floyd avoids the O(n) array when few indices are wanted from a large range.
    std::vector<std::size_t> out =
        k < n / 8 ? floyd_sample(*this, n, k) : partial_shuffle_sample(*this, n, k);
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace scantling
