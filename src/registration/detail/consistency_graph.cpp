#include "consistency_graph.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace scantling::registration::detail {
namespace {

constexpr std::size_t kRowGrain = 16;  // rows per chunk; rows shrink with i, chunks stay small

/// Coordinates as separate arrays, so that the per-row loops vectorise.
struct Columns {
    std::vector<double> x, y, z;

    explicit Columns(std::span<const Eigen::Vector3d> points) {
        for (const auto& p : points) {
            x.push_back(p.x());
            y.push_back(p.y());
            z.push_back(p.z());
        }
    }
};

/// excess[j] for j in (i, n): <= 0 exactly when pair (i, j) passes the test.
///
/// | |t| − |s| | <= bound is decided from squared lengths, without square roots (whose errno
/// handling keeps the loop from vectorising): with a = |t|² + |s|² − bound², it holds iff
/// a <= 0 or a² <= 4 |t|² |s|², i.e. iff min(a, a² − 4 |t|² |s|²) <= 0. Rotations about z
/// (kYawOnly) keep height differences and horizontal lengths separately: both must agree, so
/// the larger of the two excesses counts (only the sign matters).
template <bool kYawOnly>
void test_row(const Columns& s, const Columns& t, std::size_t i, double bound,
              std::vector<double>& excess) {
    const std::size_t n = s.x.size();
    excess.resize(n);
    const double b2 = bound * bound;
    const double sxi = s.x[i], syi = s.y[i], szi = s.z[i];
    const double txi = t.x[i], tyi = t.y[i], tzi = t.z[i];
    for (std::size_t j = i + 1; j < n; ++j) {
        const double sx = s.x[j] - sxi, sy = s.y[j] - syi, sz = s.z[j] - szi;
        const double tx = t.x[j] - txi, ty = t.y[j] - tyi, tz = t.z[j] - tzi;
        const double s2 = sx * sx + sy * sy + (kYawOnly ? 0.0 : sz * sz);
        const double t2 = tx * tx + ty * ty + (kYawOnly ? 0.0 : tz * tz);
        const double a = t2 + s2 - b2;
        const double e = std::min(a, a * a - 4.0 * t2 * s2);
        excess[j] = kYawOnly ? std::max(e, std::abs(tz - sz) - bound) : e;
    }
}

/// For every i, the j > i consistent with it, ascending.
std::vector<std::vector<std::uint32_t>> upper_neighbors(std::span<const Eigen::Vector3d> source,
                                                        std::span<const Eigen::Vector3d> target,
                                                        double bound, bool yaw_only,
                                                        const ParallelConfig& parallel) {
    const std::size_t n = source.size();
    const Columns s(source);
    const Columns t(target);
    std::vector<std::vector<std::uint32_t>> upper(n);
    parallel_for(parallel, n, kRowGrain, [&](std::size_t begin, std::size_t end) {
        std::vector<double> excess;
        for (std::size_t i = begin; i < end; ++i) {
            if (yaw_only) {
                test_row<true>(s, t, i, bound, excess);
            } else {
                test_row<false>(s, t, i, bound, excess);
            }
            for (std::size_t j = i + 1; j < n; ++j) {
                if (excess[j] <= 0.0) upper[i].push_back(static_cast<std::uint32_t>(j));
            }
        }
    });
    return upper;
}

}  // namespace

UndirectedGraph build_consistency_graph(std::span<const Eigen::Vector3d> source,
                                        std::span<const Eigen::Vector3d> target, double bound,
                                        bool yaw_only, const ParallelConfig& parallel) {
    auto upper = upper_neighbors(source, target, bound, yaw_only, parallel);
    const std::size_t n = source.size();
    std::vector<std::size_t> degree(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        degree[i] += upper[i].size();
        for (std::uint32_t j : upper[i]) ++degree[j];
    }
    UndirectedGraph graph;
    graph.neighbors.resize(n);
    for (std::size_t i = 0; i < n; ++i) graph.neighbors[i].reserve(degree[i]);
    // Lower neighbours arrive in ascending i, then the (ascending) upper ones: sorted lists.
    for (std::size_t i = 0; i < n; ++i) {
        for (std::uint32_t j : upper[i])
            graph.neighbors[j].push_back(static_cast<std::uint32_t>(i));
    }
    for (std::size_t i = 0; i < n; ++i) {
        graph.neighbors[i].insert(graph.neighbors[i].end(), upper[i].begin(), upper[i].end());
        std::vector<std::uint32_t>().swap(upper[i]);
    }
    return graph;
}

}  // namespace scantling::registration::detail
