#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/perception/plane_ransac.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <numeric>
#include <optional>
#include <utility>

#include <fmt/format.h>

namespace scantling::perception {
namespace {

// Hypotheses are ranked on a fixed random subsample of the remaining points: ranking needs
// only relative support, and 2000 points tell a 5 % plane from a 10 % one reliably (±~0.5 %
// binomial noise) while 200 hypotheses × 8 planes stay at ~3 M point tests (~5 ms) whatever
// the frame's size. The winner's full inlier set is then collected over every remaining point.
constexpr std::size_t kScoreSampleSize = 2000;
// A hypothesis from one noisy normal (or three close points) only catches a strip of its
// plane; each PCA refit on the strip straightens it, so collect → refit runs a few times.
constexpr int kRefitRounds = 3;
// Eigenvalue ratio λ₁/λ₂ below which points count as collinear (the plane is undefined).
constexpr double kCollinearRatio = 1e-12;
// sin² of the angle at a sample's first point below which the triangle is too flat to
// define a plane (repeated picks land here too).
constexpr double kMinSampleSin2 = 1e-12;

/// The plane model RANSAC works with (Plane without the inlier bookkeeping).
struct PlaneModel {
    Eigen::Vector3d normal;
    double offset_m = 0.0;
};

/// What makes a point an inlier of a plane.
struct Criteria {
    double distance_m = 0.0;
    double cos_normal = 0.0;   ///< |n_point · n_plane| at least this (normals are unsigned)
    bool use_normals = false;  ///< a NaN or zero normal then fails the test

    bool accepts(const Eigen::Vector3d& p, const Eigen::Vector3d* n, const PlaneModel& m) const {
        if (!(std::abs(m.normal.dot(p) + m.offset_m) <= distance_m)) return false;
        return !use_normals || std::abs(m.normal.dot(*n)) >= cos_normal;
    }
};

/// The subsample hypotheses are drawn from and scored on, contiguous for the scoring loop.
struct Sample {
    std::vector<Eigen::Vector3d> points;
    std::vector<Eigen::Vector3d> normals;  ///< empty without normals
};

Sample draw_sample(const PointCloud& cloud, const std::vector<std::size_t>& remaining, Rng& rng) {
    Sample s;
    const auto picks =
        rng.sample_indices(remaining.size(), std::min(kScoreSampleSize, remaining.size()));
    for (const std::size_t k : picks) {
        s.points.push_back(cloud.points[remaining[k]]);
        if (cloud.has_normals()) s.normals.push_back(cloud.normals[remaining[k]]);
    }
    return s;
}

std::optional<PlaneModel> from_point_and_normal(const Sample& s, Rng& rng) {
    const std::size_t k = rng.uniform_index(s.points.size());
    const double length = s.normals[k].norm();
    if (!std::isfinite(length) || length < 0.5) return std::nullopt;  // unusable normal
    const Eigen::Vector3d n = s.normals[k] / length;
    return PlaneModel{n, -n.dot(s.points[k])};
}

std::optional<PlaneModel> from_three_points(const Sample& s, Rng& rng) {
    const std::size_t i = rng.uniform_index(s.points.size());
    const std::size_t j = rng.uniform_index(s.points.size());
    const std::size_t k = rng.uniform_index(s.points.size());
    const Eigen::Vector3d u = s.points[j] - s.points[i];
    const Eigen::Vector3d v = s.points[k] - s.points[i];
    const Eigen::Vector3d n = u.cross(v);
    if (n.squaredNorm() <= kMinSampleSin2 * u.squaredNorm() * v.squaredNorm()) return std::nullopt;
    const Eigen::Vector3d unit = n.normalized();
    return PlaneModel{unit, -unit.dot(s.points[i])};
}

/// Inliers of `m` in the sample: the hot loop (iterations × sample size per plane), so it is
/// branch-free, specialised on normals, and only counts (a running sum of squares, for
/// tie-breaks, chains every step on the adder's latency and doubled the time).
template <bool kUseNormals>
std::size_t support(const Sample& s, const PlaneModel& m, const Criteria& c) {
    std::size_t inliers = 0;
    for (std::size_t k = 0; k < s.points.size(); ++k) {
        const double d = m.normal.dot(s.points[k]) + m.offset_m;
        bool inlier = std::abs(d) <= c.distance_m;
        if constexpr (kUseNormals) inlier &= std::abs(m.normal.dot(s.normals[k])) >= c.cos_normal;
        inliers += inlier ? 1 : 0;
    }
    return inliers;
}

std::optional<PlaneModel> best_hypothesis(const PointCloud& cloud,
                                          const std::vector<std::size_t>& remaining,
                                          const PlaneRansacConfig& config, const Criteria& c,
                                          Rng& rng) {
    const Sample s = draw_sample(cloud, remaining, rng);
    std::optional<PlaneModel> best;
    std::size_t best_support = 0;
    for (int it = 0; it < config.iterations; ++it) {
        const auto m = c.use_normals ? from_point_and_normal(s, rng) : from_three_points(s, rng);
        if (!m) continue;
        const std::size_t n = c.use_normals ? support<true>(s, *m, c) : support<false>(s, *m, c);
        if (!best || n > best_support) {  // the first of equals wins: deterministic
            best = m;
            best_support = n;
        }
    }
    return best;
}

std::vector<std::size_t> collect(const PointCloud& cloud, const std::vector<std::size_t>& remaining,
                                 const PlaneModel& m, const Criteria& c) {
    std::vector<std::size_t> inliers;
    for (const std::size_t i : remaining) {
        if (c.accepts(cloud.points[i], c.use_normals ? &cloud.normals[i] : nullptr, m)) {
            inliers.push_back(i);
        }
    }
    return inliers;
}

/// PCA plane; none when the points are fewer than three or collinear.
std::optional<Plane> try_fit_plane(const std::vector<Eigen::Vector3d>& points,
                                   const Eigen::Vector3d& towards) {
    if (points.size() < 3) return std::nullopt;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& p : points) centroid += p;
    centroid /= static_cast<double>(points.size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (const auto& p : points) scatter += (p - centroid) * (p - centroid).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
    const Eigen::Vector3d& lambda = eig.eigenvalues();  // ascending
    if (!(lambda(2) > 0.0) || lambda(1) <= kCollinearRatio * lambda(2)) return std::nullopt;
    Plane plane;
    plane.normal = eig.eigenvectors().col(0).normalized();
    if (plane.normal.dot(towards - centroid) < 0.0) plane.normal = -plane.normal;
    plane.offset_m = -plane.normal.dot(centroid);
    plane.centroid = centroid;
    double sum_sq_m2 = 0.0;
    for (const auto& p : points) {
        const double d = plane.signed_distance(p);
        sum_sq_m2 += d * d;
    }
    plane.rms_m = std::sqrt(sum_sq_m2 / static_cast<double>(points.size()));
    return plane;
}

/// Collect → PCA refit, kRefitRounds times; the plane returned is fitted to its inliers.
/// Normals face the cloud's origin (the sensor, for a depth frame).
std::optional<Plane> refine(const PointCloud& cloud, const std::vector<std::size_t>& remaining,
                            PlaneModel model, const PlaneRansacConfig& config, const Criteria& c) {
    std::optional<Plane> plane;
    for (int round = 0; round < kRefitRounds; ++round) {
        std::vector<std::size_t> inliers = collect(cloud, remaining, model, c);
        if (inliers.size() < config.min_inliers) return std::nullopt;
        std::vector<Eigen::Vector3d> points;
        points.reserve(inliers.size());
        for (const std::size_t i : inliers) points.push_back(cloud.points[i]);
        plane = try_fit_plane(points, Eigen::Vector3d::Zero());
        if (!plane) return std::nullopt;
        plane->inliers = std::move(inliers);
        model = {plane->normal, plane->offset_m};
    }
    return plane;
}

/// `remaining` minus `taken`, both sorted.
std::vector<std::size_t> without(const std::vector<std::size_t>& remaining,
                                 const std::vector<std::size_t>& taken) {
    std::vector<std::size_t> rest;
    rest.reserve(remaining.size() - taken.size());
    std::set_difference(remaining.begin(), remaining.end(), taken.begin(), taken.end(),
                        std::back_inserter(rest));
    return rest;
}

}  // namespace

void PlaneRansacConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(distance_threshold_m, prefix, "distance_threshold_m");
    require(std::isfinite(normal_threshold_deg) && normal_threshold_deg > 0.0 &&
                normal_threshold_deg <= 90.0,
            prefix, "normal_threshold_deg", normal_threshold_deg, "in (0, 90]");
    config_checks::require_count_at_least(min_inliers, 3, prefix, "min_inliers");
    config_checks::require_count_at_least(max_planes, 1, prefix, "max_planes");
    require_at_least(iterations, 1, prefix, "iterations");
}

Plane facing(Plane plane, const Eigen::Vector3d& viewpoint) {
    if (plane.signed_distance(viewpoint) < 0.0) {
        plane.normal = -plane.normal;
        plane.offset_m = -plane.offset_m;
    }
    return plane;
}

std::vector<Plane> segment_planes(const PointCloud& cloud, const PlaneRansacConfig& config) {
    config.validate();
    check_consistent(cloud, "segment_planes");
    check_finite(cloud, "segment_planes");
    const Criteria criteria{config.distance_threshold_m,
                            std::cos(config.normal_threshold_deg * std::numbers::pi / 180.0),
                            cloud.has_normals()};
    Rng rng(config.seed);
    std::vector<std::size_t> remaining(cloud.size());
    std::iota(remaining.begin(), remaining.end(), std::size_t{0});
    std::vector<Plane> planes;
    while (planes.size() < config.max_planes && remaining.size() >= config.min_inliers) {
        const auto model = best_hypothesis(cloud, remaining, config, criteria, rng);
        if (!model) break;
        auto plane = refine(cloud, remaining, *model, config, criteria);
        if (!plane) break;
        remaining = without(remaining, plane->inliers);
        planes.push_back(std::move(*plane));
    }
    // Refits can reorder the support of near-equal planes; the contract is largest first.
    std::stable_sort(planes.begin(), planes.end(), [](const Plane& a, const Plane& b) {
        return a.inliers.size() > b.inliers.size();
    });
    return planes;
}

Plane fit_plane(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& towards) {
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!points[i].allFinite()) {
            throw InputError(fmt::format("fit_plane: point {} is not finite", i));
        }
    }
    if (points.size() < 3) {
        throw InputError(fmt::format("fit_plane: needs >= 3 points, got {}", points.size()));
    }
    auto plane = try_fit_plane(points, towards);
    if (!plane)
        throw InputError(fmt::format("fit_plane: the {} points are collinear", points.size()));
    plane->inliers.resize(points.size());
    std::iota(plane->inliers.begin(), plane->inliers.end(), std::size_t{0});
    return std::move(*plane);
}

}  // namespace scantling::perception
