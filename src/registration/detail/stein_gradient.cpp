#include "stein_gradient.hpp"

#include "back_faces.hpp"

namespace scantling::registration::detail {

EulerPose make_euler_pose(const Vector6d& params) {
    EulerPose pose;
    pose.R_x = Eigen::AngleAxisd(params[3], Eigen::Vector3d::UnitX()).toRotationMatrix();
    pose.R_y = Eigen::AngleAxisd(params[4], Eigen::Vector3d::UnitY()).toRotationMatrix();
    pose.R_z = Eigen::AngleAxisd(params[5], Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.R = pose.R_z * pose.R_y * pose.R_x;
    pose.t = params.head<3>();
    return pose;
}

namespace {

/// d(R p)/d(roll, pitch, yaw): d R_x/d roll = R_x hat(e_x), and so on.
Eigen::Matrix3d rotated_point_jacobian(const EulerPose& pose, const Eigen::Vector3d& p_source) {
    Eigen::Matrix3d dRp;
    dRp.col(0) = pose.R * Eigen::Vector3d::UnitX().cross(p_source);
    dRp.col(1) = pose.R_z * pose.R_y * Eigen::Vector3d::UnitY().cross(pose.R_x * p_source);
    dRp.col(2) = Eigen::Vector3d::UnitZ().cross(pose.R * p_source);
    return dRp;
}

}  // namespace

Vector6d residual_sq_gradient(const EulerPose& pose, const Eigen::Vector3d& p_source,
                              const Eigen::Vector3d& q_target, const Eigen::Vector3d* normal) {
    const Eigen::Vector3d Rp = pose.R * p_source;
    const Eigen::Vector3d e = Rp + pose.t - q_target;
    const Eigen::Matrix3d dRp = rotated_point_jacobian(pose, p_source);
    // Both costs are eᵀ W e with W = I or n nᵀ: the gradient is 2 (W e)ᵀ d(e).
    const Eigen::Vector3d We = normal != nullptr ? Eigen::Vector3d(normal->dot(e) * *normal) : e;
    Vector6d g;
    g.head<3>() = 2.0 * We;
    g.tail<3>() = 2.0 * dRp.transpose() * We;
    return g;
}

Matrix6d residual_information(const EulerPose& pose, const Eigen::Vector3d& p_source,
                              const Eigen::Vector3d* normal) {
    Eigen::Matrix<double, 3, 6> J;
    J.leftCols<3>().setIdentity();
    J.rightCols<3>() = rotated_point_jacobian(pose, p_source);
    if (normal == nullptr) return J.transpose() * J;
    const Eigen::Matrix<double, 1, 6> Jn = normal->transpose() * J;
    return Jn.transpose() * Jn;
}

BatchGradient batch_gradient(const Vector6d& params, std::span<const Eigen::Vector3d> source,
                             std::span<const std::size_t> indices, const KdTree& target_tree,
                             std::span<const Eigen::Vector3d> target_normals, double max_distance_m,
                             BackFaces back_faces) {
    const EulerPose pose = make_euler_pose(params);
    const double max_sq = max_distance_m * max_distance_m;
    const auto& target = target_tree.points();
    FaceSearchBuffers buffers;
    BatchGradient out;
    for (const std::size_t i : indices) {
        const auto nn = face_aware_nearest(target_tree, target_normals, pose.R * source[i] + pose.t,
                                           pose.t, max_sq, back_faces, buffers);
        if (!nn) continue;
        const Eigen::Vector3d* n = target_normals.empty() ? nullptr : &target_normals[nn->index];
        const Vector6d g = residual_sq_gradient(pose, source[i], target[nn->index], n);
        out.sum += g;
        out.sum_outer += g * g.transpose();
        out.information += residual_information(pose, source[i], n);
        ++out.num_inliers;
    }
    return out;
}

}  // namespace scantling::registration::detail
