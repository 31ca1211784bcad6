#pragma once
/// @file
/// TEASER++'s pairwise consistency graph (private to registration): correspondences i and j are
/// joined when their translation-invariant measurements agree in length (rotation invariant).

#include <Eigen/Core>
#include <span>

#include <scantling/core/parallel.hpp>
#include <scantling/registration/max_clique.hpp>

namespace scantling::registration::detail {

/// Edges (i, j) with | |t_j − t_i| − |s_j − s_i| | <= `bound` (2β√c̄² for noise bound β).
/// `yaw_only`: rotations about z keep height differences and horizontal lengths separately, so
/// both must agree within `bound` (a stricter test for gravity-aligned frames).
/// O(N²) checks, parallel over rows; the graph is identical for any thread count.
UndirectedGraph build_consistency_graph(std::span<const Eigen::Vector3d> source,
                                        std::span<const Eigen::Vector3d> target, double bound,
                                        bool yaw_only, const ParallelConfig& parallel);

}  // namespace scantling::registration::detail
