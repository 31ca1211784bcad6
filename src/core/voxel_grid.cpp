#include <scantling/core/error.hpp>
#include <scantling/core/voxel_grid.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "detail/voxel_sort.hpp"

namespace scantling {
namespace {

constexpr std::size_t kGrain = 1024;  // voxels per task: amortises scheduling

using detail::VoxelRuns;

template <typename T>
T mean_of(const std::vector<T>& field, std::span<const std::size_t> members) {
    T sum = field[members[0]];
    for (std::size_t i = 1; i < members.size(); ++i) sum += field[members[i]];
    return T(sum / static_cast<double>(members.size()));
}

/// Scalar fields stored as float are summed in double so large voxels do not lose precision.
float mean_scalar(const std::vector<float>& field, std::span<const std::size_t> members) {
    double sum = 0.0;
    for (std::size_t m : members) sum += field[m];
    return static_cast<float>(sum / static_cast<double>(members.size()));
}

Eigen::Vector3d mean_normal(const std::vector<Eigen::Vector3d>& normals,
                            std::span<const std::size_t> members) {
    const Eigen::Vector3d sum = mean_of(normals, members);
    const double norm = sum.norm();
    // Exactly opposing normals cancel: keep the voxel's first normal rather than a zero vector.
    return norm > 0.0 && std::isfinite(norm) ? Eigen::Vector3d(sum / norm) : normals[members[0]];
}

Rgb8 mean_color(const std::vector<Rgb8>& colors, std::span<const std::size_t> members) {
    using Sum = Eigen::Matrix<std::int64_t, 3, 1>;  // no overflow however many points
    Sum sum = Sum::Zero();
    for (std::size_t m : members) sum += colors[m].cast<std::int64_t>();
    const auto n = static_cast<std::int64_t>(members.size());
    return ((sum.array() + n / 2) / n).matrix().cast<std::uint8_t>();  // rounded, half up
}

/// Most common ring of the voxel (a mean ring index is meaningless); ties go to the lowest.
std::uint16_t mode_ring(const std::vector<std::uint16_t>& rings,
                        std::span<const std::size_t> members, std::vector<std::uint16_t>& buf) {
    buf.clear();
    for (std::size_t m : members) buf.push_back(rings[m]);
    std::sort(buf.begin(), buf.end());
    std::uint16_t best = buf[0];
    std::size_t best_count = 0;
    for (std::size_t i = 0; i < buf.size();) {
        std::size_t j = i;
        while (j < buf.size() && buf[j] == buf[i]) ++j;
        if (j - i > best_count) std::tie(best, best_count) = std::pair(buf[i], j - i);
        i = j;
    }
    return best;
}

void resize_like(const PointCloud& in, PointCloud& out, std::size_t n) {
    out.points.resize(n);
    if (in.has_normals()) out.normals.resize(n);
    if (in.has_covariances()) out.covariances.resize(n);
    if (in.has_intensities()) out.intensities.resize(n);
    if (in.has_rings()) out.rings.resize(n);
    if (in.has_times()) out.times_s.resize(n);
    if (in.has_colors()) out.colors.resize(n);
}

void reduce_voxel(const PointCloud& in, std::span<const std::size_t> members, std::size_t v,
                  PointCloud& out, std::vector<std::uint16_t>& ring_buf) {
    out.points[v] = mean_of(in.points, members);
    if (in.has_normals()) out.normals[v] = mean_normal(in.normals, members);
    if (in.has_covariances()) out.covariances[v] = mean_of(in.covariances, members);
    if (in.has_intensities()) out.intensities[v] = mean_scalar(in.intensities, members);
    if (in.has_rings()) out.rings[v] = mode_ring(in.rings, members, ring_buf);
    if (in.has_times()) out.times_s[v] = mean_scalar(in.times_s, members);
    if (in.has_colors()) out.colors[v] = mean_color(in.colors, members);
}

PointCloud reduce_runs(const PointCloud& in, const VoxelRuns& runs, const ParallelConfig& par) {
    PointCloud out;
    out.stamp_s = in.stamp_s;
    resize_like(in, out, runs.count());
    parallel_for(par, runs.count(), kGrain, [&](std::size_t b, std::size_t e) {
        std::vector<std::uint16_t> ring_buf;
        for (std::size_t v = b; v < e; ++v) reduce_voxel(in, runs.members(v), v, out, ring_buf);
    });
    return out;
}

}  // namespace

void VoxelGridConfig::validate(std::string_view prefix) const {
    if (!(voxel_size_m > 0.0) || !std::isfinite(voxel_size_m)) {
        throw ConfigError(
            fmt::format("{}.voxel_size_m = {}, expected finite > 0", prefix, voxel_size_m));
    }
    parallel.validate(fmt::format("{}.parallel", prefix));
}

PointCloud voxel_downsample(const PointCloud& cloud, const VoxelGridConfig& config) {
    config.validate();
    check_consistent(cloud, "voxel_downsample");
    if (cloud.empty()) {
        PointCloud out;
        out.stamp_s = cloud.stamp_s;
        return out;
    }
    const VoxelRuns runs = detail::sort_into_voxels(cloud, config.voxel_size_m, config.parallel);
    return reduce_runs(cloud, runs, config.parallel);
}

PointCloud voxel_downsample(const PointCloud& cloud, double voxel_size_m) {
    VoxelGridConfig config;
    config.voxel_size_m = voxel_size_m;
    return voxel_downsample(cloud, config);
}

}  // namespace scantling
