#include <scantling/core/error.hpp>
#include <scantling/core/kdtree.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

// Among candidates at exactly the same distance, keep the lower (leaf-position) index first:
// with duplicate points the answer then depends only on the tree, not on visit order.
#define NANOFLANN_FIRST_MATCH
#include <nanoflann.hpp>

namespace scantling {
namespace {

/// nanoflann's dataset interface over the tree's own copy of the points.
struct PointsAdaptor {
    const std::vector<Eigen::Vector3d>* points;

    std::size_t kdtree_get_point_count() const { return points->size(); }
    double kdtree_get_pt(std::size_t i, std::size_t dim) const {
        return (*points)[i][static_cast<Eigen::Index>(dim)];
    }
    template <class Bbox>
    bool kdtree_get_bbox(Bbox& /*bbox*/) const {
        return false;
    }
};

using Index =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointsAdaptor>,
                                        PointsAdaptor, 3, std::size_t>;

void check_points_finite(const std::vector<Eigen::Vector3d>& points) {
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!points[i].allFinite()) {
            throw InputError(fmt::format("kdtree: point {} is not finite ({}, {}, {})", i,
                                         points[i].x(), points[i].y(), points[i].z()));
        }
    }
}

}  // namespace

void KdTreeConfig::validate(std::string_view prefix) const {
    if (leaf_max_size < 1) {
        throw ConfigError(
            fmt::format("{}.leaf_max_size = {}, expected >= 1", prefix, leaf_max_size));
    }
}

// Heap-allocated and never moved, so the index's references to the adaptor and the adaptor's
// pointer to the points stay valid when the KdTree itself is moved.
//
// After the build the points are stored again in the order the leaves visit them, and
// nanoflann's index permutation is made the identity: a leaf's points are then contiguous in
// memory, which makes leaf scans (most of a query's time) cache-friendly. Search results are leaf
// positions, mapped back through `leaf_to_input`.
struct KdTree::Impl {
    std::vector<Eigen::Vector3d> points;
    std::vector<Eigen::Vector3d> leaf_points;
    std::vector<std::size_t> leaf_to_input;
    PointsAdaptor adaptor{&leaf_points};
    Index index;

    Impl(std::vector<Eigen::Vector3d> pts, const KdTreeConfig& config)
        : points(std::move(pts)),
          leaf_points(points),
          index(3, adaptor,
                nanoflann::KDTreeSingleIndexAdaptorParams(
                    static_cast<std::size_t>(config.leaf_max_size),
                    nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex)) {
        if (points.empty()) return;
        index.buildIndex();
        leaf_to_input.assign(index.vAcc.begin(), index.vAcc.end());
        for (std::size_t j = 0; j < leaf_to_input.size(); ++j) {
            leaf_points[j] = points[leaf_to_input[j]];
            index.vAcc[j] = j;
        }
    }

    void to_input(std::size_t* indices, std::size_t count) const {
        for (std::size_t j = 0; j < count; ++j) indices[j] = leaf_to_input[indices[j]];
    }
};

KdTree::KdTree(std::vector<Eigen::Vector3d> points, const KdTreeConfig& config) {
    config.validate();
    check_points_finite(points);
    impl_ = std::make_unique<Impl>(std::move(points), config);
}

KdTree::~KdTree() = default;
KdTree::KdTree(KdTree&& other) noexcept = default;
KdTree& KdTree::operator=(KdTree&& other) noexcept = default;

std::size_t KdTree::size() const { return impl_->points.size(); }

const std::vector<Eigen::Vector3d>& KdTree::points() const { return impl_->points; }

std::span<const std::size_t> KdTree::leaf_order() const { return impl_->leaf_to_input; }

std::span<const Eigen::Vector3d> KdTree::leaf_points() const { return impl_->leaf_points; }

std::optional<Neighbor> KdTree::nearest(const Eigen::Vector3d& query) const {
    if (empty()) return std::nullopt;
    Neighbor n;
    impl_->index.knnSearch(query.data(), 1, &n.index, &n.distance_sq_m2);
    impl_->to_input(&n.index, 1);
    return n;
}

std::size_t KdTree::knn(const Eigen::Vector3d& query, std::size_t k,
                        std::vector<std::size_t>& indices,
                        std::vector<double>& distances_sq_m2) const {
    const std::size_t count = std::min(k, size());
    indices.resize(count);
    distances_sq_m2.resize(count);
    if (count == 0) return 0;
    impl_->index.knnSearch(query.data(), count, indices.data(), distances_sq_m2.data());
    impl_->to_input(indices.data(), count);
    return count;
}

std::size_t KdTree::knn_within(const Eigen::Vector3d& query, std::size_t k, double max_distance_m,
                               std::vector<std::size_t>& indices,
                               std::vector<double>& distances_sq_m2) const {
    const std::size_t count = knn_within_leaf(query, k, max_distance_m, indices, distances_sq_m2);
    impl_->to_input(indices.data(), count);
    return count;
}

std::size_t KdTree::knn_within_leaf(const Eigen::Vector3d& query, std::size_t k,
                                    double max_distance_m, std::vector<std::size_t>& indices,
                                    std::vector<double>& distances_sq_m2) const {
    if (!(max_distance_m >= 0.0)) {
        throw ConfigError(fmt::format("kdtree.max_distance_m = {}, expected >= 0", max_distance_m));
    }
    const std::size_t capacity = std::min(k, size());
    indices.resize(capacity);
    distances_sq_m2.resize(capacity);
    if (capacity == 0) return 0;
    nanoflann::KNNResultSet<double, std::size_t> found(capacity);
    found.init(indices.data(), distances_sq_m2.data());
    // The result set's worst distance is the pruning bound: start it at the limit instead of
    // infinity. nanoflann keeps points strictly closer than the bound, so the bound is the next
    // double above the limit: a point exactly at max_distance_m is kept, as knn() would.
    distances_sq_m2[capacity - 1] =
        std::nextafter(max_distance_m * max_distance_m, std::numeric_limits<double>::infinity());
    impl_->index.findNeighbors(found, query.data(), nanoflann::SearchParams());
    const std::size_t count = found.size();
    indices.resize(count);
    distances_sq_m2.resize(count);
    return count;
}

NeighborList KdTree::knn(const Eigen::Vector3d& query, std::size_t k) const {
    NeighborList list;
    knn(query, k, list.indices, list.distances_sq_m2);
    return list;
}

std::size_t KdTree::radius(const Eigen::Vector3d& query, double radius_m,
                           std::vector<std::size_t>& indices,
                           std::vector<double>& distances_sq_m2) const {
    if (!(radius_m >= 0.0) || !std::isfinite(radius_m)) {
        throw ConfigError(fmt::format("kdtree.radius_m = {}, expected finite >= 0", radius_m));
    }
    std::vector<std::pair<std::size_t, double>> found;
    if (!empty()) {
        impl_->index.radiusSearch(query.data(), radius_m * radius_m, found,
                                  nanoflann::SearchParams(32, 0.0F, false));
        for (auto& [index, distance_sq] : found) index = impl_->leaf_to_input[index];
    }
    // nanoflann's own sort is unstable on ties; (distance, index) makes the order unique.
    std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
        return a.second != b.second ? a.second < b.second : a.first < b.first;
    });
    indices.resize(found.size());
    distances_sq_m2.resize(found.size());
    for (std::size_t i = 0; i < found.size(); ++i) {
        indices[i] = found[i].first;
        distances_sq_m2[i] = found[i].second;
    }
    return found.size();
}

NeighborList KdTree::radius(const Eigen::Vector3d& query, double radius_m) const {
    NeighborList list;
    radius(query, radius_m, list.indices, list.distances_sq_m2);
    return list;
}

KnnBatchResult KdTree::knn_batch(std::span<const Eigen::Vector3d> queries, std::size_t k,
                                 const ParallelConfig& parallel) const {
    KnnBatchResult result;
    result.k = std::min(k, size());
    if (result.k == 0) return result;
    result.indices.resize(queries.size() * result.k);
    result.distances_sq_m2.resize(queries.size() * result.k);
    constexpr std::size_t kGrain = 256;  // queries per task: amortises scheduling
    parallel_for(parallel, queries.size(), kGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t q = begin; q < end; ++q) {
            std::size_t* indices = &result.indices[q * result.k];
            impl_->index.knnSearch(queries[q].data(), result.k, indices,
                                   &result.distances_sq_m2[q * result.k]);
            impl_->to_input(indices, result.k);
        }
    });
    return result;
}

}  // namespace scantling
