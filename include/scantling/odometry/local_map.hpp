#pragma once
/// @file
/// The adaptive local map m_i of LiODOM (SPEC §2): the points of the map cells around the
/// sensor, plus the edges of the last few sweeps, indexed for nearest-neighbour search.
///
/// Two k-d trees instead of one: the cell part changes slowly (the sensor crosses a cell every
/// few sweeps) and is large, the recent sweeps change every sweep and are small. Rebuilding the
/// cell tree only when the sensor has moved `rebuild_distance_m` keeps the per-sweep cost to
/// the small tree, while the recent sweeps still give the newest structure; a query merges the
/// two nearest-first lists.
#include <Eigen/Core>
#include <cstddef>
#include <deque>
#include <memory>
#include <string_view>
#include <vector>

#include <scantling/core/kdtree.hpp>
#include <scantling/mapping/cell_map.hpp>

namespace scantling::odometry {

struct LocalMapConfig {
    /// Cells whose centre lies within this distance of the sensor's cell form the map part,
    /// metres (> 0). Wider than the useful sensor range gains nothing.
    double radius_m = 60.0;
    /// Sweeps whose edges (world frame) are kept in the local map besides the cells (SPEC: 3).
    int num_recent_sweeps = 3;
    /// The cell part is re-gathered when the sensor has moved this far since the last gather,
    /// metres (>= 0; 0 = every sweep).
    double rebuild_distance_m = 2.0;
    void validate(std::string_view prefix = "local_map") const;
};

class LocalMap {
  public:
    explicit LocalMap(const LocalMapConfig& config = {});

    /// Adds one registered sweep's edges (world frame) to the recent part, dropping the oldest
    /// beyond num_recent_sweeps, and rebuilds the cell part from `map` when the sensor has moved
    /// far enough (or on the first call, or when `force_cells` is set).
    void update(const mapping::CellMap& map, const Eigen::Vector3d& sensor_position_m,
                std::vector<Eigen::Vector3d> sweep_edges_world, bool force_cells = false);

    /// The min(k, size()) nearest points over both parts, nearest first (ties: cell part
    /// first, then by index). Writes into the caller's buffers (resized); returns the count.
    std::size_t knn(const Eigen::Vector3d& query, std::size_t k,
                    std::vector<Eigen::Vector3d>& points,
                    std::vector<double>& distances_sq_m2) const;
    /// knn() over the points at most `max_distance_m` away only (fewer than k when fewer are
    /// that close): the same answer as knn() wherever its k-th neighbour is within the bound,
    /// and much cheaper for a query far from the map (KdTree::knn_within).
    std::size_t knn_within(const Eigen::Vector3d& query, std::size_t k, double max_distance_m,
                           std::vector<Eigen::Vector3d>& points,
                           std::vector<double>& distances_sq_m2) const;

    std::size_t size() const;
    bool empty() const { return size() == 0; }
    std::size_t num_cell_points() const;
    std::size_t num_recent_points() const;
    /// How many times the cell part was rebuilt (for the benchmarks' stage breakdown).
    std::size_t num_cell_rebuilds() const { return num_cell_rebuilds_; }
    void clear();

  private:
    LocalMapConfig config_;
    std::unique_ptr<KdTree> cells_;
    std::unique_ptr<KdTree> recent_;
    std::deque<std::vector<Eigen::Vector3d>> recent_sweeps_;
    Eigen::Vector3d last_gather_position_m_ = Eigen::Vector3d::Zero();
    bool has_cells_ = false;
    std::size_t num_cell_rebuilds_ = 0;
};

}  // namespace scantling::odometry
