#include "back_faces.hpp"

namespace scantling::registration::detail {
namespace {

// A plate sampled alike on both faces puts about half of any 8 nearest points on the front.
constexpr std::size_t kFrontFaceNeighbors = 8;

/// The hidden face of a plate: its outward normal points away from the sensor at `origin`.
bool is_back_face(const KdTree& tree, std::span<const Eigen::Vector3d> normals, std::size_t j,
                  const Eigen::Vector3d& origin) {
    return normals[j].dot(origin - tree.points()[j]) <= 0.0;
}

}  // namespace

std::optional<Neighbor> face_aware_nearest(const KdTree& tree,
                                           std::span<const Eigen::Vector3d> normals,
                                           const Eigen::Vector3d& q, const Eigen::Vector3d& origin,
                                           double max_sq_m2, BackFaces mode,
                                           FaceSearchBuffers& buffers) {
    std::optional<Neighbor> nn = tree.nearest(q);
    if (!nn || nn->distance_sq_m2 > max_sq_m2) return std::nullopt;
    if (normals.empty() || mode == BackFaces::kKeep ||
        !is_back_face(tree, normals, nn->index, origin)) {
        return nn;
    }
    if (mode == BackFaces::kReject) return std::nullopt;
    const std::size_t n =
        tree.knn(q, kFrontFaceNeighbors, buffers.indices, buffers.distances_sq_m2);
    for (std::size_t k = 0; k < n && buffers.distances_sq_m2[k] <= max_sq_m2; ++k) {
        if (!is_back_face(tree, normals, buffers.indices[k], origin)) {
            return Neighbor{buffers.indices[k], buffers.distances_sq_m2[k]};
        }
    }
    return nn;  // no front face near: the normals are not oriented for this sensor
}

}  // namespace scantling::registration::detail
