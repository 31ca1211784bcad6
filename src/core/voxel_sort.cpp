#include <scantling/core/error.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "detail/voxel_sort.hpp"

namespace scantling::detail {
namespace {

// Voxel indices are kept well inside int64 so that (max - min) cannot overflow either.
constexpr double kMaxVoxelIndex = 4.0e18;
constexpr std::size_t kGrain = 4096;  // points per task: amortises scheduling

using VoxelIndex = Eigen::Matrix<std::int64_t, 3, 1>;

/// Bounds of a range of points, plus a probe that is 0 exactly when every coordinate is
/// finite (x - x is NaN for NaN and ±inf): finiteness is checked in the same pass.
struct Bounds {
    Eigen::Array3d min = Eigen::Array3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Array3d max = Eigen::Array3d::Constant(-std::numeric_limits<double>::infinity());
    double finite_probe = 0.0;
};

Bounds range_bounds(const Eigen::Vector3d* p, std::size_t n) {
    Bounds b;
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Array3d a = p[i].array();
        b.min = b.min.min(a);
        b.max = b.max.max(a);
        b.finite_probe += (a - a).sum();
    }
    return b;
}

Bounds parallel_bounds(const PointCloud& cloud, const ParallelConfig& par) {
    Bounds b = parallel_reduce_ordered(
        par, cloud.size(), kGrain, Bounds{},
        [&](std::size_t begin, std::size_t end) {
            return range_bounds(cloud.points.data() + begin, end - begin);
        },
        [](Bounds a, const Bounds& c) {
            a.min = a.min.min(c.min);
            a.max = a.max.max(c.max);
            a.finite_probe += c.finite_probe;
            return a;
        });
    if (!(b.finite_probe == 0.0)) check_finite(cloud, "voxel_downsample");  // throws
    return b;
}

/// floor(q) for |q| < 2^63 without a libm call.
std::int64_t floor_to_int(double q) {
    const auto t = static_cast<std::int64_t>(q);
    return t - static_cast<std::int64_t>(static_cast<double>(t) > q);
}

VoxelIndex voxel_index(const Eigen::Vector3d& p, double voxel_size_m) {
    // Division (not multiplication by the inverse) so boundaries are exactly k * voxel_size_m.
    return {floor_to_int(p.x() / voxel_size_m), floor_to_int(p.y() / voxel_size_m),
            floor_to_int(p.z() / voxel_size_m)};
}

/// The grid's index range: each axis' index is offset by its minimum and packed into
/// `bits[axis]` bits of a sort key.
struct GridLayout {
    VoxelIndex min_index = VoxelIndex::Zero();
    std::array<int, 3> bits{};

    int total_bits() const { return bits[0] + bits[1] + bits[2]; }
};

GridLayout make_layout(const Bounds& bounds, double voxel_size_m) {
    GridLayout layout;
    for (int a = 0; a < 3; ++a) {
        const double lo = std::floor(bounds.min[a] / voxel_size_m);
        const double hi = std::floor(bounds.max[a] / voxel_size_m);
        if (std::abs(lo) > kMaxVoxelIndex || std::abs(hi) > kMaxVoxelIndex) {
            throw InputError(fmt::format(
                "voxel_downsample: coordinate range [{}, {}] m on axis {} spans voxel indices "
                "beyond +-{:.0e} at voxel_size_m = {}; use a larger voxel or recentre the cloud",
                bounds.min[a], bounds.max[a], a, kMaxVoxelIndex, voxel_size_m));
        }
        layout.min_index[a] = static_cast<std::int64_t>(lo);
        const auto span =
            static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - layout.min_index[a]);
        layout.bits[a] = static_cast<int>(std::bit_width(span));
    }
    return layout;
}

/// v << s, and 0 for s = 64 (possible only for a zero-width field, whose value is 0).
std::uint64_t shift_left(std::uint64_t v, int s) { return s >= 64 ? 0 : v << s; }

/// One 64-bit item per point: voxel key in the high bits, point index in the low `index_bits`,
/// so sorting the items sorts by voxel and then by point index.
std::vector<std::uint64_t> packed_items(const PointCloud& cloud, double voxel_size_m,
                                        const GridLayout& layout, int index_bits,
                                        const ParallelConfig& par) {
    std::vector<std::uint64_t> items(cloud.size());
    const int shift_x = layout.bits[1] + layout.bits[2] + index_bits;
    const int shift_y = layout.bits[2] + index_bits;
    parallel_for(par, items.size(), kGrain, [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) {
            const VoxelIndex v = voxel_index(cloud.points[i], voxel_size_m) - layout.min_index;
            const auto u = [&](int a) { return static_cast<std::uint64_t>(v[a]); };
            items[i] = shift_left(u(0), shift_x) | shift_left(u(1), shift_y) |
                       shift_left(u(2), index_bits) | i;
        }
    });
    return items;
}

/// Fixed cut of [0, n) into chunks for the radix sort: enough to keep two threads busy, few
/// enough that the per-chunk histograms stay small. The sorted result does not depend on it.
struct Chunks {
    std::size_t n = 0;
    std::size_t count = 1;
    std::size_t size = 0;

    explicit Chunks(std::size_t items)
        : n(items),
          count(std::clamp<std::size_t>(items / 16384, 1, 16)),
          size((items + count - 1) / count) {}
    std::size_t begin(std::size_t c) const { return std::min(n, c * size); }
    std::size_t end(std::size_t c) const { return std::min(n, (c + 1) * size); }
};

/// Stable LSD radix sort on bits [low_bit, low_bit + key_bits). Each pass counts digits per
/// chunk, turns the counts into write offsets in (digit, chunk) order and scatters every chunk
/// from its own offsets: chunks run in parallel and the result is the one stable order
/// whatever the thread count. A pass whose digit is the same for every item is skipped.
void radix_sort(std::vector<std::uint64_t>& items, int low_bit, int key_bits,
                const ParallelConfig& par) {
    if (key_bits == 0) return;
    const int passes = (key_bits + 10) / 11;  // <= 2048 buckets: a histogram stays in L1
    const int digit_bits = (key_bits + passes - 1) / passes;
    const std::size_t buckets = std::size_t{1} << digit_bits;
    const std::uint64_t mask = buckets - 1;
    const Chunks chunks(items.size());
    std::vector<std::size_t> offsets(chunks.count * buckets);
    std::vector<std::uint64_t> scratch(items.size());
    for (int p = 0; p < passes; ++p) {
        const int shift = low_bit + p * digit_bits;
        const auto digit = [&](std::uint64_t it) { return (it >> shift) & mask; };
        parallel_for(par, chunks.count, 1, [&](std::size_t c_begin, std::size_t c_end) {
            for (std::size_t c = c_begin; c < c_end; ++c) {
                std::size_t* h = &offsets[c * buckets];
                std::fill(h, h + buckets, std::size_t{0});
                for (std::size_t i = chunks.begin(c); i < chunks.end(c); ++i) ++h[digit(items[i])];
            }
        });
        std::size_t next = 0;
        bool one_digit = false;
        for (std::size_t d = 0; d < buckets; ++d) {
            const std::size_t first = next;
            for (std::size_t c = 0; c < chunks.count; ++c) {
                next += std::exchange(offsets[c * buckets + d], next);
            }
            one_digit = one_digit || next - first == items.size();
        }
        if (one_digit) continue;
        parallel_for(par, chunks.count, 1, [&](std::size_t c_begin, std::size_t c_end) {
            for (std::size_t c = c_begin; c < c_end; ++c) {
                std::size_t* h = &offsets[c * buckets];
                for (std::size_t i = chunks.begin(c); i < chunks.end(c); ++i)
                    scratch[h[digit(items[i])]++] = items[i];
            }
        });
        items.swap(scratch);
    }
}

VoxelRuns runs_from_packed(const PointCloud& cloud, double voxel_size_m, const GridLayout& layout,
                           int index_bits, const ParallelConfig& par) {
    std::vector<std::uint64_t> items = packed_items(cloud, voxel_size_m, layout, index_bits, par);
    radix_sort(items, index_bits, layout.total_bits(), par);
    const std::uint64_t index_mask = (std::uint64_t{1} << index_bits) - 1;
    const auto starts_voxel = [&](std::size_t i) {
        return i == 0 || (items[i] >> index_bits) != (items[i - 1] >> index_bits);
    };
    VoxelRuns runs;
    runs.order.resize(items.size());
    // Two passes over the same chunks: count each chunk's voxel starts, then write them from
    // the chunk's offset, so the parallel result is the serial one.
    const Chunks chunks(items.size());
    std::vector<std::size_t> first_run(chunks.count + 1, 0);
    parallel_for(par, chunks.count, 1, [&](std::size_t c_begin, std::size_t c_end) {
        for (std::size_t c = c_begin; c < c_end; ++c) {
            std::size_t count = 0;
            for (std::size_t i = chunks.begin(c); i < chunks.end(c); ++i) {
                runs.order[i] = static_cast<std::size_t>(items[i] & index_mask);
                count += starts_voxel(i);
            }
            first_run[c + 1] = count;
        }
    });
    std::partial_sum(first_run.begin(), first_run.end(), first_run.begin());
    runs.starts.resize(first_run.back() + 1);
    parallel_for(par, chunks.count, 1, [&](std::size_t c_begin, std::size_t c_end) {
        for (std::size_t c = c_begin; c < c_end; ++c) {
            std::size_t next = first_run[c];
            for (std::size_t i = chunks.begin(c); i < chunks.end(c); ++i) {
                if (starts_voxel(i)) runs.starts[next++] = i;
            }
        }
    });
    runs.starts.back() = items.size();
    return runs;
}

/// Fallback when key and index do not fit 64 bits (huge extent relative to the voxel, or a
/// huge cloud): a comparison sort on the (x, y, z, index) tuple, same order as the packed path.
VoxelRuns runs_from_tuples(const PointCloud& cloud, double voxel_size_m,
                           const ParallelConfig& par) {
    std::vector<VoxelIndex> index(cloud.size());
    parallel_for(par, index.size(), kGrain, [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) index[i] = voxel_index(cloud.points[i], voxel_size_m);
    });
    const auto less = [&](std::size_t a, std::size_t b) {
        const VoxelIndex& u = index[a];
        const VoxelIndex& w = index[b];
        return std::tie(u.x(), u.y(), u.z(), a) < std::tie(w.x(), w.y(), w.z(), b);
    };
    VoxelRuns runs;
    runs.order.resize(cloud.size());
    std::iota(runs.order.begin(), runs.order.end(), std::size_t{0});
    std::sort(runs.order.begin(), runs.order.end(), less);
    for (std::size_t i = 0; i < runs.order.size(); ++i) {
        if (i == 0 || index[runs.order[i]] != index[runs.order[i - 1]]) runs.starts.push_back(i);
    }
    runs.starts.push_back(runs.order.size());
    return runs;
}

}  // namespace

VoxelRuns sort_into_voxels(const PointCloud& cloud, double voxel_size_m,
                           const ParallelConfig& parallel) {
    const GridLayout layout = make_layout(parallel_bounds(cloud, parallel), voxel_size_m);
    const int index_bits = static_cast<int>(std::bit_width(cloud.size() - 1));
    if (layout.total_bits() + index_bits <= 64) {
        return runs_from_packed(cloud, voxel_size_m, layout, index_bits, parallel);
    }
    return runs_from_tuples(cloud, voxel_size_m, parallel);
}

}  // namespace scantling::detail
