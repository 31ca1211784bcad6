// The next-best-view gains (SPEC §8): E(M, ξ) per node in parallel into per-node slots, the
// defect weight μ, and Q accumulated serially along the tree (identical for any thread count).
#include <algorithm>
#include <cmath>

#include <scantling/core/parallel.hpp>
#include <scantling/planning/nbv_planner.hpp>

#include "detail/nbv.hpp"

namespace scantling::planning {
namespace {

using Eigen::Vector3d;

/// True when `p_camera` (camera frame, x forward) lies in the frustum's pyramid and reach.
bool in_frustum(const mapping::ViewFrustum& camera, const Vector3d& p_camera) {
    if (p_camera.x() <= 0.0 || p_camera.norm() > camera.max_depth_m) return false;
    return std::abs(std::atan2(p_camera.y(), p_camera.x())) <= camera.horizontal_fov_rad / 2.0 &&
           std::abs(std::atan2(p_camera.z(), p_camera.x())) <= camera.vertical_fov_rad / 2.0;
}

/// 1 / d for a point seen from the camera at `o_world`, else 0.
double defect_term(const mapping::OccupancyOctree& map, const mapping::ViewFrustum& camera,
                   const Eigen::Isometry3d& T_world_camera, const Vector3d& p_world) {
    if (!in_frustum(camera, T_world_camera.inverse() * p_world)) return 0.0;
    const Vector3d o_world = T_world_camera.translation();
    const double d_m = (p_world - o_world).norm();
    // One voxel diagonal towards the camera: a defect on a wall sits in (or just behind) the
    // wall's first occupied voxel, which must not hide it.
    const double pull_m = std::sqrt(3.0) * map.resolution_m();
    if (d_m > pull_m && !map.line_of_sight(o_world, p_world - (p_world - o_world) * (pull_m / d_m)))
        return 0.0;
    return 1.0 / std::max(d_m, map.resolution_m());
}

}  // namespace

Eigen::Isometry3d nbv_camera_pose(const NbvPlannerConfig& config, const NbvState& state) {
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    T_world_body.translation() = state.p_world_m;
    T_world_body.linear() = Eigen::AngleAxisd(state.yaw_rad, Vector3d::UnitZ()).toRotationMatrix();
    Eigen::Isometry3d T_body_camera = Eigen::Isometry3d::Identity();
    T_body_camera.translation() = config.p_body_camera_m;
    T_body_camera.linear() =
        Eigen::AngleAxisd(config.camera_pitch_rad, Vector3d::UnitY()).toRotationMatrix();
    return T_world_body * T_body_camera;
}

double nbv_defect_weight(const mapping::OccupancyOctree& map, const mapping::ViewFrustum& camera,
                         const Eigen::Isometry3d& T_world_camera,
                         std::span<const Eigen::Vector3d> interest_points_world) {
    double mu = 1.0;
    for (const Vector3d& p_world : interest_points_world)
        mu += defect_term(map, camera, T_world_camera, p_world);
    return mu;
}

namespace detail {

void evaluate_nbv_gains(const mapping::OccupancyOctree& map, const NbvPlannerConfig& config,
                        std::span<const Eigen::Vector3d> interest_points_world,
                        std::vector<NbvNode>& nodes, NbvStats& stats) {
    const Eigen::AlignedBox3d bounds(config.bounds_min_world_m, config.bounds_max_world_m);
    // Each index writes only its own node: the split among threads cannot change a value.
    parallel_for(config.parallel, nodes.size() - 1, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin + 1; i < end + 1; ++i) {
            const Eigen::Isometry3d T_world_camera = nbv_camera_pose(config, nodes[i].state);
            nodes[i].unknown_m3 =
                map.visible_unknown_volume(T_world_camera, config.camera, bounds).unknown_m3;
            nodes[i].mu =
                config.defect_aware
                    ? nbv_defect_weight(map, config.camera, T_world_camera, interest_points_world)
                    : 1.0;
        }
    });
    stats.gain_evaluations += nodes.size() - 1;
    // Q(n_k) = Q(n_{k−1}) + μ · E · exp(−λ c): parents precede children.
    for (std::size_t i = 1; i < nodes.size(); ++i) {
        NbvNode& n = nodes[i];
        n.value = nodes[static_cast<std::size_t>(n.parent)].value +
                  n.mu * n.unknown_m3 * std::exp(-config.lambda_per_m * n.edge_m);
    }
}

}  // namespace detail
}  // namespace scantling::planning
