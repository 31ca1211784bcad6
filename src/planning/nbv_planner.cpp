// Receding-horizon next-best-view planner (SPEC §8): the config, and plan() tying together the
// tree (nbv_tree.cpp) and its gains (nbv_gain.cpp).
#include <scantling/planning/nbv_planner.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>

#include "detail/nbv.hpp"

namespace scantling::planning {
namespace {

using Eigen::Vector3d;

void validate_bounds(const NbvPlannerConfig& c, std::string_view prefix) {
    using config_checks::require;
    for (int axis = 0; axis < 3; ++axis) {
        const std::string field = fmt::format("bounds_max_world_m[{}]", axis);
        require(std::isfinite(c.bounds_min_world_m[axis]), prefix,
                fmt::format("bounds_min_world_m[{}]", axis), c.bounds_min_world_m[axis], "finite");
        require(
            std::isfinite(c.bounds_max_world_m[axis]) &&
                c.bounds_max_world_m[axis] > c.bounds_min_world_m[axis],
            prefix, field, c.bounds_max_world_m[axis],
            fmt::format("finite > bounds_min_world_m[{}] = {}", axis, c.bounds_min_world_m[axis]));
        config_checks::require_positive(c.vehicle_box_m[axis], prefix,
                                        fmt::format("vehicle_box_m[{}]", axis));
        require(std::isfinite(c.p_body_camera_m[axis]), prefix,
                fmt::format("p_body_camera_m[{}]", axis), c.p_body_camera_m[axis], "finite");
    }
}

std::string describe(const Vector3d& p) { return fmt::format("({}, {}, {})", p.x(), p.y(), p.z()); }

void require_finite_inputs(const NbvState& start, std::span<const Vector3d> interest_points) {
    if (!start.p_world_m.allFinite() || !std::isfinite(start.yaw_rad))
        throw InputError(fmt::format("nbv: start {} m, yaw {} rad is not finite",
                                     describe(start.p_world_m), start.yaw_rad));
    for (std::size_t i = 0; i < interest_points.size(); ++i) {
        if (!interest_points[i].allFinite())
            throw InputError(fmt::format("nbv: interest point {} is not finite", i));
    }
}

std::string start_not_free_message(const mapping::OccupancyOctree& map, const Vector3d& p) {
    const mapping::Occupancy at = map.query(p);
    const char* state = at == mapping::Occupancy::kOccupied  ? "occupied"
                        : at == mapping::Occupancy::kUnknown ? "unknown"
                                                             : "free";
    return fmt::format(
        "nbv: start {} m is not in known free space: the vehicle box there is not all known free "
        "(its centre voxel is {})",
        describe(p), state);
}

/// The branch from the root to `best`, root excluded.
std::vector<NbvState> branch_to(const std::vector<NbvNode>& tree, std::size_t best) {
    std::vector<NbvState> branch;
    for (int i = static_cast<int>(best); i > 0; i = tree[static_cast<std::size_t>(i)].parent)
        branch.push_back(tree[static_cast<std::size_t>(i)].state);
    return {branch.rbegin(), branch.rend()};
}

/// log2 of the frontier cell in voxels, nearest, in [0, 8].
int frontier_levels(const NbvPlannerConfig& config, const mapping::OccupancyOctree& map) {
    const double levels = std::round(std::log2(config.frontier_cell_m / map.resolution_m()));
    return static_cast<int>(std::clamp(levels, 0.0, 8.0));
}

std::size_t best_node(const std::vector<NbvNode>& tree) {
    std::size_t best = 1;
    for (std::size_t i = 2; i < tree.size(); ++i) {
        if (tree[i].value > tree[best].value) best = i;  // ties: the earliest
    }
    return best;
}

}  // namespace

void NbvPlannerConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    validate_bounds(*this, prefix);
    require_at_least(max_nodes, 2, prefix, "max_nodes");
    require_at_least(samples_per_node, 1, prefix, "samples_per_node");
    require_positive(max_edge_m, prefix, "max_edge_m");
    require_non_negative(clearance_m, prefix, "clearance_m");
    require_non_negative(lambda_per_m, prefix, "lambda_per_m");
    camera.validate(fmt::format("{}.camera", prefix));
    require(std::abs(camera_pitch_rad) < std::numbers::pi / 2.0, prefix, "camera_pitch_rad",
            camera_pitch_rad, "in (-pi/2, pi/2)");
    require_non_negative(min_gain_m3, prefix, "min_gain_m3");
    require(frontier_sample_fraction >= 0.0 && frontier_sample_fraction <= 1.0, prefix,
            "frontier_sample_fraction", frontier_sample_fraction, "in [0, 1]");
    require_non_negative(frontier_standoff_m, prefix, "frontier_standoff_m");
    require_positive(frontier_cell_m, prefix, "frontier_cell_m");
    parallel.validate(fmt::format("{}.parallel", prefix));
}

NbvPlanner::NbvPlanner(const NbvPlannerConfig& config) : config_(config) {
    config_.validate("nbv");
}

void NbvPlanner::reset() {
    kept_branch_.clear();
    plans_ = 0;
}

NbvPlan NbvPlanner::plan(const mapping::OccupancyOctree& map, const NbvState& start,
                         std::span<const Eigen::Vector3d> interest_points_world) {
    require_finite_inputs(start, interest_points_world);
    Rng rng = Rng(config_.seed).split(plans_++);
    const std::vector<NbvState> kept = std::exchange(kept_branch_, {});
    NbvPlan plan;
    plan.next_goal = start;
    plan.tree.push_back(NbvNode{start, -1, 0.0, 0.0, 1.0, 0.0});
    if (!map.box_is_free(detail::vehicle_box(config_, start.p_world_m))) {
        plan.status = NbvStatus::kStartNotFree;
        plan.message = start_not_free_message(map, start.p_world_m);
        return plan;
    }
    std::vector<Vector3d> frontiers;
    if (config_.sampling == NbvSampling::kFrontier)
        frontiers = map.frontier_points({config_.bounds_min_world_m, config_.bounds_max_world_m},
                                        frontier_levels(config_, map));
    plan.stats.frontier_points = frontiers.size();
    detail::grow_nbv_tree(map, config_, kept, frontiers, rng, plan.tree, plan.stats);
    if (plan.tree.size() == 1) {
        plan.status = NbvStatus::kNoFreeEdge;
        plan.message = fmt::format("nbv: no free edge from the start {} m in {} samples",
                                   describe(start.p_world_m), plan.stats.samples);
        return plan;
    }
    detail::evaluate_nbv_gains(map, config_, interest_points_world, plan.tree, plan.stats);
    const std::size_t best = best_node(plan.tree);
    plan.branch = branch_to(plan.tree, best);
    plan.best_value = plan.tree[best].value;
    if (plan.best_value < config_.min_gain_m3) {
        plan.status = NbvStatus::kExhausted;
        plan.message = fmt::format("nbv: exhausted: best gain {} m³ < min_gain_m3 = {} m³",
                                   plan.best_value, config_.min_gain_m3);
        return plan;
    }
    plan.next_goal = plan.branch.front();
    kept_branch_.assign(plan.branch.begin() + 1, plan.branch.end());
    return plan;
}

}  // namespace scantling::planning
