#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <scantling/core/error.hpp>
#include <scantling/odometry/edge_registration.hpp>
#include <string>
#include <vector>

namespace scantling::odometry {
namespace {

void require(bool ok, const std::string& prefix, const char* field, double value,
             const char* expected) {
    if (!ok) {
        throw ConfigError(prefix + "." + field + " = " + std::to_string(value) + ", expected " +
                          expected);
    }
}

struct NormalEquations {
    Matrix6d H = Matrix6d::Zero();
    Vector6d g = Vector6d::Zero();
    std::size_t count = 0;
    double sum_sq_distance = 0.0;
};

NormalEquations linearize(const EdgeFeatures& edges, const std::vector<EdgeLine>& lines,
                          const std::vector<double>& weights, const Eigen::Isometry3d& T,
                          double huber_delta_m) {
    NormalEquations ne;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (!lines[i].valid) continue;
        const Eigen::Vector3d q = T * edges.points[i];
        const Eigen::Vector3d& u = lines[i].direction;
        const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - u * u.transpose();
        const Eigen::Vector3d r = P * (q - lines[i].centroid);
        const double d = r.norm();
        const double omega = weights[i];
        const double s = omega * d;
        // IRLS weight of the Huber loss on the weighted residual.
        const double huber = s <= huber_delta_m ? 1.0 : huber_delta_m / s;
        const double w = huber * omega * omega;
        Eigen::Matrix<double, 3, 6> J;
        J.leftCols<3>() = P;
        J.rightCols<3>() = -P * hat(q);
        ne.H.noalias() += w * J.transpose() * J;
        ne.g.noalias() += w * J.transpose() * r;
        ne.sum_sq_distance += d * d;
        ++ne.count;
    }
    return ne;
}

/// Adds the point-to-plane residuals n·(T p − c) of the planar points to `ne`.
void add_planes(const EdgeFeatures& edges, const std::vector<SurfacePatch>& patches,
                const std::vector<double>& weights, const Eigen::Isometry3d& T,
                double huber_delta_m, NormalEquations& ne) {
    for (std::size_t i = 0; i < patches.size(); ++i) {
        if (!patches[i].valid) continue;
        const Eigen::Vector3d q = T * edges.plane_points[i];
        const Eigen::Vector3d& n = patches[i].normal;
        const double d = n.dot(q - patches[i].centroid);
        const double s = weights[i] * std::abs(d);
        const double huber = s <= huber_delta_m ? 1.0 : huber_delta_m / s;
        const double w = huber * weights[i] * weights[i];
        Vector6d J;
        J.head<3>() = n;
        J.tail<3>() = q.cross(n);  // n^T (-hat(q)) as a column
        ne.H.noalias() += w * J * J.transpose();
        ne.g.noalias() += w * J * d;
        ne.sum_sq_distance += d * d;
        ++ne.count;
    }
}

/// Range of point i: its recorded range, or its norm when the features carry no ranges.
double range_of(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& ranges_m,
                std::size_t i) {
    return i < ranges_m.size() ? ranges_m[i] : points[i].norm();
}

/// The normal equations of every valid edge and planar correspondence at T.
NormalEquations linearize_all(const EdgeFeatures& edges, const std::vector<EdgeLine>& lines,
                              const std::vector<double>& weights,
                              const std::vector<SurfacePatch>& patches,
                              const std::vector<double>& plane_weights, const Eigen::Isometry3d& T,
                              double huber_delta_m) {
    NormalEquations ne = linearize(edges, lines, weights, T, huber_delta_m);
    add_planes(edges, patches, plane_weights, T, huber_delta_m, ne);
    return ne;
}

/// The `num_neighbors` nearest map points of `query`, all within `max_neighbor_distance_m`:
/// their centroid and the eigen-decomposition of their covariance (eigenvalues ascending).
/// False when fewer are that close.
bool neighbour_shape(const LocalMap& map, const Eigen::Vector3d& query,
                     const EdgeRegistrationConfig& config, std::vector<Eigen::Vector3d>& points,
                     std::vector<double>& distances, Eigen::Vector3d& mean,
                     Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>& eig) {
    const auto k = static_cast<std::size_t>(config.num_neighbors);
    // Neighbours beyond the limit would reject the fit anyway: the bounded search skips them.
    if (map.knn_within(query, k, config.max_neighbor_distance_m, points, distances) < k) {
        return false;
    }
    mean.setZero();
    for (const auto& p : points) mean += p;
    mean /= static_cast<double>(k);
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : points) cov += (p - mean) * (p - mean).transpose();
    cov /= static_cast<double>(k);
    eig.computeDirect(cov);
    return true;
}

}  // namespace

SurfacePatch fit_surface_patch(const LocalMap& map, const Eigen::Vector3d& query,
                               const EdgeRegistrationConfig& config,
                               std::vector<Eigen::Vector3d>& points,
                               std::vector<double>& distances) {
    SurfacePatch patch;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    if (!neighbour_shape(map, query, config, points, distances, patch.centroid, eig)) return patch;
    const Eigen::Vector3d& lambda = eig.eigenvalues();
    if (!(lambda(1) > 0.0) || lambda(1) < config.plane_eigen_ratio * lambda(0)) return patch;
    patch.normal = eig.eigenvectors().col(0).normalized();
    patch.valid = true;
    return patch;
}

EdgeLine fit_edge_line(const LocalMap& map, const Eigen::Vector3d& query,
                       const EdgeRegistrationConfig& config, std::vector<Eigen::Vector3d>& points,
                       std::vector<double>& distances) {
    EdgeLine line;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    if (!neighbour_shape(map, query, config, points, distances, line.centroid, eig)) return line;
    const Eigen::Vector3d& lambda = eig.eigenvalues();
    if (!(lambda(2) > 0.0) || lambda(2) < config.line_eigen_ratio * lambda(1)) return line;
    line.direction = eig.eigenvectors().col(2).normalized();
    line.valid = true;
    return line;
}

double edge_range_weight(double range_m, double min_range_m, double max_range_m, bool enabled) {
    if (!enabled || !(max_range_m > min_range_m)) return 1.0;
    const double w = 1.0 - (range_m - min_range_m) / (max_range_m - min_range_m);
    return std::clamp(w, 0.0, 1.0);
}

void EdgeRegistrationConfig::validate(std::string_view prefix) const {
    const std::string p(prefix);
    require(num_neighbors >= 2, p, "num_neighbors", num_neighbors, ">= 2");
    require(max_neighbor_distance_m > 0.0 && std::isfinite(max_neighbor_distance_m), p,
            "max_neighbor_distance_m", max_neighbor_distance_m, "> 0");
    require(line_eigen_ratio >= 1.0 && std::isfinite(line_eigen_ratio), p, "line_eigen_ratio",
            line_eigen_ratio, ">= 1");
    require(plane_eigen_ratio > 1.0 && std::isfinite(plane_eigen_ratio), p, "plane_eigen_ratio",
            plane_eigen_ratio, "> 1");
    require(huber_delta_m > 0.0 && std::isfinite(huber_delta_m), p, "huber_delta_m", huber_delta_m,
            "> 0");
    require(max_iterations >= 1, p, "max_iterations", max_iterations, ">= 1");
    require(inner_iterations >= 1, p, "inner_iterations", inner_iterations, ">= 1");
    require(refit_distance_m >= 0.0 && std::isfinite(refit_distance_m), p, "refit_distance_m",
            refit_distance_m, ">= 0");
    require(min_correspondences >= 6, p, "min_correspondences", min_correspondences, ">= 6");
    require(convergence_translation_m >= 0.0, p, "convergence_translation_m",
            convergence_translation_m, ">= 0");
    require(convergence_rotation_rad >= 0.0, p, "convergence_rotation_rad",
            convergence_rotation_rad, ">= 0");
    require(degeneracy_ratio >= 0.0 && degeneracy_ratio < 1.0, p, "degeneracy_ratio",
            degeneracy_ratio, "in [0, 1)");
    parallel.validate(p + ".parallel");
}

namespace {

/// `H` without its directions weaker than `ratio` × the strongest (judged in the scaled frame
/// of `D`, as the degeneracy test): after solution remapping the pose along them is the
/// prior's, so the registration carries no information there.
Matrix6d observed_information(const Matrix6d& H, const Matrix6d& D, double ratio) {
    const Matrix6d Hs = D * H * D;
    const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(0.5 * (Hs + Hs.transpose()));
    const Vector6d& lambda = eig.eigenvalues();
    Matrix6d kept = Matrix6d::Zero();
    for (int j = 0; j < 6; ++j) {
        if (!(lambda(j) > ratio * lambda(5)) || !(lambda(j) > 0.0)) continue;
        kept += lambda(j) * eig.eigenvectors().col(j) * eig.eigenvectors().col(j).transpose();
    }
    const Matrix6d D_inverse = D.inverse();
    return D_inverse * kept * D_inverse;
}

}  // namespace

EdgeRegistrationResult register_edges(const EdgeFeatures& edges, const LocalMap& map,
                                      const Eigen::Isometry3d& T_init, double min_range_m,
                                      double max_range_m, const EdgeRegistrationConfig& config,
                                      const LocalMap* plane_map) {
    config.validate();
    EdgeRegistrationResult result;
    result.T_world_sensor = T_init;
    const std::size_t n = edges.points.size();
    if (n < static_cast<std::size_t>(config.min_correspondences) || map.empty()) return result;

    std::vector<double> weights(n);
    double mean_range = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double r = range_of(edges.points, edges.ranges_m, i);
        weights[i] = edge_range_weight(r, min_range_m, max_range_m, config.range_weighting);
        mean_range += r;
    }
    mean_range = std::max(mean_range / static_cast<double>(n), 1e-3);
    // Rotation in "metres at the mean range", so eigenvalues of translation and rotation compare.
    Vector6d scale;
    scale << 1.0, 1.0, 1.0, 1.0 / mean_range, 1.0 / mean_range, 1.0 / mean_range;
    const Matrix6d D = scale.asDiagonal();

    const std::size_t m = plane_map && !plane_map->empty() ? edges.plane_points.size() : 0;
    std::vector<double> plane_weights(m);
    for (std::size_t i = 0; i < m; ++i) {
        const double r = range_of(edges.plane_points, edges.plane_ranges_m, i);
        plane_weights[i] = edge_range_weight(r, min_range_m, max_range_m, config.range_weighting);
    }

    Eigen::Isometry3d T = T_init;
    std::vector<EdgeLine> lines(n);
    std::vector<SurfacePatch> patches(m);
    // Where each edge (then each planar point) was when its line (plane) was fitted.
    std::vector<Eigen::Vector3d> fitted_at(n + m);
    const double refit_sq_m2 = config.refit_distance_m * config.refit_distance_m;
    NormalEquations ne;
    for (int outer = 0; outer < config.max_iterations; ++outer) {
        parallel_for(config.parallel, n + m, 256, [&](std::size_t begin, std::size_t end) {
            std::vector<Eigen::Vector3d> points;
            std::vector<double> distances;
            for (std::size_t i = begin; i < end; ++i) {
                const bool edge = i < n;
                const Eigen::Vector3d query =
                    T * (edge ? edges.points[i] : edges.plane_points[i - n]);
                if (outer > 0 && (query - fitted_at[i]).squaredNorm() <= refit_sq_m2) continue;
                if (edge) {
                    lines[i] = fit_edge_line(map, query, config, points, distances);
                } else {
                    patches[i - n] =
                        fit_surface_patch(*plane_map, query, config, points, distances);
                }
                fitted_at[i] = query;
            }
        });
        bool converged = false;
        for (int inner = 0; inner < config.inner_iterations; ++inner) {
            ne = linearize_all(edges, lines, weights, patches, plane_weights, T,
                               config.huber_delta_m);
            if (ne.count < static_cast<std::size_t>(config.min_correspondences)) {
                result.T_world_sensor = T_init;
                result.num_correspondences = ne.count;
                result.iterations = outer + 1;
                return result;
            }
            const Matrix6d Hs = D * ne.H * D;
            const Vector6d gs = D * ne.g;
            Eigen::SelfAdjointEigenSolver<Matrix6d> eig(Hs);
            const Vector6d& lambda = eig.eigenvalues();
            const double threshold = config.degeneracy_ratio * lambda(5);
            Vector6d step_s = Vector6d::Zero();
            Vector6d observed_s = Vector6d::Zero();  // step_s along the well-observed directions
            int degenerate = 0;
            // Without remapping, a tiny floor keeps a truly null direction from blowing up.
            const double floor = 1e-12 * std::max(lambda(5), 1e-300);
            for (int j = 0; j < 6; ++j) {
                const bool weak = !(lambda(j) > threshold) || !(lambda(j) > 0.0);
                if (weak) ++degenerate;
                if ((weak && config.remap_degenerate) || !(lambda(j) > floor)) continue;
                const Vector6d v = eig.eigenvectors().col(j);
                const Vector6d along = v * (v.dot(gs) / lambda(j));
                step_s -= along;
                if (!weak) observed_s -= along;
            }
            const Vector6d step = D * step_s;
            const Vector6d tested = config.converge_on_observed ? Vector6d(D * observed_s) : step;
            T = se3_exp(step) * T;
            result.eigenvalues = lambda;
            result.min_eigen_ratio = lambda(5) > 0.0 ? std::max(lambda(0), 0.0) / lambda(5) : 0.0;
            result.num_degenerate = degenerate;
            result.degenerate_directions.resize(6, degenerate);
            for (int j = 0, c = 0; j < 6; ++j) {
                if (!(lambda(j) > threshold) || !(lambda(j) > 0.0)) {
                    result.degenerate_directions.col(c++) = eig.eigenvectors().col(j);
                }
            }
            converged = tested.head<3>().norm() < config.convergence_translation_m &&
                        tested.tail<3>().norm() < config.convergence_rotation_rad;
            if (converged) break;
        }
        result.iterations = outer + 1;
        if (converged) {
            result.converged = true;
            break;
        }
    }
    // Thousands of composed updates would drift off SO(3).
    T.linear() = orthonormalize(T.linear());
    // Statistics at the final pose with the last correspondences.
    ne = linearize_all(edges, lines, weights, patches, plane_weights, T, config.huber_delta_m);
    result.T_world_sensor = T;
    result.registered = true;
    result.num_correspondences = ne.count;
    result.information =
        config.remap_degenerate ? observed_information(ne.H, D, config.degeneracy_ratio) : ne.H;
    result.rmse_m =
        ne.count > 0 ? std::sqrt(ne.sum_sq_distance / static_cast<double>(ne.count)) : 0.0;
    return result;
}

}  // namespace scantling::odometry
