#include <scantling/mapping/occupancy_octree.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <ostream>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <octomap/OcTree.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>

namespace scantling::mapping {
namespace {

// OctoMap's 16-level tree: keys 0 … 65535 per axis, voxel index i ↔ key i + 32768.
constexpr double kHalfKeyRange = 32768.0;
constexpr int kKeyOffset = 32768;

octomap::point3d to_point3d(const Eigen::Vector3d& p) {
    return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

void require_below(double value, double bound, std::string_view prefix, std::string_view field,
                   std::string_view bound_name) {
    config_checks::require(value < bound, prefix, field, value,
                           fmt::format("< {} = {}", bound_name, bound));
}

void require_above(double value, double bound, std::string_view prefix, std::string_view field,
                   std::string_view bound_name) {
    config_checks::require(value > bound, prefix, field, value,
                           fmt::format("> {} = {}", bound_name, bound));
}

struct LeafVolumes {
    double free_m3 = 0.0;
    double occupied_m3 = 0.0;
};

LeafVolumes leaf_volumes(const octomap::OcTree& tree) {
    LeafVolumes volumes;
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
        const double edge_m = it.getSize();
        (tree.isNodeOccupied(*it) ? volumes.occupied_m3 : volumes.free_m3) +=
            edge_m * edge_m * edge_m;
    }
    return volumes;
}

/// Unit rays of `view` in the camera frame (x forward), on an evenly spaced grid of the angles
/// atan(y / x) and atan(z / x): the edge rays are the edges of a pinhole's rectangular pyramid.
std::vector<Eigen::Vector3d> frustum_directions(const ViewFrustum& view) {
    std::vector<Eigen::Vector3d> directions;
    directions.reserve(static_cast<std::size_t>(view.rays_horizontal) *
                       static_cast<std::size_t>(view.rays_vertical));
    const auto angle = [](double fov_rad, int i, int n) {
        return fov_rad * (static_cast<double>(i) / (n - 1) - 0.5);
    };
    for (int v = 0; v < view.rays_vertical; ++v) {
        const double tan_v = std::tan(angle(view.vertical_fov_rad, v, view.rays_vertical));
        for (int h = 0; h < view.rays_horizontal; ++h) {
            const double tan_h = std::tan(angle(view.horizontal_fov_rad, h, view.rays_horizontal));
            directions.push_back(Eigen::Vector3d(1.0, tan_h, tan_v).normalized());
        }
    }
    return directions;
}

/// The length, at most `length_m`, for which the ray from `o` (inside) along `d` stays in the
/// cube |x_i| <= half_extent_m.
double clip_to_cube(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double length_m,
                    double half_extent_m) {
    for (int i = 0; i < 3; ++i) {
        if (d[i] > 0.0) length_m = std::min(length_m, (half_extent_m - o[i]) / d[i]);
        if (d[i] < 0.0) length_m = std::min(length_m, (-half_extent_m - o[i]) / d[i]);
    }
    return length_m;
}

}  // namespace

void OccupancyOctreeConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(resolution_m, prefix, "resolution_m");
    require_positive(max_range_m, prefix, "max_range_m");
    // A sensor anywhere in the inner half of the map must reach no farther than its edge.
    require(max_range_m <= kHalfKeyRange / 2.0 * resolution_m, prefix, "max_range_m", max_range_m,
            fmt::format("<= 16384 · resolution_m = {} (half the map's half-extent)",
                        kHalfKeyRange / 2.0 * resolution_m));
    require(prob_hit > 0.5 && prob_hit < 1.0, prefix, "prob_hit", prob_hit, "in (0.5, 1)");
    require(prob_miss > 0.0 && prob_miss < 0.5, prefix, "prob_miss", prob_miss, "in (0, 0.5)");
    require_open_unit(occupied_threshold, prefix, "occupied_threshold");
    require(clamp_min > 0.0, prefix, "clamp_min", clamp_min, "> 0");
    require_below(clamp_min, occupied_threshold, prefix, "clamp_min", "occupied_threshold");
    require(clamp_max < 1.0, prefix, "clamp_max", clamp_max, "< 1");
    require_above(clamp_max, occupied_threshold, prefix, "clamp_max", "occupied_threshold");
}

void ViewFrustum::validate(std::string_view prefix) const {
    using namespace config_checks;
    // A FOV of pi or more has no pinhole pyramid (tan of ±pi/2 diverges).
    require(horizontal_fov_rad > 0.0 && horizontal_fov_rad < std::numbers::pi, prefix,
            "horizontal_fov_rad", horizontal_fov_rad, "in (0, pi)");
    require(vertical_fov_rad > 0.0 && vertical_fov_rad < std::numbers::pi, prefix,
            "vertical_fov_rad", vertical_fov_rad, "in (0, pi)");
    require_positive(max_depth_m, prefix, "max_depth_m");
    require_at_least(rays_horizontal, 2, prefix, "rays_horizontal");
    require_at_least(rays_vertical, 2, prefix, "rays_vertical");
}

struct OccupancyOctree::Impl {
    explicit Impl(const OccupancyOctreeConfig& c) : config(c), tree(c.resolution_m) {
        tree.setProbHit(c.prob_hit);
        tree.setProbMiss(c.prob_miss);
        tree.setClampingThresMin(c.clamp_min);
        tree.setClampingThresMax(c.clamp_max);
        tree.setOccupancyThres(c.occupied_threshold);
    }

    /// Rays must stay inside the map, or OctoMap drops them with a message on stderr.
    void check_origin(const Eigen::Vector3d& origin_world) const {
        const double reach_m = config.max_range_m + 2.0 * config.resolution_m;
        const double half_extent_m = kHalfKeyRange * config.resolution_m;
        if (origin_world.cwiseAbs().maxCoeff() + reach_m >= half_extent_m) {
            throw InputError(fmt::format(
                "occupancy_octree: sensor at ({}, {}, {}) m is within max_range_m of the map's "
                "edge (±{} m at resolution_m = {})",
                origin_world.x(), origin_world.y(), origin_world.z(), half_extent_m,
                config.resolution_m));
        }
    }

    /// Walks one ray's voxels from its origin, collecting the unknown ones into `unknown`, up
    /// to the first occupied one; true when an occupied voxel stopped it.
    bool walk_ray(const octomap::point3d& origin, const octomap::point3d& end, octomap::KeyRay& ray,
                  octomap::KeySet& unknown) const {
        if (!tree.computeRayKeys(origin, end, ray)) return false;  // not after clipping
        for (const octomap::OcTreeKey& key : ray) {
            const octomap::OcTreeNode* node = tree.search(key);
            if (node == nullptr) {
                unknown.insert(key);
            } else if (tree.isNodeOccupied(node)) {
                return true;
            }
        }
        return false;
    }

    OccupancyOctreeConfig config;
    octomap::OcTree tree;
};

OccupancyOctree::OccupancyOctree(const OccupancyOctreeConfig& config) {
    config.validate("occupancy_octree");
    impl_ = std::make_unique<Impl>(config);
}

OccupancyOctree::~OccupancyOctree() = default;
OccupancyOctree::OccupancyOctree(OccupancyOctree&&) noexcept = default;
OccupancyOctree& OccupancyOctree::operator=(OccupancyOctree&&) noexcept = default;

InsertStats OccupancyOctree::insert_depth_frame(const PointCloud& points_sensor,
                                                const Eigen::Isometry3d& T_world_sensor) {
    if (!T_world_sensor.matrix().allFinite())
        throw InputError("occupancy_octree: T_world_sensor is not finite");
    impl_->check_origin(T_world_sensor.translation());
    const OccupancyOctreeConfig& c = impl_->config;
    // A miss is cut (in double, before OctoMap's float maths) to a length that stays beyond
    // max_range_m even after discretisation moves it to its voxel centre (≤ 0.87 voxel), so
    // OctoMap clears up to max_range_m and never marks its end occupied; an enormous point
    // would otherwise overflow float.
    const double cut_m = c.max_range_m + 2.0 * c.resolution_m;
    InsertStats stats;
    octomap::Pointcloud cloud_world;
    cloud_world.reserve(points_sensor.size());
    for (const Eigen::Vector3d& p_sensor : points_sensor.points) {
        if (!p_sensor.allFinite()) {
            ++stats.dropped_non_finite;
            continue;
        }
        const double range_m = p_sensor.norm();
        const bool miss = range_m > c.max_range_m;
        stats.misses += miss ? 1 : 0;
        cloud_world.push_back(to_point3d(
            T_world_sensor * (miss ? Eigen::Vector3d(p_sensor * (cut_m / range_m)) : p_sensor)));
    }
    stats.points = cloud_world.size();
    impl_->tree.insertPointCloud(cloud_world, to_point3d(T_world_sensor.translation()),
                                 c.max_range_m, /*lazy_eval=*/false, c.discretize);
    return stats;
}

Occupancy OccupancyOctree::query(const Eigen::Vector3d& p_world) const {
    if (!p_world.allFinite()) {
        throw InputError(fmt::format("occupancy_octree: query point ({}, {}, {}) is not finite",
                                     p_world.x(), p_world.y(), p_world.z()));
    }
    octomap::OcTreeKey key;
    if (!impl_->tree.coordToKeyChecked(p_world.x(), p_world.y(), p_world.z(), key))
        return Occupancy::kUnknown;
    const octomap::OcTreeNode* node = impl_->tree.search(key);
    if (node == nullptr) return Occupancy::kUnknown;
    return impl_->tree.isNodeOccupied(node) ? Occupancy::kOccupied : Occupancy::kFree;
}

double OccupancyOctree::explored_volume_m3() const {
    const LeafVolumes volumes = leaf_volumes(impl_->tree);
    return volumes.free_m3 + volumes.occupied_m3;
}

double OccupancyOctree::free_volume_m3() const { return leaf_volumes(impl_->tree).free_m3; }

double OccupancyOctree::occupied_volume_m3() const { return leaf_volumes(impl_->tree).occupied_m3; }

double OccupancyOctree::unknown_volume_in_m3(const Eigen::AlignedBox3d& box_world) const {
    if (!box_world.min().allFinite() || !box_world.max().allFinite())
        throw InputError("occupancy_octree: unknown_volume_in_m3 box is not finite");
    const double res_m = impl_->config.resolution_m;
    // Voxel i spans [i, i + 1) · res_m; its centre is in the box when i + 0.5 ∈ [min, max] / res.
    std::array<long long, 3> first{}, last{};
    for (int axis = 0; axis < 3; ++axis) {
        first[axis] = static_cast<long long>(std::ceil(box_world.min()[axis] / res_m - 0.5));
        last[axis] = static_cast<long long>(std::floor(box_world.max()[axis] / res_m - 0.5));
        if (first[axis] > last[axis]) return 0.0;
        if (first[axis] < -kKeyOffset || last[axis] >= kKeyOffset) {
            throw InputError(fmt::format(
                "occupancy_octree: unknown_volume_in_m3 box exceeds the map's extent (±{} m)",
                kHalfKeyRange * res_m));
        }
    }
    std::size_t unknown = 0;
    for (long long x = first[0]; x <= last[0]; ++x) {
        for (long long y = first[1]; y <= last[1]; ++y) {
            for (long long z = first[2]; z <= last[2]; ++z) {
                const octomap::OcTreeKey key(static_cast<octomap::key_type>(x + kKeyOffset),
                                             static_cast<octomap::key_type>(y + kKeyOffset),
                                             static_cast<octomap::key_type>(z + kKeyOffset));
                unknown += impl_->tree.search(key) == nullptr ? 1 : 0;
            }
        }
    }
    return static_cast<double>(unknown) * res_m * res_m * res_m;
}

VisibleVolume OccupancyOctree::visible_unknown_volume(const Eigen::Isometry3d& T_world_camera,
                                                      const ViewFrustum& view) const {
    if (!T_world_camera.matrix().allFinite())
        throw InputError("occupancy_octree: visible_unknown_volume T_world_camera is not finite");
    view.validate("view_frustum");
    const double res_m = impl_->config.resolution_m;
    // One voxel inside the map's edge, so float rounding never puts a ray's end outside it.
    const double half_extent_m = (kHalfKeyRange - 1.0) * res_m;
    const Eigen::Vector3d o_world = T_world_camera.translation();
    if (o_world.cwiseAbs().maxCoeff() >= half_extent_m) {
        throw InputError(fmt::format(
            "occupancy_octree: visible_unknown_volume camera at ({}, {}, {}) m is outside the "
            "map (±{} m)",
            o_world.x(), o_world.y(), o_world.z(), half_extent_m));
    }
    VisibleVolume result;
    octomap::KeySet unknown;  // a voxel crossed by several rays counts once
    octomap::KeyRay ray;
    for (const Eigen::Vector3d& d_camera : frustum_directions(view)) {
        const Eigen::Vector3d d_world = T_world_camera.linear() * d_camera;
        const double length_m = clip_to_cube(o_world, d_world, view.max_depth_m, half_extent_m);
        const bool blocked = impl_->walk_ray(
            to_point3d(o_world), to_point3d(o_world + length_m * d_world), ray, unknown);
        ++result.rays;
        result.rays_blocked += blocked ? 1 : 0;
    }
    result.unknown_voxels = unknown.size();
    result.unknown_m3 = static_cast<double>(unknown.size()) * res_m * res_m * res_m;
    return result;
}

std::size_t OccupancyOctree::num_leaves() const { return impl_->tree.getNumLeafNodes(); }

double OccupancyOctree::resolution_m() const { return impl_->config.resolution_m; }

const OccupancyOctreeConfig& OccupancyOctree::config() const { return impl_->config; }

void OccupancyOctree::write_binary(const std::string& path) const {
    io::write_file_atomically(path, [&](std::ostream& out) {
        if (!impl_->tree.writeBinaryConst(out))
            throw FileError(path, "OctoMap could not write the tree");
    });
}

}  // namespace scantling::mapping
