// The RRT of the next-best-view planner (SPEC §8): re-seeding with the last best branch, then
// sampling, steering and conservative swept-box collision checks in known free space.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <scantling/planning/nbv_planner.hpp>

#include "detail/nbv.hpp"

namespace scantling::planning {
namespace detail {
namespace {

using Eigen::Vector3d;

Eigen::AlignedBox3d bounds(const NbvPlannerConfig& config) {
    return {config.bounds_min_world_m, config.bounds_max_world_m};
}

/// The AABB of the box swept from `a` to `b`: it holds every position of the box between.
Eigen::AlignedBox3d swept_box(const Vector3d& box_m, const Vector3d& a, const Vector3d& b) {
    return {a.cwiseMin(b) - box_m / 2.0, a.cwiseMax(b) + box_m / 2.0};
}

bool edge_free(const mapping::OccupancyOctree& map, const Vector3d& box_m, const Vector3d& a,
               const Vector3d& b) {
    if (map.box_is_free(swept_box(box_m, a, b))) return true;
    if ((b - a).norm() <= map.resolution_m()) return false;
    const Vector3d mid = 0.5 * (a + b);
    return edge_free(map, box_m, a, mid) && edge_free(map, box_m, mid, b);
}

/// The box the edges are checked with: the vehicle's plus the clearance on every side.
Vector3d checked_box(const NbvPlannerConfig& config) {
    return config.vehicle_box_m + Vector3d::Constant(2.0 * config.clearance_m);
}

std::size_t nearest(const std::vector<NbvNode>& nodes, const Vector3d& p) {
    std::size_t best = 0;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const double d2 = (nodes[i].state.p_world_m - p).squaredNorm();
        if (d2 < best_d2) best = i, best_d2 = d2;
    }
    return best;
}

/// A sample and how far short of it the steer stops.
struct Target {
    Vector3d p_world;
    double standoff_m = 0.0;
    bool frontier = false;  ///< a frontier sample: the new node looks at it
};

Target sample_target(const NbvPlannerConfig& config, std::span<const Vector3d> frontiers,
                     Rng& rng) {
    if (config.sampling == NbvSampling::kFrontier && !frontiers.empty() &&
        rng.uniform() < config.frontier_sample_fraction)
        return {frontiers[rng.uniform_index(frontiers.size())], config.frontier_standoff_m, true};
    const Vector3d& lo = config.bounds_min_world_m;
    const Vector3d& hi = config.bounds_max_world_m;
    return {Vector3d(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()),
                     rng.uniform(lo.z(), hi.z())),
            0.0, false};
}

/// Adds the node reached from the nearest one towards `target` if its edge is free.
bool try_extend(const mapping::OccupancyOctree& map, const NbvPlannerConfig& config,
                const Target& target, Rng& rng, std::vector<NbvNode>& nodes) {
    const std::size_t from = nearest(nodes, target.p_world);
    const Vector3d& a = nodes[from].state.p_world_m;
    const double distance_m = (target.p_world - a).norm();
    const double step_m = std::min(config.max_edge_m, distance_m - target.standoff_m);
    if (step_m <= map.resolution_m()) return false;
    const Vector3d b = a + (target.p_world - a) * (step_m / distance_m);
    if (!bounds(config).contains(b) || !edge_free(map, checked_box(config), a, b)) return false;
    NbvNode node;
    // A frontier sample's node looks at its frontier; a uniform one anywhere.
    const Vector3d to_target = target.p_world - b;
    node.state = {b, target.frontier ? std::atan2(to_target.y(), to_target.x())
                                     : rng.uniform(-std::numbers::pi, std::numbers::pi)};
    node.parent = static_cast<int>(from);
    node.edge_m = step_m;
    nodes.push_back(node);
    return true;
}

void reseed(const mapping::OccupancyOctree& map, const NbvPlannerConfig& config,
            std::span<const NbvState> kept, std::vector<NbvNode>& nodes, NbvStats& stats) {
    constexpr double kLengthSlackM = 1e-9;  // the kept edges were ≤ max_edge_m when planned
    for (const NbvState& state : kept) {
        if (nodes.size() >= static_cast<std::size_t>(config.max_nodes)) return;
        const Vector3d& a = nodes.back().state.p_world_m;
        const double edge_m = (state.p_world_m - a).norm();
        if (edge_m > config.max_edge_m + kLengthSlackM ||
            !bounds(config).contains(state.p_world_m) ||
            !edge_free(map, checked_box(config), a, state.p_world_m))
            return;
        nodes.push_back({state, static_cast<int>(nodes.size() - 1), edge_m, 0.0, 1.0, 0.0});
        ++stats.reseeded_nodes;
    }
}

}  // namespace

Eigen::AlignedBox3d vehicle_box(const NbvPlannerConfig& config, const Vector3d& p_world) {
    return {p_world - config.vehicle_box_m / 2.0, p_world + config.vehicle_box_m / 2.0};
}

void grow_nbv_tree(const mapping::OccupancyOctree& map, const NbvPlannerConfig& config,
                   std::span<const NbvState> kept, std::span<const Vector3d> frontiers, Rng& rng,
                   std::vector<NbvNode>& nodes, NbvStats& stats) {
    reseed(map, config, kept, nodes, stats);
    const std::size_t budget = static_cast<std::size_t>(config.samples_per_node) *
                               static_cast<std::size_t>(config.max_nodes);
    while (nodes.size() < static_cast<std::size_t>(config.max_nodes) && stats.samples < budget) {
        ++stats.samples;
        const Target target = sample_target(config, frontiers, rng);
        if (!try_extend(map, config, target, rng, nodes)) ++stats.rejected_edges;
    }
}

}  // namespace detail

bool nbv_edge_is_free(const mapping::OccupancyOctree& map, const Eigen::Vector3d& box_m,
                      const Eigen::Vector3d& a_world, const Eigen::Vector3d& b_world) {
    return detail::edge_free(map, box_m, a_world, b_world);
}

}  // namespace scantling::planning
