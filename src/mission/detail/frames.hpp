#pragma once
// Frame helpers shared by the vehicles' stacks (drone_stack.cpp, rov_stack.cpp).
#include <Eigen/Geometry>
#include <string_view>

#include <fmt/format.h>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>

namespace scantling::mission::detail {

inline double yaw_of(const Eigen::Matrix3d& R) { return euler_zyx_from_rotation(R).z(); }

/// The start pose with its roll and pitch removed: the odom frame of a stack's local EKF
/// (gravity-aligned, the start's heading). InputError naming `stack` for a non-finite pose.
inline Eigen::Isometry3d levelled(const Eigen::Isometry3d& T_world_body, std::string_view stack) {
    if (!T_world_body.matrix().allFinite()) {
        throw InputError(fmt::format("{}: the start pose is not finite", stack));
    }
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw_of(T_world_body.linear()), Eigen::Vector3d::UnitZ())
                     .toRotationMatrix();
    T.translation() = T_world_body.translation();
    return T;
}

}  // namespace scantling::mission::detail
