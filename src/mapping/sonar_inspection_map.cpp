#include <scantling/mapping/sonar_inspection_map.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::mapping {
namespace {

bool axis_index(double v, double size_m, std::int32_t& out) {
    const double q = std::floor(v / size_m);
    if (q < std::numeric_limits<std::int32_t>::min() ||
        q > std::numeric_limits<std::int32_t>::max()) {
        return false;
    }
    out = static_cast<std::int32_t>(q);
    return true;
}

bool try_key(const Eigen::Vector3d& p, double size_m, CellKey& key) {
    return axis_index(p.x(), size_m, key.x) && axis_index(p.y(), size_m, key.y) &&
           axis_index(p.z(), size_m, key.z);
}

}  // namespace

void SonarInspectionMapConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(voxel_size_m, prefix, "voxel_size_m");
    require_count_at_least(min_points_per_voxel, 3, prefix, "min_points_per_voxel");
    require_positive(max_point_sigma_m, prefix, "max_point_sigma_m");
    require_count_at_least(max_voxels, 1, prefix, "max_voxels");
}

SonarInspectionMap::SonarInspectionMap(const SonarInspectionMapConfig& config) : config_(config) {
    config_.validate("sonar_map");
}

CellKey SonarInspectionMap::key_of(const Eigen::Vector3d& p_world) const {
    CellKey key;
    if (!p_world.allFinite() || !try_key(p_world, config_.voxel_size_m, key)) {
        throw InputError(fmt::format(
            "sonar_map: point ({}, {}, {}) is not finite or beyond the int32 voxel index range",
            p_world.x(), p_world.y(), p_world.z()));
    }
    return key;
}

void SonarInspectionMap::check_input(std::span<const Eigen::Vector3d> points_world,
                                     std::span<const double> sigma_m, double stamp_s) const {
    if (sigma_m.size() != points_world.size()) {
        throw InputError(
            fmt::format("sonar_map: sigma_m has {} values, expected {} (one per "
                        "points_world entry)",
                        sigma_m.size(), points_world.size()));
    }
    if (!std::isfinite(stamp_s)) {
        throw InputError(fmt::format("sonar_map: stamp_s = {}, expected finite", stamp_s));
    }
    for (std::size_t i = 0; i < points_world.size(); ++i) {
        const Eigen::Vector3d& p = points_world[i];
        CellKey key;
        if (!p.allFinite() || !try_key(p, config_.voxel_size_m, key)) {
            throw InputError(fmt::format(
                "sonar_map: points_world[{}] = ({}, {}, {}), expected finite within the int32 "
                "voxel index range",
                i, p.x(), p.y(), p.z()));
        }
        if (!std::isfinite(sigma_m[i]) || sigma_m[i] < 0.0) {
            throw InputError(
                fmt::format("sonar_map: sigma_m[{}] = {}, expected finite >= 0", i, sigma_m[i]));
        }
    }
}

SonarAddResult SonarInspectionMap::add(std::span<const Eigen::Vector3d> points_world,
                                       std::span<const double> sigma_m, double stamp_s) {
    check_input(points_world, sigma_m, stamp_s);  // all or nothing
    SonarAddResult result;
    for (std::size_t i = 0; i < points_world.size(); ++i) {
        if (sigma_m[i] > config_.max_point_sigma_m) {
            ++result.rejected_unreliable;
            continue;
        }
        const Eigen::Vector3d& p = points_world[i];
        const CellKey key = key_of(p);
        auto it = voxels_.find(key);
        if (it == voxels_.end()) {
            if (voxels_.size() >= config_.max_voxels) {
                ++result.refused_memory;
                continue;
            }
            it = voxels_.emplace(key, Accumulator{}).first;
            it->second.first_stamp_s = it->second.last_stamp_s = stamp_s;
            ++result.voxels_created;
        }
        Accumulator& acc = it->second;
        // Welford: stable where Σp pᵀ − n mean meanᵀ would cancel at hull coordinates.
        ++acc.n;
        const Eigen::Vector3d delta = p - acc.mean;
        acc.mean += delta / static_cast<double>(acc.n);
        acc.m2 += delta * (p - acc.mean).transpose();
        acc.sigma_sum_m += sigma_m[i];
        // min/max, not first/last seen: the stamps do not depend on the insertion order.
        acc.first_stamp_s = std::min(acc.first_stamp_s, stamp_s);
        acc.last_stamp_s = std::max(acc.last_stamp_s, stamp_s);
        ++result.added;
    }
    num_points_ += result.added;
    return result;
}

namespace {

SonarVoxel make_voxel(const CellKey& key, std::size_t n, const Eigen::Vector3d& mean,
                      const Eigen::Matrix3d& m2, double sigma_sum_m) {
    SonarVoxel v;
    v.key = key;
    v.num_points = n;
    v.mean_world_m = mean;
    const double nd = static_cast<double>(n);
    // Symmetrise: Welford's outer products agree only up to rounding.
    v.covariance_m2 = 0.5 * (m2 + m2.transpose()) / (nd - 1.0);
    v.mean_covariance_m2 = v.covariance_m2 / nd;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(v.covariance_m2);
    const double lambda_min = std::max(eig.eigenvalues()(0), 0.0);  // ascending order
    v.normal_world = eig.eigenvectors().col(0);
    v.normal_spread_m = std::sqrt(lambda_min);
    v.mean_point_sigma_m = sigma_sum_m / nd;
    v.uncertainty_m = std::sqrt(lambda_min / nd + v.mean_point_sigma_m * v.mean_point_sigma_m);
    return v;
}

}  // namespace

std::vector<SonarVoxel> SonarInspectionMap::voxels() const {
    std::vector<SonarVoxel> out;
    for (const auto& [key, acc] : voxels_) {
        if (acc.n < config_.min_points_per_voxel) continue;
        SonarVoxel v = make_voxel(key, acc.n, acc.mean, acc.m2, acc.sigma_sum_m);
        v.first_stamp_s = acc.first_stamp_s;
        v.last_stamp_s = acc.last_stamp_s;
        out.push_back(v);
    }
    std::sort(out.begin(), out.end(),
              [](const SonarVoxel& a, const SonarVoxel& b) { return a.key < b.key; });
    return out;
}

std::size_t SonarInspectionMap::num_existing_voxels() const {
    return static_cast<std::size_t>(std::count_if(voxels_.begin(), voxels_.end(), [&](auto& kv) {
        return kv.second.n >= config_.min_points_per_voxel;
    }));
}

void SonarInspectionMap::clear() {
    voxels_.clear();
    num_points_ = 0;
}

}  // namespace scantling::mapping
