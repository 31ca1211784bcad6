#pragma once
/// @file
/// Receding-horizon next-best-view exploration planner (SPEC §8, thesis art. G; after Bircher
/// et al., "Receding Horizon Next-Best-View Planner for 3D Exploration", ICRA 2016).
///
/// State ξ = (x, y, z, yaw), world frame, metres and radians; the body's x axis points along
/// yaw, z up (the vehicle keeps roll = pitch = 0). Each plan() grows a rapidly-exploring
/// random tree (RRT) of at most max_nodes nodes from the current state inside KNOWN FREE space
/// of the occupancy map:
///  1. re-seeding: the rest of the previous best branch is re-inserted first, its edges
///     re-checked in the current map (the branch is cut at the first edge no longer free);
///  2. sampling: a point uniform in the exploration bounds (or, with
///     sampling = kFrontier, a fraction of the samples at frontier points, see below); the
///     nearest node (Euclidean, xyz) is steered towards it by at most max_edge_m; the edge is
///     kept only if the vehicle's axis-aligned box (plus clearance_m) swept along it stays in
///     known-free voxels (conservative: the AABB of every sub-segment ≤ one voxel long is checked
///     with OccupancyOctree::box_is_free, so no edge through unknown or occupied space is ever
///     accepted). Each new node gets a yaw uniform in [−π, π): one gain evaluation per node,
///     because gains are the whole cost (at 0.05 m one costs ~ 1–5 ms) and evaluating k yaws
///     would divide the tree's size by k within the same time;
///  3. gains (SPEC §8): Q(n_k) = Q(n_{k−1}) + μ · E(M, ξ_k) · exp(−λ · c), E =
///     OccupancyOctree::visible_unknown_volume of the camera at ξ_k (T_world_body(ξ_k) ·
///     T_body_camera) clipped to the bounds, c the edge length from the parent (the thesis'
///     c(σ)), Q(root) = 0. With defect_aware, μ = 1 + Σ_i 1 / d_i over the interest points
///     (detected defects) visible from ξ_k: inside the frustum, within max_depth_m and with a
///     clear line of sight (no occupied voxel between; the point is pulled one voxel diagonal
///     towards the camera, so a defect on a wall is not hidden by its own voxel); d_i the
///     camera–defect distance, m. SPEC writes μ = Σ 1 / d_i (μ = 1 with none); taken literally
///     a view of one defect 3 m away would be worth a third of a view of none, so the stated
///     rule here is μ = 1 + Σ 1 / d_i. Without defect_aware (vanilla) μ = 1.
///  4. the best branch is the root's path to the node of highest Q; its first node is the
///     next goal, the rest is kept for re-seeding.
/// Termination: status kExhausted when the best Q is below min_gain_m3. E counts unknown voxels
/// any gain ray reaches, including wall voxels no frame happened to hit, so in large scenes
/// the best Q may stay above a small min_gain_m3 once everything reachable is seen: a mission
/// should also stop on its own known-volume or plan budget.
///
/// Frontier-guided sampling (sampling = kFrontier, the improvement over vanilla, after
/// frontier-based exploration, Yamauchi 1997, and its use in sampling planners, e.g. Dai et
/// al. 2020): before growing, OccupancyOctree::frontier_points lists the faces of free space
/// next to unknown space inside the bounds; a fraction frontier_sample_fraction of the samples
/// is a random frontier point instead of a uniform one, and the steer towards it stops
/// frontier_standoff_m short of it (the vehicle's box cannot stand on the frontier), and the
/// new node looks at its frontier point. The tree then grows where the gain is instead of
/// spending nodes in explored space. Measured (docs/benchmarks.md, "Next-best-view planner
/// (issue 16)"): best branches with 25–35 % more gain per plan at 0.1 m, but no faster
/// exploration of a baffled tank over 5 seeds, and the same number of gain evaluations; so
/// it is off by default.
///
/// Determinism: all randomness from Rng(seed).split(number of previous plan() calls); the
/// tree's geometry is grown serially, the gains are evaluated in parallel into per-node slots
/// and accumulated serially, so any num_threads gives the identical plan.
/// Thread-safety: plan() mutates the kept branch; one planner per thread. The map is only
/// read (const), so it may be shared with other readers.
/// Cost: O(max_nodes · (gain + edge check)) with the gain O(rays · max_depth / resolution · 16)
/// dominating; plus, with kFrontier, O(free leaves) for the frontiers.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/mapping/occupancy_octree.hpp>

namespace scantling::planning {

/// A vehicle state ξ: position and heading (yaw about world z), world frame.
struct NbvState {
    Eigen::Vector3d p_world_m = Eigen::Vector3d::Zero();
    double yaw_rad = 0.0;
};

/// Where the tree's new samples come from.
enum class NbvSampling {
    kUniform,   ///< uniform in the bounds (vanilla RH-NBVP)
    kFrontier,  ///< frontier_sample_fraction of them at frontier points (see the file comment)
};

/// SPEC §8 / table G.1 defaults (λ = 0.2, N_T = 30, edges ≤ 2 m, max depth 5 m). Table G.2's
/// larger setting uses λ = 1.0, N_T = 180 on a 0.05 m map.
struct NbvPlannerConfig {
    /// Exploration volume, world, m: samples, nodes and counted gains stay inside it.
    Eigen::Vector3d bounds_min_world_m = Eigen::Vector3d(-5.0, -5.0, -2.0);
    Eigen::Vector3d bounds_max_world_m = Eigen::Vector3d(5.0, 5.0, 2.0);  ///< > min per axis
    int max_nodes = 30;         ///< N_T, >= 2: nodes of the tree, the root included
    int samples_per_node = 20;  ///< >= 1: sample budget = samples_per_node · max_nodes
    double max_edge_m = 2.0;    ///< > 0: longest edge (the steer's step), m
    double lambda_per_m = 0.2;  ///< >= 0: λ, the gain's discount per metre of edge
    /// > 0 per axis: the vehicle's axis-aligned collision box, centred on ξ's position, m.
    Eigen::Vector3d vehicle_box_m = Eigen::Vector3d(0.6, 0.6, 0.3);
    /// >= 0: margin added to the vehicle box on every side for the tree's edges, m (the
    /// start's check uses the bare box). At least one voxel keeps an accepted node's box off
    /// voxels that hold a surface but were seen free (rays crossing their free part), which a
    /// later frame turns occupied: without it a tank run stopped (kStartNotFree) at a node
    /// whose box ended 9 mm from a baffle.
    double clearance_m = 0.1;
    /// The camera's view (body convention: x forward); max_depth_m = SPEC's 5 m.
    mapping::ViewFrustum camera{};
    /// The camera's position in the body frame, m (T_body_camera's translation).
    Eigen::Vector3d p_body_camera_m = Eigen::Vector3d::Zero();
    /// The camera's pitch in the body frame, rad, in (−π/2, π/2); > 0 looks down
    /// (T_body_camera's rotation about body y).
    double camera_pitch_rad = 0.0;
    /// >= 0: best Q below this, m³, means exploration is done (kExhausted). Default 0.05 m³:
    /// 50 voxels at 0.1 m, 400 at 0.05 m, i.e. a 0.37 m cube of unknown space; below it the
    /// residue is voxels grazed between rays and corners no reachable pose sees.
    double min_gain_m3 = 0.05;
    bool defect_aware = false;  ///< μ = 1 + Σ 1 / d_i over visible interest points, else μ = 1
    NbvSampling sampling = NbvSampling::kUniform;  ///< the improvement: kFrontier
    double frontier_sample_fraction = 0.5;         ///< in [0, 1]: share of frontier samples
    /// >= 0: a frontier sample's steer stops this far short of it, m (about the vehicle box's
    /// half diagonal, so the new node's box is not on the frontier itself).
    double frontier_standoff_m = 0.5;
    /// > 0: frontiers are found on cells of about this edge, m (the map's voxel · 2^k nearest
    /// to it, at least one voxel): unknown holes smaller than a cell, left between sparse rays,
    /// are not frontiers, and there are far fewer cells to visit (see
    /// OccupancyOctree::frontier_points).
    double frontier_cell_m = 0.2;
    std::uint64_t seed = 16;  ///< RNG seed
    ParallelConfig parallel{};

    /// Throws ConfigError naming the field: "<prefix>.max_edge_m = 0, expected finite > 0".
    void validate(std::string_view prefix = "nbv") const;
};

enum class NbvStatus {
    kOk,            ///< a branch with best Q >= min_gain_m3: go to next_goal
    kExhausted,     ///< best Q < min_gain_m3: nothing reachable left to see
    kStartNotFree,  ///< the vehicle's box at the start is not all known free
    kNoFreeEdge,    ///< no edge from the start could be added (boxed in by unknown space)
};

/// One node of the tree: its state, parent (−1 for the root) and gains.
struct NbvNode {
    NbvState state;
    int parent = -1;        ///< index into NbvPlan::tree, −1 for the root
    double edge_m = 0.0;    ///< c: length of the edge from the parent, m
    double unknown_m3 = 0;  ///< E(M, ξ): visible unknown volume, m³
    double mu = 1.0;        ///< the defect weight μ
    double value = 0.0;     ///< Q, m³
};

struct NbvStats {
    std::size_t samples = 0;  ///< samples drawn
    /// samples that added no node: edge not all known free, end out of bounds, or a frontier
    /// sample within standoff + one voxel of its nearest node
    std::size_t rejected_edges = 0;
    std::size_t gain_evaluations = 0;  ///< visible_unknown_volume calls
    std::size_t reseeded_nodes = 0;    ///< nodes of the previous branch re-inserted
    std::size_t frontier_points = 0;   ///< frontier points listed (kFrontier), else 0
};

struct NbvPlan {
    NbvStatus status = NbvStatus::kOk;
    std::string message;           ///< why, for any status but kOk
    NbvState next_goal;            ///< the best branch's first node (the start if none)
    std::vector<NbvState> branch;  ///< the best branch, root excluded, next_goal first
    double best_value = 0.0;       ///< Q of the branch's last node, m³
    std::vector<NbvNode> tree;     ///< every node, the root first; parents before children
    NbvStats stats;
};

class NbvPlanner {
  public:
    /// Throws ConfigError for an invalid config.
    explicit NbvPlanner(const NbvPlannerConfig& config = {});

    /// Plans from `start` in `map` (see the file comment), weighting views of
    /// `interest_points_world` (defect positions, m) when defect_aware. Keeps the best
    /// branch's tail for the next call. Not-free starts and empty trees are statuses, not
    /// errors. Throws InputError for a non-finite start or interest point.
    NbvPlan plan(const mapping::OccupancyOctree& map, const NbvState& start,
                 std::span<const Eigen::Vector3d> interest_points_world = {});

    /// Forgets the kept branch and restarts the random streams (as freshly constructed).
    void reset();

    const NbvPlannerConfig& config() const { return config_; }
    /// The kept tail of the last best branch (re-inserted first by the next plan()).
    const std::vector<NbvState>& kept_branch() const { return kept_branch_; }

  private:
    NbvPlannerConfig config_;
    std::vector<NbvState> kept_branch_;
    std::uint64_t plans_ = 0;
};

/// The camera's pose for state ξ: T_world_body(ξ) · T_body_camera (see the config).
Eigen::Isometry3d nbv_camera_pose(const NbvPlannerConfig& config, const NbvState& state);

/// μ for a camera pose (see the file comment): 1 + Σ 1 / d_i over the visible points.
double nbv_defect_weight(const mapping::OccupancyOctree& map, const mapping::ViewFrustum& camera,
                         const Eigen::Isometry3d& T_world_camera,
                         std::span<const Eigen::Vector3d> interest_points_world);

/// True when the vehicle box swept from `a_world` to `b_world` stays in known-free voxels
/// (sub-segments ≤ one voxel, each's swept AABB checked with box_is_free).
bool nbv_edge_is_free(const mapping::OccupancyOctree& map, const Eigen::Vector3d& box_m,
                      const Eigen::Vector3d& a_world, const Eigen::Vector3d& b_world);

}  // namespace scantling::planning
