#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/perception/surface_obstacles.hpp>

#include "detail/missing_returns.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include <fmt/format.h>

namespace scantling::perception {
namespace {

// Hypotheses are ranked on a fixed random subsample (as in plane_ransac.cpp): ranking needs only
// relative support; the winner's inliers are then collected over every point.
constexpr std::size_t kScoreSampleSize = 2000;
// Collect → refit rounds until the inlier set stops changing. On a curved wall each round
// reaches farther out (see the header); the cap bounds the cost.
constexpr int kMaxRefitRounds = 15;
constexpr int kSampleSize = 6;  // the height-field quadric's unknowns
// Height span below which the inliers do not determine g (see refit()).
constexpr double kCurvedHeightM = 0.03;

using Vector7d = Eigen::Matrix<double, 7, 1>;
using Matrix7d = Eigen::Matrix<double, 7, 7>;

/// The regressors of z in F = 0 (coefficient order of QuadricSurface).
Vector7d regressors(const Eigen::Vector3d& p) {
    Vector7d r;
    r << p.x() * p.x(), p.x() * p.y(), p.y() * p.y(), p.x(), p.y(), 1.0, p.z() * p.z();
    return r;
}

QuadricSurface from_coefficients(const Vector7d& c) {
    return QuadricSurface{c(0), c(1), c(2), c(3), c(4), c(5), c(6)};
}

/// The exact height-field quadric (g = 0) through six points; none when they are degenerate in
/// x-y (on a conic) or the surface is steeper or more curved than the config allows.
std::optional<QuadricSurface> hypothesis(const std::array<Eigen::Vector3d, kSampleSize>& pts,
                                         const SurfaceObstaclesConfig& config) {
    Eigen::Matrix<double, kSampleSize, kSampleSize> A;
    Eigen::Matrix<double, kSampleSize, 1> z;
    for (int i = 0; i < kSampleSize; ++i) {
        A.row(i) = regressors(pts[i]).head<kSampleSize>().transpose();
        z(i) = pts[i].z();
    }
    const Eigen::ColPivHouseholderQR<Eigen::Matrix<double, kSampleSize, kSampleSize>> qr(A);
    if (qr.rank() < kSampleSize) return std::nullopt;
    Vector7d c = Vector7d::Zero();
    c.head<kSampleSize>() = qr.solve(z);
    if (!c.allFinite()) return std::nullopt;
    // Hessian of the height field is [[2a, b], [b, 2c]]: its eigenvalues are the principal
    // curvatures (at small slope), bounded by 1/min_radius_m.
    Eigen::Matrix2d hessian;
    hessian << 2.0 * c(0), c(1), c(1), 2.0 * c(2);
    const double max_curvature = hessian.eigenvalues().cwiseAbs().maxCoeff();
    const double tan_tilt = std::tan(config.max_tilt_deg * std::numbers::pi / 180.0);
    if (max_curvature * config.min_radius_m > 1.0) return std::nullopt;
    if (std::hypot(c(3), c(4)) > tan_tilt) return std::nullopt;
    return from_coefficients(c);
}

std::size_t support(const std::vector<Eigen::Vector3d>& sample, const QuadricSurface& s,
                    double threshold_m) {
    std::size_t n = 0;
    for (const auto& p : sample) n += std::abs(s.signed_distance_m(p)) <= threshold_m ? 1 : 0;
    return n;
}

std::optional<QuadricSurface> best_hypothesis(const std::vector<Eigen::Vector3d>& points,
                                              const SurfaceObstaclesConfig& config, Rng& rng) {
    std::vector<Eigen::Vector3d> sample;
    for (const std::size_t k :
         rng.sample_indices(points.size(), std::min(kScoreSampleSize, points.size()))) {
        sample.push_back(points[k]);
    }
    std::optional<QuadricSurface> best;
    std::size_t best_support = 0;
    for (int it = 0; it < config.iterations; ++it) {
        const auto idx = rng.sample_indices(sample.size(), kSampleSize);
        std::array<Eigen::Vector3d, kSampleSize> picks;
        for (std::size_t i = 0; i < idx.size(); ++i) picks[i] = sample[idx[i]];
        const auto s = hypothesis(picks, config);
        if (!s) continue;
        const std::size_t n = support(sample, *s, config.inlier_threshold_m);
        if (!best || n > best_support) {  // the first of equals wins: deterministic
            best = s;
            best_support = n;
        }
    }
    return best;
}

std::vector<std::size_t> collect(const std::vector<Eigen::Vector3d>& points,
                                 const QuadricSurface& s, double threshold_m) {
    std::vector<std::size_t> inliers;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (std::abs(s.signed_distance_m(points[i])) <= threshold_m) inliers.push_back(i);
    }
    return inliers;
}

/// Weighted least squares on the inliers: each row F(p) = 0 is divided by |∇F(p)| of the
/// previous surface (Sampson), so the residuals are distances. The ridge on g acts as if every
/// inlier also said g · (3 cm)² = 0: negligible on a curved wall, whose inliers span decimetres
/// of height (z⁴ ~ 5e-4 m⁴ on the Ø 5 m tank's convex side against 8e-7), decisive on a plate,
/// where z² is only noise and a few obstacle points in the inlier band (always above) pulled an
/// unregularised g to ~1.5 /m in the tests: its second sheet 0.7 m over the plate.
std::optional<QuadricSurface> refit(const std::vector<Eigen::Vector3d>& points,
                                    const std::vector<std::size_t>& inliers,
                                    const QuadricSurface& previous) {
    Matrix7d H = Matrix7d::Zero();
    Vector7d b = Vector7d::Zero();
    for (const std::size_t i : inliers) {
        const Vector7d r = regressors(points[i]);
        const double w2 = 1.0 / previous.gradient(points[i]).squaredNorm();
        H.selfadjointView<Eigen::Lower>().rankUpdate(r, w2);
        b += w2 * points[i].z() * r;
    }
    H(6, 6) += static_cast<double>(inliers.size()) * std::pow(kCurvedHeightM, 4);
    const Eigen::LDLT<Matrix7d> ldlt(H.selfadjointView<Eigen::Lower>());
    if (ldlt.info() != Eigen::Success) return std::nullopt;
    const Vector7d c = ldlt.solve(b);
    if (!c.allFinite()) return std::nullopt;
    return from_coefficients(c);
}

/// Collect → refit until the inliers stop changing; the surface returned is fitted to them.
std::pair<QuadricSurface, std::vector<std::size_t>> refine(
    const std::vector<Eigen::Vector3d>& points, QuadricSurface surface,
    const SurfaceObstaclesConfig& config) {
    std::vector<std::size_t> inliers = collect(points, surface, config.inlier_threshold_m);
    for (int round = 0; round < kMaxRefitRounds && inliers.size() >= kSampleSize; ++round) {
        const auto next = refit(points, inliers, surface);
        if (!next) break;
        surface = *next;
        auto next_inliers = collect(points, surface, config.inlier_threshold_m);
        const bool settled = next_inliers == inliers;
        inliers = std::move(next_inliers);
        if (settled) break;
    }
    return {surface, std::move(inliers)};
}

/// One point per x-y column of `cell_m`: the mean x, y and the median z of its points, in
/// column order. See SurfaceObstaclesConfig::column_median. Independent of the input order to
/// the bit: each column's points are sorted before their x, y are summed (a floating-point sum
/// depends on its order, and a last-bit change of one point moves the fitted surface).
PointCloud column_medians(const PointCloud& cloud, double cell_m) {
    std::map<std::pair<std::int64_t, std::int64_t>, std::vector<Eigen::Vector3d>> columns;
    for (const auto& p : cloud.points) {
        columns[{static_cast<std::int64_t>(std::floor(p.x() / cell_m)),
                 static_cast<std::int64_t>(std::floor(p.y() / cell_m))}]
            .push_back(p);
    }
    PointCloud out;
    out.points.reserve(columns.size());
    for (auto& [key, points] : columns) {
        std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
            return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
        });
        Eigen::Vector2d xy = Eigen::Vector2d::Zero();
        std::vector<double> z;
        z.reserve(points.size());
        for (const auto& p : points) {
            xy += p.head<2>();
            z.push_back(p.z());
        }
        const auto mid = z.begin() + static_cast<std::ptrdiff_t>(z.size() / 2);
        std::nth_element(z.begin(), mid, z.end());
        xy /= static_cast<double>(points.size());
        out.points.emplace_back(xy.x(), xy.y(), *mid);
    }
    return out;
}

/// The finite points within max_range_m (x-y) of the robot, voxelised (or column medians).
PointCloud prepare(const PointCloud& cloud, const SurfaceObstaclesConfig& config,
                   SurfaceObstacles& result) {
    PointCloud in_range;
    for (const auto& p : cloud.points) {
        if (!p.allFinite()) {
            ++result.num_non_finite;
        } else if (p.head<2>().norm() > config.max_range_m) {
            ++result.num_out_of_range;
        } else {
            in_range.points.push_back(p);
        }
    }
    if (config.column_median) return column_medians(in_range, config.voxel_size_m);
    VoxelGridConfig voxel;
    voxel.voxel_size_m = config.voxel_size_m;
    voxel.parallel = config.parallel;
    return voxel_downsample(in_range, voxel);
}

SurfaceLabel label_of(double distance_m, const SurfaceObstaclesConfig& config) {
    if (std::abs(distance_m) <= config.inlier_threshold_m) return SurfaceLabel::kFree;
    if (distance_m > config.obstacle_threshold_m) return SurfaceLabel::kPositive;
    if (distance_m < -config.obstacle_threshold_m) return SurfaceLabel::kNegative;
    return SurfaceLabel::kUncertain;
}

void label_points(SurfaceObstacles& result, const std::vector<std::size_t>& inliers,
                  const SurfaceObstaclesConfig& config) {
    for (const auto& p : result.points.points) {
        const double d = result.surface.signed_distance_m(p);
        result.distances_m.push_back(d);
        result.labels.push_back(label_of(d, config));
    }
    double sum_sq_m2 = 0.0;
    for (const std::size_t i : inliers) sum_sq_m2 += result.distances_m[i] * result.distances_m[i];
    result.num_inliers = inliers.size();
    result.inlier_rms_m =
        inliers.empty() ? 0.0 : std::sqrt(sum_sq_m2 / static_cast<double>(inliers.size()));
}

// ---- grid -------------------------------------------------------------------------------

SurfaceGrid empty_grid(const SurfaceObstaclesConfig& config) {
    SurfaceGrid grid;
    grid.cell_size_m = config.cell_size_m;
    grid.cells_per_side = 2 * static_cast<int>(std::ceil(config.max_range_m / config.cell_size_m));
    const double half_m = 0.5 * grid.cells_per_side * grid.cell_size_m;
    grid.origin_xy_m = Eigen::Vector2d(-half_m, -half_m);
    grid.cells.assign(static_cast<std::size_t>(grid.cells_per_side) * grid.cells_per_side,
                      SurfaceLabel::kUnknown);
    return grid;
}

std::optional<std::size_t> cell_index(const SurfaceGrid& grid, const Eigen::Vector2d& p) {
    const Eigen::Vector2d q = (p - grid.origin_xy_m) / grid.cell_size_m;
    if (!(q.x() >= 0.0 && q.y() >= 0.0 && q.x() < grid.cells_per_side &&
          q.y() < grid.cells_per_side)) {
        return std::nullopt;
    }
    return static_cast<std::size_t>(std::floor(q.y())) * grid.cells_per_side +
           static_cast<std::size_t>(std::floor(q.x()));
}

using CellCounts = std::vector<std::array<std::uint32_t, 4>>;  // per cell, per point label

CellCounts count_labels(const SurfaceGrid& grid, const SurfaceObstacles& result) {
    CellCounts counts(grid.cells.size(), {0, 0, 0, 0});
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        const auto c = cell_index(grid, result.points.points[i].head<2>());
        if (c) ++counts[*c][static_cast<std::size_t>(result.labels[i])];
    }
    return counts;
}

/// Points of `label` in the 3×3 cells around cell c.
std::uint32_t neighbourhood_count(const SurfaceGrid& grid, const CellCounts& counts, std::size_t c,
                                  SurfaceLabel label) {
    const int n = grid.cells_per_side;
    const int ix = static_cast<int>(c % n), iy = static_cast<int>(c / n);
    std::uint32_t total = 0;
    for (int jy = std::max(iy - 1, 0); jy <= std::min(iy + 1, n - 1); ++jy) {
        for (int jx = std::max(ix - 1, 0); jx <= std::min(ix + 1, n - 1); ++jx) {
            total += counts[static_cast<std::size_t>(jy) * n + jx][static_cast<std::size_t>(label)];
        }
    }
    return total;
}

/// An obstacle point without min_obstacle_support points of its sign within a cell around it
/// becomes uncertain: with 3 mm noise a 12 mm threshold is 4σ, so ~1e-4 of the surface points
/// cross it, alone; every real obstacle in the tests gives several (a Ø 20 mm bolt ~4).
void require_support(SurfaceObstacles& result, const SurfaceGrid& grid,
                     const SurfaceObstaclesConfig& config) {
    const CellCounts counts = count_labels(grid, result);
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        const SurfaceLabel l = result.labels[i];
        if (l != SurfaceLabel::kPositive && l != SurfaceLabel::kNegative) continue;
        const auto c = cell_index(grid, result.points.points[i].head<2>());
        if (c && neighbourhood_count(grid, counts, *c, l) < config.min_obstacle_support) {
            result.labels[i] = SurfaceLabel::kUncertain;
        }
    }
}

/// Any obstacle point makes its cell an obstacle (the crawler must not drive onto a bolt that
/// shares a cell with the plate); positive and negative points vote; then free, then uncertain.
void fill_cells(SurfaceGrid& grid, const SurfaceObstacles& result) {
    const CellCounts counts = count_labels(grid, result);
    for (std::size_t c = 0; c < grid.cells.size(); ++c) {
        const auto& n = counts[c];
        const auto at = [&](SurfaceLabel l) { return n[static_cast<std::size_t>(l)]; };
        if (at(SurfaceLabel::kPositive) + at(SurfaceLabel::kNegative) > 0) {
            grid.cells[c] = at(SurfaceLabel::kPositive) >= at(SurfaceLabel::kNegative)
                                ? SurfaceLabel::kPositive
                                : SurfaceLabel::kNegative;
        } else if (at(SurfaceLabel::kFree) > 0) {
            grid.cells[c] = SurfaceLabel::kFree;
        } else if (at(SurfaceLabel::kUncertain) > 0) {
            grid.cells[c] = SurfaceLabel::kUncertain;
        }
    }
}

/// Cells of the connected component of `label` holding `seed` (4- or 8-connected), marked in
/// `seen`; breadth-first, so the order is deterministic.
std::vector<std::size_t> component(const SurfaceGrid& grid, std::size_t seed, SurfaceLabel label,
                                   bool eight_connected, std::vector<bool>& seen) {
    const int n = grid.cells_per_side;
    std::vector<std::size_t> cells{seed};
    seen[seed] = true;
    for (std::size_t k = 0; k < cells.size(); ++k) {
        const int ix = static_cast<int>(cells[k] % n), iy = static_cast<int>(cells[k] / n);
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                if ((dx == 0 && dy == 0) || (!eight_connected && dx != 0 && dy != 0)) continue;
                const int jx = ix + dx, jy = iy + dy;
                if (jx < 0 || jy < 0 || jx >= n || jy >= n) continue;
                const auto j = static_cast<std::size_t>(jy) * n + jx;
                if (seen[j] || grid.cells[j] != label) continue;
                seen[j] = true;
                cells.push_back(j);
            }
        }
    }
    return cells;
}

bool on_border(const SurfaceGrid& grid, std::size_t c) {
    const int n = grid.cells_per_side;
    const int ix = static_cast<int>(c % n), iy = static_cast<int>(c / n);
    return ix == 0 || iy == 0 || ix == n - 1 || iy == n - 1;
}

/// Obstacle cells within rim_cells of a cell without points (or of the grid's border) become
/// uncertain, and so do their points. See SurfaceObstaclesConfig::rim_cells.
void erode_rim(SurfaceObstacles& result, int rim_cells) {
    if (rim_cells <= 0) return;
    SurfaceGrid& grid = result.grid;
    const int n = grid.cells_per_side;
    const std::vector<SurfaceLabel> before = grid.cells;
    const auto near_unknown = [&](int ix, int iy) {
        for (int dy = -rim_cells; dy <= rim_cells; ++dy) {
            for (int dx = -rim_cells; dx <= rim_cells; ++dx) {
                const int x = ix + dx, y = iy + dy;
                if (x < 0 || y < 0 || x >= n || y >= n) return true;
                if (before[static_cast<std::size_t>(y * n + x)] == SurfaceLabel::kUnknown)
                    return true;
            }
        }
        return false;
    };
    for (int iy = 0; iy < n; ++iy) {
        for (int ix = 0; ix < n; ++ix) {
            SurfaceLabel& l = grid.cells[static_cast<std::size_t>(iy * n + ix)];
            const bool obstacle = l == SurfaceLabel::kPositive || l == SurfaceLabel::kNegative;
            if (obstacle && near_unknown(ix, iy)) l = SurfaceLabel::kUncertain;
        }
    }
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        const auto c = cell_index(grid, result.points.points[i].head<2>());
        const SurfaceLabel l = result.labels[i];
        const bool obstacle = l == SurfaceLabel::kPositive || l == SurfaceLabel::kNegative;
        if (obstacle && c && grid.cells[*c] == SurfaceLabel::kUncertain) {
            result.labels[i] = SurfaceLabel::kUncertain;
        }
    }
}

/// Unknown regions not 4-connected to the border, of at least the configured size, become
/// negative obstacles (see the header).
void mark_enclosed_unknown(SurfaceGrid& grid, const SurfaceObstaclesConfig& config) {
    std::vector<bool> seen(grid.cells.size(), false);
    for (std::size_t c = 0; c < grid.cells.size(); ++c) {
        if (seen[c] || grid.cells[c] != SurfaceLabel::kUnknown) continue;
        const auto cells = component(grid, c, SurfaceLabel::kUnknown, false, seen);
        const bool enclosed = std::none_of(cells.begin(), cells.end(),
                                           [&](std::size_t k) { return on_border(grid, k); });
        if (!enclosed || cells.size() < config.min_enclosed_unknown_cells) continue;
        for (const std::size_t k : cells) grid.cells[k] = SurfaceLabel::kNegative;
    }
}

ObstacleCluster summarise(const SurfaceGrid& grid, const std::vector<std::size_t>& cells,
                          SurfaceLabel label) {
    ObstacleCluster cluster;
    cluster.label = label;
    cluster.num_cells = cells.size();
    const Eigen::Vector2d half(0.5 * grid.cell_size_m, 0.5 * grid.cell_size_m);
    cluster.min_xy_m.setConstant(std::numeric_limits<double>::infinity());
    cluster.max_xy_m = -cluster.min_xy_m;
    for (const std::size_t c : cells) {
        const int n = grid.cells_per_side;
        const Eigen::Vector2d centre =
            grid.cell_centre(static_cast<int>(c % n), static_cast<int>(c / n));
        cluster.centroid_xy_m += centre / static_cast<double>(cells.size());
        cluster.min_xy_m = cluster.min_xy_m.cwiseMin(centre - half);
        cluster.max_xy_m = cluster.max_xy_m.cwiseMax(centre + half);
    }
    return cluster;
}

/// The obstacle clusters; one smaller than min_cluster_cells is relabelled uncertain in the grid.
std::vector<ObstacleCluster> find_clusters(SurfaceGrid& grid, std::size_t min_cluster_cells) {
    std::vector<ObstacleCluster> clusters;
    std::vector<bool> seen(grid.cells.size(), false);
    for (const SurfaceLabel label : {SurfaceLabel::kPositive, SurfaceLabel::kNegative}) {
        for (std::size_t c = 0; c < grid.cells.size(); ++c) {
            if (seen[c] || grid.cells[c] != label) continue;
            const auto cells = component(grid, c, label, true, seen);
            if (cells.size() < min_cluster_cells) {
                for (const auto cell : cells) grid.cells[cell] = SurfaceLabel::kUncertain;
                continue;
            }
            clusters.push_back(summarise(grid, cells, label));
        }
    }
    return clusters;
}

void rasterise(SurfaceObstacles& result, const SurfaceObstaclesConfig& config,
               const std::optional<ExpectedView>& view) {
    result.grid = empty_grid(config);
    if (result.status == SurfaceStatus::kOk) require_support(result, result.grid, config);
    fill_cells(result.grid, result);
    erode_rim(result, config.rim_cells);
    if (view && result.status == SurfaceStatus::kOk) {
        detail::mark_missing_returns(result.grid, result.surface, *view);
    }
    if (config.enclosed_unknown_is_negative) mark_enclosed_unknown(result.grid, config);
    result.clusters = find_clusters(result.grid, config.min_cluster_cells);
}

}  // namespace

void SurfaceObstaclesConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(voxel_size_m, prefix, "voxel_size_m");
    require_positive(max_range_m, prefix, "max_range_m");
    require_positive(inlier_threshold_m, prefix, "inlier_threshold_m");
    require(std::isfinite(obstacle_threshold_m) && obstacle_threshold_m >= inlier_threshold_m,
            prefix, "obstacle_threshold_m", obstacle_threshold_m, ">= inlier_threshold_m");
    require_at_least(iterations, 1, prefix, "iterations");
    require_count_at_least(min_points, kSampleSize, prefix, "min_points");
    require_positive(min_radius_m, prefix, "min_radius_m");
    require(std::isfinite(max_tilt_deg) && max_tilt_deg > 0.0 && max_tilt_deg < 90.0, prefix,
            "max_tilt_deg", max_tilt_deg, "in (0, 90)");
    require_positive(cell_size_m, prefix, "cell_size_m");
    // A grid of more than 4096² cells is a unit mistake (cm for m), not a map.
    require(max_range_m / cell_size_m <= 2048.0, prefix, "cell_size_m", cell_size_m,
            ">= max_range_m / 2048");
    require_count_at_least(min_obstacle_support, 1, prefix, "min_obstacle_support");
    require_count_at_least(min_enclosed_unknown_cells, 1, prefix, "min_enclosed_unknown_cells");
    require_count_at_least(min_cluster_cells, 1, prefix, "min_cluster_cells");
    config_checks::require(rim_cells >= 0 && rim_cells <= 50, prefix, "rim_cells", rim_cells,
                           "in [0, 50]");
    parallel.validate(fmt::format("{}.parallel", prefix));
}

double QuadricSurface::residual(const Eigen::Vector3d& p) const {
    const double x = p.x(), y = p.y(), z = p.z();
    return xx * x * x + xy * x * y + yy * y * y + x_slope * x + y_slope * y + offset_m +
           zz * z * z - z;
}

Eigen::Vector3d QuadricSurface::gradient(const Eigen::Vector3d& p) const {
    return {2.0 * xx * p.x() + xy * p.y() + x_slope, xy * p.x() + 2.0 * yy * p.y() + y_slope,
            2.0 * zz * p.z() - 1.0};
}

double QuadricSurface::height_m(const Eigen::Vector2d& p) const {
    const double x = p.x(), y = p.y();
    const double poly = xx * x * x + xy * x * y + yy * y * y + x_slope * x + y_slope * y + offset_m;
    double z = poly;
    for (int i = 0; i < 3; ++i) z = poly + zz * z * z;
    return std::isfinite(z) ? z : poly;
}

double QuadricSurface::signed_distance_m(const Eigen::Vector3d& p) const {
    return -residual(p) / gradient(p).norm();
}

SurfaceLabel SurfaceGrid::label_at(const Eigen::Vector2d& p_body_xy_m) const {
    const auto c = cell_index(*this, p_body_xy_m);
    return c ? cells[*c] : SurfaceLabel::kUnknown;
}

Eigen::Vector2d SurfaceGrid::cell_centre(int ix, int iy) const {
    return origin_xy_m + cell_size_m * Eigen::Vector2d(ix + 0.5, iy + 0.5);
}

SurfaceObstacles detect_surface_obstacles(const PointCloud& cloud_body,
                                          const SurfaceObstaclesConfig& config,
                                          const std::optional<ExpectedView>& view) {
    if (view && (!(view->half_fov_rad > 0.0 && view->half_fov_rad <= std::numbers::pi / 2) ||
                 !(view->margin_rad >= 0.0) || !(view->max_range_m > 0.0) ||
                 !view->T_body_sensor.matrix().allFinite())) {
        throw InputError(
            "detect_surface_obstacles: the expected view needs a finite mount, "
            "half_fov_rad in (0, pi/2], margin_rad >= 0 and max_range_m > 0");
    }
    config.validate();
    check_consistent(cloud_body, "detect_surface_obstacles");
    SurfaceObstacles result;
    result.points = prepare(cloud_body, config, result);
    const std::vector<Eigen::Vector3d>& points = result.points.points;
    std::optional<QuadricSurface> start;
    if (points.size() >= config.min_points) {
        Rng rng(config.seed);
        start = best_hypothesis(points, config, rng);
        result.status = SurfaceStatus::kNoSurface;
    }
    if (start) {
        auto [surface, inliers] = refine(points, *start, config);
        if (inliers.size() >= config.min_points) {
            result.status = SurfaceStatus::kOk;
            result.surface = surface;
            label_points(result, inliers, config);
        }
    }
    if (result.status != SurfaceStatus::kOk) {
        result.labels.assign(points.size(), SurfaceLabel::kUncertain);
        result.distances_m.assign(points.size(), 0.0);
    }
    rasterise(result, config, view);
    return result;
}

}  // namespace scantling::perception
