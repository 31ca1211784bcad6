#pragma once
/// @file Exact nearest-neighbour search over 3D points (a k-d tree).
///
/// Backed by nanoflann, which stays in the source file: this header has no third-party include
/// beyond Eigen.

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>

namespace scantling {

struct KdTreeConfig {
    /// Most points in a leaf, >= 1. Small leaves mean deeper trees (slower build, more node
    /// visits); large leaves mean more distance evaluations per leaf. 10 is nanoflann's default;
    /// on a 124k-point LiDAR sweep 16 was ~5 % faster for k = 10..30 and 5 ~25 % slower.
    int leaf_max_size = 10;

    /// Throws ConfigError("<prefix>.leaf_max_size = 0, expected >= 1").
    void validate(std::string_view prefix = "kdtree") const;
};

/// One neighbour: index into the tree's points and squared Euclidean distance in m².
struct Neighbor {
    std::size_t index = 0;
    double distance_sq_m2 = 0.0;
};

/// Neighbours of one query, nearest first (equal distances: lower index first for radius
/// queries; for kNN the order among exact ties is fixed by the tree, hence deterministic).
struct NeighborList {
    std::vector<std::size_t> indices;
    std::vector<double> distances_sq_m2;

    std::size_t size() const { return indices.size(); }
};

/// kNN results of many queries, flattened row by row: query q's neighbours are at
/// [q * k, (q + 1) * k), nearest first.
struct KnnBatchResult {
    std::size_t k = 0;  ///< neighbours per query: min(requested k, tree size)
    std::vector<std::size_t> indices;
    std::vector<double> distances_sq_m2;

    std::size_t num_queries() const { return k == 0 ? 0 : indices.size() / k; }
};

/// Static k-d tree over a set of points (positions in metres, any single frame; queries must be
/// in the same frame).
///
/// Lifetime: the tree owns a copy of its points (pass an rvalue to move them in), so it stays
/// valid whatever happens to the caller's vector. Build is O(n log n); a kNN query is
/// O(log n + k) on average. Memory: about 70 bytes per point (the points in input order and
/// in leaf order, two permutations, nanoflann's nodes).
///
/// Thread-safety: all query methods are const and may be called concurrently. A moved-from
/// tree may only be destroyed or assigned to.
/// @note Results are exact and deterministic: the same points and query give the same
/// neighbours in the same order, whatever the thread count of the batch queries.
class KdTree {
  public:
    /// Builds the tree. An empty point set is allowed: every search then finds nothing.
    /// Throws InputError naming the first non-finite point, ConfigError on a bad config.
    explicit KdTree(std::vector<Eigen::Vector3d> points, const KdTreeConfig& config = {});
    ~KdTree();
    KdTree(KdTree&& other) noexcept;
    KdTree& operator=(KdTree&& other) noexcept;
    KdTree(const KdTree&) = delete;
    KdTree& operator=(const KdTree&) = delete;

    std::size_t size() const;
    bool empty() const { return size() == 0; }
    /// The points the tree was built over (neighbour indices refer to this vector).
    const std::vector<Eigen::Vector3d>& points() const;
    /// Every index of points() once, in the order the tree's leaves hold them: consecutive
    /// entries are spatial neighbours. Querying the tree's own points in this order keeps the
    /// visited nodes in cache (much faster than input order for scattered inputs).
    std::span<const std::size_t> leaf_order() const;
    /// The points in that order: leaf_points()[j] == points()[leaf_order()[j]].
    std::span<const Eigen::Vector3d> leaf_points() const;

    /// The nearest point, or nullopt for an empty tree.
    std::optional<Neighbor> nearest(const Eigen::Vector3d& query) const;

    /// The min(k, size()) nearest points, nearest first, written into `indices` and
    /// `distances_sq_m2` (resized). Returns the count. Hot-path form: reuses the caller's buffers.
    std::size_t knn(const Eigen::Vector3d& query, std::size_t k, std::vector<std::size_t>& indices,
                    std::vector<double>& distances_sq_m2) const;
    NeighborList knn(const Eigen::Vector3d& query, std::size_t k) const;

    /// knn() restricted to points at most `max_distance_m` away: the min(k, size()) nearest
    /// of those, nearest first (fewer when fewer are that close). The bound prunes the search,
    /// so a query whose neighbours are far away costs little; for the points it returns the
    /// answer equals knn()'s; +infinity is no bound (= knn()). Throws ConfigError on a negative
    /// or NaN distance.
    std::size_t knn_within(const Eigen::Vector3d& query, std::size_t k, double max_distance_m,
                           std::vector<std::size_t>& indices,
                           std::vector<double>& distances_sq_m2) const;
    /// knn_within() answering positions into leaf_points() instead of indices into points():
    /// the search has just read those points, so fetching them costs no cache miss (the
    /// odometry's local maps read the neighbours of ~10^4 queries a sweep).
    std::size_t knn_within_leaf(const Eigen::Vector3d& query, std::size_t k, double max_distance_m,
                                std::vector<std::size_t>& leaf_positions,
                                std::vector<double>& distances_sq_m2) const;

    /// Every point strictly closer than `radius_m` (>= 0), nearest first, ties by index.
    /// Returns the count. Throws ConfigError on a negative or non-finite radius.
    std::size_t radius(const Eigen::Vector3d& query, double radius_m,
                       std::vector<std::size_t>& indices,
                       std::vector<double>& distances_sq_m2) const;
    NeighborList radius(const Eigen::Vector3d& query, double radius_m) const;

    /// kNN for every query, in parallel. Identical output for any thread count.
    KnnBatchResult knn_batch(std::span<const Eigen::Vector3d> queries, std::size_t k,
                             const ParallelConfig& parallel = {}) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace scantling
