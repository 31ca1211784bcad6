#pragma once
// Input contracts shared by the trajectory metrics (trajectory_metrics.cpp) and the alignment
// and association (trajectory_alignment.cpp).

#include <scantling/core/error.hpp>

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <span>
#include <string_view>

namespace scantling::detail {

/// Throws InputError naming `what` and the first offending pose when `poses` holds a
/// non-finite value.
inline void check_finite_poses(std::span<const Eigen::Isometry3d> poses, std::string_view what,
                               std::string_view which) {
    for (std::size_t i = 0; i < poses.size(); ++i) {
        if (!poses[i].matrix().allFinite()) {
            throw InputError(fmt::format("{}: {} pose {} is not finite", what, which, i));
        }
    }
}

/// The contract of every metric: two non-empty trajectories of the same size, at least 2
/// poses, all finite.
inline void check_matched_trajectories(std::span<const Eigen::Isometry3d> gt,
                                       std::span<const Eigen::Isometry3d> est,
                                       std::string_view what) {
    if (gt.empty() || est.empty()) {
        throw InputError(fmt::format("{}: empty trajectory ({} ground-truth, {} estimated poses)",
                                     what, gt.size(), est.size()));
    }
    if (gt.size() != est.size()) {
        throw InputError(fmt::format(
            "{}: {} ground-truth poses but {} estimated poses, expected one estimate per "
            "ground-truth pose",
            what, gt.size(), est.size()));
    }
    if (gt.size() < 2) {
        throw InputError(fmt::format("{}: {} pose, expected at least 2", what, gt.size()));
    }
    check_finite_poses(gt, what, "ground-truth");
    check_finite_poses(est, what, "estimated");
}

}  // namespace scantling::detail
