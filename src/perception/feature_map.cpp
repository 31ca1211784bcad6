#include <scantling/perception/feature_map.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::perception {
namespace {

// Cell coordinates are packed in 21 bits each (±1e6 cells: ±40 km at 4 cm).
constexpr std::int64_t kCellBias = 1 << 20;
constexpr std::uint64_t kCellMask = (std::uint64_t{1} << 21) - 1;

std::uint64_t pack(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x + kCellBias) & kCellMask) |
           ((static_cast<std::uint64_t>(y + kCellBias) & kCellMask) << 21) |
           ((static_cast<std::uint64_t>(z + kCellBias) & kCellMask) << 42);
}

}  // namespace

void FeatureMapConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(merge_radius_m, prefix, "merge_radius_m");
    require_count_at_least(min_observations, 1, prefix, "min_observations");
    require_count_at_least(culling_window_frames, 1, prefix, "culling_window_frames");
    require(std::isfinite(min_found_ratio) && min_found_ratio >= 0.0 && min_found_ratio <= 1.0,
            prefix, "min_found_ratio", min_found_ratio, "in [0, 1]");
    intrinsics.validate(fmt::format("{}.intrinsics", prefix));
    require_positive(min_depth_m, prefix, "min_depth_m");
    require(std::isfinite(max_depth_m) && max_depth_m > min_depth_m, prefix, "max_depth_m",
            max_depth_m, fmt::format("finite and > min_depth_m = {}", min_depth_m));
    require(max_view_angle_rad > 0.0 && max_view_angle_rad <= std::numbers::pi, prefix,
            "max_view_angle_rad", max_view_angle_rad, "in (0, pi]");
}

FeatureMap::FeatureMap(FeatureMapConfig config) : config_(std::move(config)) { config_.validate(); }

FeatureMap::CellKey FeatureMap::key_of(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d c = (p / config_.merge_radius_m).array().floor();
    return pack(static_cast<std::int64_t>(c.x()), static_cast<std::int64_t>(c.y()),
                static_cast<std::int64_t>(c.z()));
}

std::size_t FeatureMap::nearest(const Eigen::Vector3d& p_world) const {
    const Eigen::Vector3d c = (p_world / config_.merge_radius_m).array().floor();
    std::size_t best = points_.size();
    double best_d2 = config_.merge_radius_m * config_.merge_radius_m;
    for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dz = -1; dz <= 1; ++dz) {
                const auto it = cells_.find(pack(static_cast<std::int64_t>(c.x()) + dx,
                                                 static_cast<std::int64_t>(c.y()) + dy,
                                                 static_cast<std::int64_t>(c.z()) + dz));
                if (it == cells_.end()) continue;
                for (const std::size_t i : it->second) {
                    const double d2 = (points_[i].p_world - p_world).squaredNorm();
                    // Ties go to the older point (lower index), whatever the cell order.
                    if (d2 < best_d2 || (d2 == best_d2 && best != points_.size() && i < best)) {
                        best_d2 = d2;
                        best = i;
                    }
                }
            }
        }
    }
    return best;
}

void FeatureMap::unhash(std::size_t index) {
    std::vector<std::size_t>& cell = cells_[key_of(points_[index].p_world)];
    cell.erase(std::find(cell.begin(), cell.end(), index));
}

void FeatureMap::observe(std::size_t index, const Eigen::Vector3d& p_world,
                         const Eigen::Vector3d& ray) {
    MapPoint& point = points_[index];
    const CellKey before = key_of(point.p_world);
    ++point.observations;
    point.p_world += (p_world - point.p_world) / static_cast<double>(point.observations);
    point.view_sum += ray;
    point.last_observed_frame = num_frames_;
    const CellKey after = key_of(point.p_world);
    if (after != before) {
        std::vector<std::size_t>& cell = cells_[before];
        cell.erase(std::find(cell.begin(), cell.end(), index));
        cells_[after].push_back(index);
    }
}

void FeatureMap::create(const Eigen::Vector3d& p_world, const Eigen::Vector3d& ray) {
    MapPoint point;
    point.p_world = p_world;
    point.view_sum = ray;
    point.observations = 1;
    point.visible = 1;
    point.first_frame = num_frames_;
    point.last_observed_frame = num_frames_;
    cells_[key_of(p_world)].push_back(points_.size());
    candidates_.push_back(points_.size());
    points_.push_back(point);
}

bool FeatureMap::should_see(const MapPoint& point, const Eigen::Isometry3d& T_camera_world,
                            const Eigen::Vector3d& camera_world) const {
    const Eigen::Vector3d p_camera = T_camera_world * point.p_world;
    if (p_camera.z() < config_.min_depth_m || p_camera.z() > config_.max_depth_m) return false;
    if (!config_.intrinsics.project(p_camera)) return false;
    const Eigen::Vector3d ray = (point.p_world - camera_world).normalized();
    const Eigen::Vector3d mean = point.view_sum.normalized();
    return ray.dot(mean) >= std::cos(config_.max_view_angle_rad);
}

void FeatureMap::judge_candidates(const Eigen::Isometry3d& T_world_camera,
                                  FeatureFrameStats& stats) {
    const Eigen::Isometry3d T_camera_world = T_world_camera.inverse();
    std::vector<std::size_t> kept;
    kept.reserve(candidates_.size());
    for (const std::size_t i : candidates_) {
        MapPoint& point = points_[i];
        if (point.first_frame != num_frames_) {  // creation already counted as visible
            if (point.last_observed_frame == num_frames_ ||
                should_see(point, T_camera_world, T_world_camera.translation())) {
                ++point.visible;
            }
        }
        const double found_ratio =
            static_cast<double>(point.observations) / static_cast<double>(point.visible);
        const bool judged = num_frames_ - point.first_frame >= config_.culling_window_frames;
        if (found_ratio < config_.min_found_ratio ||
            (judged && point.observations < config_.min_observations)) {
            point.alive = false;
            unhash(i);
            ++stats.culled;
        } else if (judged) {
            point.confirmed = true;
            ++num_confirmed_;
            ++stats.confirmed;
        } else {
            kept.push_back(i);
        }
    }
    candidates_ = std::move(kept);
}

FeatureFrameStats FeatureMap::insert(std::span<const Eigen::Vector3d> points_camera,
                                     const Eigen::Isometry3d& T_world_camera) {
    if (!T_world_camera.matrix().allFinite()) {
        throw InputError("feature_map.insert: T_world_camera is not finite");
    }
    FeatureFrameStats stats;
    stats.frame_points = points_camera.size();
    const Eigen::Vector3d camera_world = T_world_camera.translation();
    for (std::size_t k = 0; k < points_camera.size(); ++k) {
        if (!points_camera[k].allFinite()) {
            throw InputError(fmt::format("feature_map.insert: point {} is not finite", k));
        }
        const Eigen::Vector3d p_world = T_world_camera * points_camera[k];
        const Eigen::Vector3d ray = (p_world - camera_world).normalized();
        const std::size_t j = nearest(p_world);
        if (j == points_.size()) {
            create(p_world, ray);
            ++stats.created;
        } else if (points_[j].last_observed_frame == num_frames_) {
            ++stats.dropped;
        } else {
            observe(j, p_world, ray);
            ++stats.observed;
        }
    }
    judge_candidates(T_world_camera, stats);
    ++num_frames_;
    return stats;
}

PointCloud FeatureMap::confirmed_cloud() const {
    PointCloud cloud;
    cloud.points.reserve(num_confirmed_);
    for (const MapPoint& point : points_) {
        if (point.alive && point.confirmed) cloud.points.push_back(point.p_world);
    }
    return cloud;
}

}  // namespace scantling::perception
