#include <scantling/core/error.hpp>
#include <scantling/registration/fpfh.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "detail/config_checks.hpp"

namespace scantling::registration {
namespace {

constexpr std::size_t kGrain = 256;  // points per parallel chunk
constexpr int kBins = 11;
using Histogram = std::array<double, kFpfhDimension>;

/// Radius neighbours of every point, the point itself and duplicates removed, nearest first,
/// at most `stride` per point, stored with a fixed stride.
struct Neighborhoods {
    std::size_t stride = 0;
    std::vector<std::uint32_t> counts;
    std::vector<std::uint32_t> indices;
    std::vector<double> distances_m;
};

Neighborhoods find_neighborhoods(const KdTree& tree, const FpfhConfig& config) {
    const std::size_t n = tree.size();
    Neighborhoods nb;
    nb.stride = static_cast<std::size_t>(config.max_neighbors - 1);
    nb.counts.assign(n, 0);
    nb.indices.resize(n * nb.stride);
    nb.distances_m.resize(n * nb.stride);
    const auto order = tree.leaf_order();  // spatially coherent queries stay in cache
    const double radius_sq = config.radius_m * config.radius_m;
    parallel_for(config.parallel, n, kGrain, [&](std::size_t begin, std::size_t end) {
        std::vector<std::size_t> idx;
        std::vector<double> d2;
        for (std::size_t q = begin; q < end; ++q) {
            const std::size_t i = order[q];
            // k nearest, then cut at the radius: on dense clouds a radius search would collect
            // and sort thousands of points only to keep the nearest max_neighbors.
            tree.knn(tree.points()[i], nb.stride + 1, idx, d2);
            std::uint32_t c = 0;
            for (std::size_t k = 0; k < idx.size() && c < nb.stride; ++k) {
                if (d2[k] >= radius_sq) break;
                if (idx[k] == i || d2[k] == 0.0) continue;
                nb.indices[i * nb.stride + c] = static_cast<std::uint32_t>(idx[k]);
                nb.distances_m[i * nb.stride + c] = std::sqrt(d2[k]);
                ++c;
            }
            nb.counts[i] = c;
        }
    });
    return nb;
}

int bin_of(double value, double low, double high) {
    const int b = static_cast<int>(std::floor(kBins * (value - low) / (high - low)));
    return std::clamp(b, 0, kBins - 1);
}

// Below this difference of |cos| the two normals count as equally inclined to the line. Then
// p stays the source of the frame: near-parallel normals (neighbouring points often get
// bit-identical normals from identical neighbourhoods) otherwise flip phi's sign on rounding
// noise, so a rotated copy of the cloud would get different histograms.
constexpr double kTieCos = 1e-12;

/// Adds the pair (p, n) → (q, m) at distance `d` (> 0) to `hist` with weight `incr`. The source
/// of the Darboux frame is the point whose normal makes the smaller angle with the line (|cos|
/// larger), as in PCL and Open3D, which makes the features symmetric in the pair.
void add_pair(const Eigen::Vector3d& p, const Eigen::Vector3d& n, const Eigen::Vector3d& q,
              const Eigen::Vector3d& m, double d, double incr, Histogram& hist) {
    Eigen::Vector3d line = (q - p) / d;
    const double cos1 = n.dot(line);
    const double cos2 = m.dot(line);
    Eigen::Vector3d u = n;
    Eigen::Vector3d target_normal = m;
    double phi = cos1;
    if (std::abs(cos1) < std::abs(cos2) - kTieCos) {
        u = m;
        target_normal = n;
        line = -line;
        phi = -cos2;
    }
    Eigen::Vector3d v = line.cross(u);
    const double v_norm = v.norm();
    double theta = 0.0;
    double alpha = 0.0;
    if (v_norm != 0.0) {  // degenerate pair: all features 0, as in Open3D
        v /= v_norm;
        const Eigen::Vector3d w = u.cross(v);
        alpha = v.dot(target_normal);
        theta = std::atan2(w.dot(target_normal), u.dot(target_normal));
    } else {
        phi = 0.0;
    }
    hist[bin_of(theta, -std::numbers::pi, std::numbers::pi)] += incr;
    hist[kBins + bin_of(alpha, -1.0, 1.0)] += incr;
    hist[2 * kBins + bin_of(phi, -1.0, 1.0)] += incr;
}

Histogram spfh_of(const PointCloud& cloud, const Neighborhoods& nb, std::size_t i) {
    Histogram hist{};
    const std::uint32_t count = nb.counts[i];
    if (count == 0) return hist;
    const double incr = 100.0 / count;
    for (std::size_t k = 0; k < count; ++k) {
        const std::size_t j = nb.indices[i * nb.stride + k];
        add_pair(cloud.points[i], cloud.normals[i], cloud.points[j], cloud.normals[j],
                 nb.distances_m[i * nb.stride + k], incr, hist);
    }
    return hist;
}

void fpfh_of(const std::vector<Histogram>& spfh, const Neighborhoods& nb, std::size_t i,
             FpfhWeighting weighting, float* out) {
    const std::uint32_t count = nb.counts[i];
    if (count == 0) return;  // the column stays zero, as in Open3D
    Histogram sum{};
    for (std::size_t k = 0; k < count; ++k) {
        const double d = nb.distances_m[i * nb.stride + k];
        const double weight =
            weighting == FpfhWeighting::kInverseDistance ? 1.0 / d : 1.0 / (d * d);
        const Histogram& h = spfh[nb.indices[i * nb.stride + k]];
        for (int b = 0; b < kFpfhDimension; ++b) sum[b] += weight * h[b];
    }
    for (int block = 0; block < 3; ++block) {
        double total = 0.0;
        for (int b = 0; b < kBins; ++b) total += sum[block * kBins + b];
        const double scale = total > 0.0 ? 100.0 / total : 0.0;
        for (int b = block * kBins; b < (block + 1) * kBins; ++b) {
            out[b] = static_cast<float>(sum[b] * scale + spfh[i][b]);
        }
    }
}

void check_input(const PointCloud& cloud, const KdTree& tree) {
    check_usable(cloud, "fpfh cloud");
    if (!cloud.has_normals()) {
        throw InputError(
            "fpfh cloud: normals missing, expected one unit normal per point "
            "(see core/normals.hpp)");
    }
    if (tree.size() != cloud.size()) {
        throw InputError(fmt::format("fpfh: tree holds {} points, expected the cloud's {}",
                                     tree.size(), cloud.size()));
    }
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!cloud.normals[i].allFinite()) {
            throw InputError(fmt::format("fpfh cloud: normal {} is not finite", i));
        }
    }
}

}  // namespace

void FpfhConfig::validate(std::string_view prefix) const {
    detail::require_positive(radius_m, prefix, "radius_m");
    detail::require_at_least(max_neighbors, 2, prefix, "max_neighbors");
    parallel.validate(fmt::format("{}.parallel", prefix));
}

FeatureMatrix compute_fpfh(const PointCloud& cloud, const FpfhConfig& config) {
    config.validate();
    check_usable(cloud, "fpfh cloud");
    const KdTree tree(cloud.points);
    return compute_fpfh(cloud, tree, config);
}

FeatureMatrix compute_fpfh(const PointCloud& cloud, const KdTree& tree, const FpfhConfig& config) {
    config.validate();
    check_input(cloud, tree);
    const Neighborhoods nb = find_neighborhoods(tree, config);
    std::vector<Histogram> spfh(cloud.size());
    parallel_for(config.parallel, cloud.size(), kGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) spfh[i] = spfh_of(cloud, nb, i);
    });
    FeatureMatrix features =
        FeatureMatrix::Zero(kFpfhDimension, static_cast<Eigen::Index>(cloud.size()));
    parallel_for(config.parallel, cloud.size(), kGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            fpfh_of(spfh, nb, i, config.weighting,
                    features.col(static_cast<Eigen::Index>(i)).data());
        }
    });
    return features;
}

}  // namespace scantling::registration
