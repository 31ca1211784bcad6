#include <algorithm>
#include <cmath>
#include <limits>
#include <scantling/core/error.hpp>
#include <scantling/odometry/local_map.hpp>
#include <string>

namespace scantling::odometry {

void LocalMapConfig::validate(std::string_view prefix) const {
    const std::string p(prefix);
    if (!(radius_m > 0.0) || !std::isfinite(radius_m)) {
        throw ConfigError(p + ".radius_m = " + std::to_string(radius_m) + ", expected > 0");
    }
    if (num_recent_sweeps < 0) {
        throw ConfigError(p + ".num_recent_sweeps = " + std::to_string(num_recent_sweeps) +
                          ", expected >= 0");
    }
    if (!(rebuild_distance_m >= 0.0) || !std::isfinite(rebuild_distance_m)) {
        throw ConfigError(p + ".rebuild_distance_m = " + std::to_string(rebuild_distance_m) +
                          ", expected >= 0");
    }
}

LocalMap::LocalMap(const LocalMapConfig& config) : config_(config) { config_.validate(); }

void LocalMap::update(const mapping::CellMap& map, const Eigen::Vector3d& sensor_position_m,
                      std::vector<Eigen::Vector3d> sweep_edges_world, bool force_cells) {
    if (config_.num_recent_sweeps > 0) {
        recent_sweeps_.push_back(std::move(sweep_edges_world));
        while (recent_sweeps_.size() > static_cast<std::size_t>(config_.num_recent_sweeps)) {
            recent_sweeps_.pop_front();
        }
        std::vector<Eigen::Vector3d> recent;
        std::size_t total = 0;
        for (const auto& sweep : recent_sweeps_) total += sweep.size();
        recent.reserve(total);
        for (const auto& sweep : recent_sweeps_)
            recent.insert(recent.end(), sweep.begin(), sweep.end());
        recent_ = std::make_unique<KdTree>(std::move(recent));
    }
    const bool moved =
        (sensor_position_m - last_gather_position_m_).norm() >= config_.rebuild_distance_m;
    if (!has_cells_ || moved || force_cells) {
        std::vector<Eigen::Vector3d> points;
        map.gather_near(sensor_position_m, config_.radius_m, points);
        cells_ = std::make_unique<KdTree>(std::move(points));
        last_gather_position_m_ = sensor_position_m;
        has_cells_ = true;
        ++num_cell_rebuilds_;
    }
}

namespace {

/// Merges two nearest-first lists (a: cell part, b: recent part) into the first k of both.
std::size_t merge_nearest(const KdTree* cells, const std::vector<std::size_t>& idx_a,
                          const std::vector<double>& d_a, const KdTree* recent,
                          const std::vector<std::size_t>& idx_b, const std::vector<double>& d_b,
                          std::size_t k, std::vector<Eigen::Vector3d>& points,
                          std::vector<double>& distances_sq_m2) {
    const std::size_t na = idx_a.size(), nb = idx_b.size();
    const std::size_t n = std::min(k, na + nb);
    points.resize(n);
    distances_sq_m2.resize(n);
    std::size_t a = 0, b = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (b >= nb || (a < na && d_a[a] <= d_b[b])) {
            points[i] = cells->leaf_points()[idx_a[a]];
            distances_sq_m2[i] = d_a[a++];
        } else {
            points[i] = recent->leaf_points()[idx_b[b]];
            distances_sq_m2[i] = d_b[b++];
        }
    }
    return n;
}

}  // namespace

std::size_t LocalMap::knn(const Eigen::Vector3d& query, std::size_t k,
                          std::vector<Eigen::Vector3d>& points,
                          std::vector<double>& distances_sq_m2) const {
    return knn_within(query, k, std::numeric_limits<double>::infinity(), points, distances_sq_m2);
}

std::size_t LocalMap::knn_within(const Eigen::Vector3d& query, std::size_t k, double max_distance_m,
                                 std::vector<Eigen::Vector3d>& points,
                                 std::vector<double>& distances_sq_m2) const {
    // Small per-thread buffers: k is a handful, so a merge of two sorted lists beats anything
    // clever, and the hot path allocates nothing.
    thread_local std::vector<std::size_t> idx_a, idx_b;
    thread_local std::vector<double> d_a, d_b;
    idx_a.clear(), idx_b.clear(), d_a.clear(), d_b.clear();
    // The small recent part first: when it holds k points, only cell points at most as far as
    // its k-th can enter the merged list, so that distance bounds the search of the large cell
    // part (ties included: the merge puts cell points first on equal distance, as before).
    double bound_m = max_distance_m;
    if (recent_) {
        recent_->knn_within_leaf(query, k, max_distance_m, idx_b, d_b);
        if (d_b.size() == k && k > 0) {
            // One ulp up: the square of the bound is then at least the k-th squared distance.
            const double kth_m =
                std::nextafter(std::sqrt(d_b.back()), std::numeric_limits<double>::infinity());
            bound_m = std::min(bound_m, kth_m);
        }
    }
    if (cells_) cells_->knn_within_leaf(query, k, bound_m, idx_a, d_a);
    return merge_nearest(cells_.get(), idx_a, d_a, recent_.get(), idx_b, d_b, k, points,
                         distances_sq_m2);
}

std::size_t LocalMap::num_cell_points() const { return cells_ ? cells_->size() : 0; }
std::size_t LocalMap::num_recent_points() const { return recent_ ? recent_->size() : 0; }
std::size_t LocalMap::size() const { return num_cell_points() + num_recent_points(); }

void LocalMap::clear() {
    cells_.reset();
    recent_.reset();
    recent_sweeps_.clear();
    has_cells_ = false;
}

}  // namespace scantling::odometry
