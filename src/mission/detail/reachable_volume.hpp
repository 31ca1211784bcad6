#pragma once
// The exploration's ground truth (exploration_mission.hpp): the free voxels of the exploration
// volume that a point can reach from the take-off point, from the world's surfaces.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include <scantling/sim/ray_caster.hpp>

namespace scantling::mission::detail {

struct ReachableVolume {
    double resolution_m = 0.1;
    std::vector<Eigen::Vector3d> centres_world;  ///< of the reachable free voxels
    double volume_m3() const {
        return static_cast<double>(centres_world.size()) * resolution_m * resolution_m *
               resolution_m;
    }
};

/// Voxels of `resolution_m` tiling `bounds_world` from its min corner; a voxel is blocked when
/// a surface crosses it, found by casting rays through every voxel centre along the three axes
/// and marking the voxel of every hit (a plate thinner than a voxel is found wherever a line of
/// centres crosses it). The reachable ones are the free voxels 6-connected to the voxel holding
/// `start_world`. Empty when the start's voxel is blocked or outside the bounds.
/// Cost: O(lines · hits per line) casts plus O(voxels).
ReachableVolume reachable_free_volume(const sim::RayCaster& caster,
                                      const Eigen::AlignedBox3d& bounds_world, double resolution_m,
                                      const Eigen::Vector3d& start_world);

}  // namespace scantling::mission::detail
