#pragma once
/// @file
/// The correspondence search of IcpConfig::back_faces, shared by ICP and Stein-ICP (private).

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include <scantling/core/kdtree.hpp>
#include <scantling/registration/icp.hpp>

namespace scantling::registration::detail {

/// Scratch of the front-face search, reused across queries of one thread.
struct FaceSearchBuffers {
    std::vector<std::size_t> indices;
    std::vector<double> distances_sq_m2;
};

/// The target point to pair with `q` (target frame), at most sqrt(`max_sq_m2`) away: the
/// nearest, or per `mode` the nearest front-facing one among the 8 nearest (kPreferFront; the
/// nearest when none faces the sensor) or none (kReject) when the nearest faces away from the
/// sensor at `origin`. `normals` are the target's (empty: the nearest, whatever `mode`).
std::optional<Neighbor> face_aware_nearest(const KdTree& tree,
                                           std::span<const Eigen::Vector3d> normals,
                                           const Eigen::Vector3d& q, const Eigen::Vector3d& origin,
                                           double max_sq_m2, BackFaces mode,
                                           FaceSearchBuffers& buffers);

}  // namespace scantling::registration::detail
