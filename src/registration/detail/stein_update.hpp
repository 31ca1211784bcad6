#pragma once
/// @file
/// The Stein variational gradient iterations of Stein ICP (private; see stein_icp.hpp).

#include <Eigen/Core>
#include <span>
#include <vector>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/stein_icp.hpp>

namespace scantling::registration::detail {

/// Moves `particles` for `config.iterations` SVGD steps (Adam per block). `target_normals`
/// empty = point-to-point. Deterministic for any thread count.
void run_svgd(std::vector<Vector6d>& particles, std::span<const Eigen::Vector3d> source,
              const KdTree& target_tree, std::span<const Eigen::Vector3d> target_normals,
              const SteinIcpConfig& config);

}  // namespace scantling::registration::detail
