#pragma once
// Analytic scenes for the next-best-view planner's tests (planning may not use the simulator):
// an axis-aligned box room with optional box obstacles, ray cast exactly, and depth frames of
// the planner's own camera model inserted into an OccupancyOctree.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <scantling/core/point_cloud.hpp>
#include <scantling/mapping/occupancy_octree.hpp>
#include <scantling/planning/nbv_planner.hpp>

namespace scantling::planning::test {

/// A closed room (the inside of `room`) holding solid boxes `obstacles`.
struct BoxScene {
    Eigen::AlignedBox3d room;
    std::vector<Eigen::AlignedBox3d> obstacles;

    /// Distance from `o` (inside the room, outside every obstacle) along unit `d` to the first
    /// surface.
    double range(const Eigen::Vector3d& o, const Eigen::Vector3d& d) const {
        double t = std::numeric_limits<double>::infinity();
        for (int i = 0; i < 3; ++i) {
            if (d[i] > 0.0) t = std::min(t, (room.max()[i] - o[i]) / d[i]);
            if (d[i] < 0.0) t = std::min(t, (room.min()[i] - o[i]) / d[i]);
        }
        for (const Eigen::AlignedBox3d& box : obstacles) t = std::min(t, entry(box, o, d));
        return t;
    }

    /// Slab method: the entry distance into `box`, infinity when missed.
    static double entry(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& o,
                        const Eigen::Vector3d& d) {
        double t_near = 0.0, t_far = std::numeric_limits<double>::infinity();
        for (int i = 0; i < 3; ++i) {
            if (d[i] == 0.0) {
                if (o[i] < box.min()[i] || o[i] > box.max()[i]) return t_far;
                continue;
            }
            double t0 = (box.min()[i] - o[i]) / d[i], t1 = (box.max()[i] - o[i]) / d[i];
            if (t0 > t1) std::swap(t0, t1);
            t_near = std::max(t_near, t0);
            t_far = std::min(t_far, t1);
        }
        return t_near <= t_far ? t_near : std::numeric_limits<double>::infinity();
    }

    /// Free volume: the room minus its obstacles (assumed inside it, disjoint), m³.
    double free_volume_m3() const {
        double v = room.volume();
        for (const auto& box : obstacles) v -= box.volume();
        return v;
    }
};

/// A depth frame of `camera`'s FOV (body convention, x forward), `width` × `height` rays on
/// the tangent grid, sensor frame; ranges beyond the scene stay (the map cuts them).
inline PointCloud depth_frame(const BoxScene& scene, const Eigen::Isometry3d& T_world_sensor,
                              const mapping::ViewFrustum& camera, int width = 96, int height = 72) {
    PointCloud cloud;
    const double tx = std::tan(camera.horizontal_fov_rad / 2.0);
    const double ty = std::tan(camera.vertical_fov_rad / 2.0);
    for (int v = 0; v < height; ++v) {
        for (int u = 0; u < width; ++u) {
            const Eigen::Vector3d d = Eigen::Vector3d(1.0, tx * (2.0 * (u + 0.5) / width - 1.0),
                                                      ty * (2.0 * (v + 0.5) / height - 1.0))
                                          .normalized();
            const double r = scene.range(T_world_sensor.translation(), T_world_sensor.linear() * d);
            cloud.points.push_back(d * std::min(r, 50.0));
        }
    }
    return cloud;
}

/// A full-sphere scan from `p_world` (1° × 1°): the vehicle looking around before exploring,
/// which also clears its own box.
inline void look_around(const BoxScene& scene, const Eigen::Vector3d& p_world,
                        mapping::OccupancyOctree& map) {
    PointCloud cloud;
    constexpr double kDeg = std::numbers::pi / 180.0;
    for (int e = -89; e <= 89; ++e) {
        for (int a = 0; a < 360; ++a) {
            const Eigen::Vector3d d(std::cos(e * kDeg) * std::cos(a * kDeg),
                                    std::cos(e * kDeg) * std::sin(a * kDeg), std::sin(e * kDeg));
            cloud.points.push_back(d * std::min(scene.range(p_world, d), 50.0));
        }
    }
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = p_world;
    map.insert_depth_frame(cloud, T);
}

/// Inserts the frame the planner's camera takes at `state`.
inline void observe(const BoxScene& scene, const NbvPlannerConfig& config, const NbvState& state,
                    mapping::OccupancyOctree& map) {
    const Eigen::Isometry3d T = nbv_camera_pose(config, state);
    map.insert_depth_frame(depth_frame(scene, T, config.camera), T);
}

/// Known volume (free or occupied) of the voxels centred inside `box`, m³.
inline double known_volume_m3(const mapping::OccupancyOctree& map, const Eigen::AlignedBox3d& box) {
    const double res = map.resolution_m();
    Eigen::Vector3d cells;
    for (int i = 0; i < 3; ++i)
        cells[i] = std::floor(box.max()[i] / res - 0.5) - std::ceil(box.min()[i] / res - 0.5) + 1;
    return cells.prod() * res * res * res - map.unknown_volume_in_m3(box);
}

}  // namespace scantling::planning::test
