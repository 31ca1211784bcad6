#pragma once
/// @file
/// The steps of NbvPlanner::plan (nbv_planner.hpp), one per source file: growing the tree's
/// geometry (nbv_tree.cpp, serial, seeded) and evaluating its gains (nbv_gain.cpp, parallel
/// into per-node slots, accumulated serially).

#include <Eigen/Core>
#include <span>
#include <vector>

#include <scantling/core/random.hpp>
#include <scantling/mapping/occupancy_octree.hpp>
#include <scantling/planning/nbv_planner.hpp>

namespace scantling::planning::detail {

/// The vehicle's box centred on `p_world`.
Eigen::AlignedBox3d vehicle_box(const NbvPlannerConfig& config, const Eigen::Vector3d& p_world);

/// Appends to `nodes` (the root already in it): first the `kept` states chained from the root
/// while their edges stay free and ≤ max_edge_m, then sampled nodes until max_nodes or the
/// sample budget. Counts into `stats`.
void grow_nbv_tree(const mapping::OccupancyOctree& map, const NbvPlannerConfig& config,
                   std::span<const NbvState> kept, std::span<const Eigen::Vector3d> frontiers,
                   Rng& rng, std::vector<NbvNode>& nodes, NbvStats& stats);

/// Fills every non-root node's unknown_m3 and mu (in parallel), then value (Q) in order.
void evaluate_nbv_gains(const mapping::OccupancyOctree& map, const NbvPlannerConfig& config,
                        std::span<const Eigen::Vector3d> interest_points_world,
                        std::vector<NbvNode>& nodes, NbvStats& stats);

}  // namespace scantling::planning::detail
