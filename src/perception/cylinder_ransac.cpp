#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/perception/cylinder_ransac.hpp>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace scantling::perception {
namespace {

// Hypotheses are ranked on a fixed random subsample (as in plane_ransac.cpp): ranking needs
// only relative support; the winner's inliers are then collected over every point.
constexpr std::size_t kScoreSampleSize = 2000;
// Gauss–Newton → recollect rounds until the inlier set stops changing. On a short arc the
// fit is weakly determined along one direction (centre along the bisector and radius
// together), so a fit to the points inside the start circle's band is pulled towards that
// circle; each round removes part of the pull (1–3 rounds from an MSAC start in the tests,
// up to 10 from a count-ranked one). The cap bounds the cost.
constexpr int kMaxRefitRounds = 10;
// Gauss–Newton on a circle converges quadratically from a RANSAC start: ~3–5 steps reach the
// step tolerance; the cap only guards against a degenerate normal matrix.
constexpr int kMaxGaussNewtonSteps = 20;
constexpr double kStepToleranceM = 1e-10;
// Two normals closer than ~0.5° to parallel put the centre at infinity in practice.
constexpr double kMinNormalSin = 0.01;

/// A circle in the plane perpendicular to the axis, in the basis (e1, e2).
struct Circle {
    Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
    double radius_m = 0.0;
};

/// The cloud seen along the axis. A projected normal is not renormalised: its length is the
/// sine of the normal's angle to the axis, so |m · radial| is the cosine to the radial direction.
struct Projection {
    Eigen::Vector3d axis, e1, e2;
    std::vector<Eigen::Vector2d> points;
    std::vector<Eigen::Vector2d> normals;  ///< empty without normals
};

/// What makes a projected point an inlier of a circle.
struct Criteria {
    double distance_m = 0.0;
    double cos_normal = 0.0;  ///< |n · radial| at least this (normals are unsigned)
    bool use_normals = false;

    bool accepts(const Eigen::Vector2d& q, const Eigen::Vector2d* m, const Circle& c) const {
        const Eigen::Vector2d d = q - c.centre_m;
        const double r = d.norm();
        if (!(std::abs(r - c.radius_m) <= distance_m)) return false;
        return !use_normals || (r > 0.0 && std::abs(m->dot(d)) >= cos_normal * r);
    }
    /// A point whose normal is too close to the axis (a floor) can support no circle.
    bool may_accept(const Eigen::Vector2d* m) const {
        return !use_normals || m->norm() >= cos_normal;
    }
};

/// MSAC cost (Torr & Zisserman 2000): Σ min(r², t²), a point that is no inlier costing t².
/// Counting inliers cannot rank hypotheses on a short arc, where circles a few centimetres
/// apart all cover the same band; the truncated quadratic prefers the one through the points.
struct Score {
    double cost_m2 = 0.0;

    bool better_than(const Score& other) const { return cost_m2 < other.cost_m2; }
};

/// Gauss–Newton normal equations of r_i = |q_i − c| − R over `inliers`.
struct NormalEquations {
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();         ///< JᵀJ
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero();  ///< Jᵀr
    double sum_sq_m2 = 0.0;
};

void check_axis(const Eigen::Vector3d& axis) {
    const double length = axis.stableNorm();
    if (!axis.allFinite() || !(length > 0.0) || !std::isfinite(length)) {
        throw InputError(fmt::format("fit_cylinder: axis ({}, {}, {}) must be finite and non-zero",
                                     axis.x(), axis.y(), axis.z()));
    }
}

Projection project(const PointCloud& cloud, const Eigen::Vector3d& axis) {
    Projection p;
    p.axis = axis / axis.stableNorm();
    p.e1 = p.axis.unitOrthogonal();
    p.e2 = p.axis.cross(p.e1);
    p.points.reserve(cloud.size());
    for (const auto& x : cloud.points) p.points.emplace_back(p.e1.dot(x), p.e2.dot(x));
    p.normals.reserve(cloud.normals.size());
    for (const auto& n : cloud.normals) p.normals.emplace_back(p.e1.dot(n), p.e2.dot(n));
    return p;
}

bool in_bounds(const Circle& c, const CylinderRansacConfig& config) {
    return c.radius_m >= config.min_radius_m && c.radius_m <= config.max_radius_m;
}

/// The circle through three points (relative coordinates keep far-off clouds exact).
std::optional<Circle> through_three(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                    const Eigen::Vector2d& c) {
    const Eigen::Vector2d u = b - a;
    const Eigen::Vector2d v = c - a;
    const double d = 2.0 * (u.x() * v.y() - u.y() * v.x());
    if (!(std::abs(d) > 0.0)) return std::nullopt;
    const Eigen::Vector2d centre(v.y() * u.squaredNorm() - u.y() * v.squaredNorm(),
                                 u.x() * v.squaredNorm() - v.x() * u.squaredNorm());
    const Circle circle{a + centre / d, centre.norm() / std::abs(d)};
    if (!circle.centre_m.allFinite() || !std::isfinite(circle.radius_m)) return std::nullopt;
    return circle;
}

/// The circle centred where the two normal lines meet.
std::optional<Circle> through_two_with_normals(const Eigen::Vector2d& q1, const Eigen::Vector2d& m1,
                                               const Eigen::Vector2d& q2,
                                               const Eigen::Vector2d& m2) {
    Eigen::Matrix2d A;
    A << m1, -m2;
    const double det = A.determinant();
    if (!(std::abs(det) > kMinNormalSin * m1.norm() * m2.norm())) return std::nullopt;
    const Eigen::Vector2d st = A.inverse() * (q2 - q1);
    const Eigen::Vector2d centre = q1 + st.x() * m1;
    return Circle{centre, 0.5 * ((q1 - centre).norm() + (q2 - centre).norm())};
}

/// Positions (into the projection) of the subsample that can support a circle.
std::vector<std::size_t> draw_candidates(const Projection& p, const Criteria& c, Rng& rng) {
    const std::size_t n = p.points.size();
    std::vector<std::size_t> candidates;
    for (const std::size_t i : rng.sample_indices(n, std::min(kScoreSampleSize, n))) {
        if (c.may_accept(c.use_normals ? &p.normals[i] : nullptr)) candidates.push_back(i);
    }
    return candidates;
}

std::optional<Circle> hypothesis(const Projection& p, const std::vector<std::size_t>& candidates,
                                 const Criteria& c, Rng& rng) {
    const auto pick = [&] { return candidates[rng.uniform_index(candidates.size())]; };
    const std::size_t i = pick();
    const std::size_t j = pick();
    if (i == j) return std::nullopt;
    if (c.use_normals) {
        return through_two_with_normals(p.points[i], p.normals[i], p.points[j], p.normals[j]);
    }
    return through_three(p.points[i], p.points[j], p.points[pick()]);
}

Score score(const Projection& p, const std::vector<std::size_t>& candidates, const Circle& circle,
            const Criteria& c) {
    const double outlier_cost_m2 = c.distance_m * c.distance_m;
    Score sc;
    for (const std::size_t i : candidates) {
        if (!c.accepts(p.points[i], c.use_normals ? &p.normals[i] : nullptr, circle)) {
            sc.cost_m2 += outlier_cost_m2;
            continue;
        }
        const double r = (p.points[i] - circle.centre_m).norm() - circle.radius_m;
        sc.cost_m2 += r * r;
    }
    return sc;
}

std::optional<Circle> best_circle(const Projection& p, const CylinderRansacConfig& config,
                                  const Criteria& c, Rng& rng) {
    const std::vector<std::size_t> candidates = draw_candidates(p, c, rng);
    if (candidates.size() < 3) return std::nullopt;
    std::optional<Circle> best;
    Score best_score;
    for (int it = 0; it < config.iterations; ++it) {
        const auto circle = hypothesis(p, candidates, c, rng);
        if (!circle || !in_bounds(*circle, config)) continue;
        const Score sc = score(p, candidates, *circle, c);
        if (!best || sc.better_than(best_score)) {
            best = circle;
            best_score = sc;
        }
    }
    return best;
}

std::vector<std::size_t> collect(const Projection& p, const Circle& circle, const Criteria& c) {
    std::vector<std::size_t> inliers;
    for (std::size_t i = 0; i < p.points.size(); ++i) {
        if (c.accepts(p.points[i], c.use_normals ? &p.normals[i] : nullptr, circle)) {
            inliers.push_back(i);
        }
    }
    return inliers;
}

/// J_i = ∂r_i/∂(c, R) = (−(q_i − c)ᵀ/|q_i − c|, −1); a point on the centre has no gradient.
NormalEquations normal_equations(const Projection& p, const std::vector<std::size_t>& inliers,
                                 const Circle& circle) {
    NormalEquations ne;
    for (const std::size_t i : inliers) {
        const Eigen::Vector2d d = p.points[i] - circle.centre_m;
        const double r = d.norm();
        if (!(r > 0.0)) continue;
        const Eigen::Vector3d J(-d.x() / r, -d.y() / r, -1.0);
        const double residual = r - circle.radius_m;
        ne.H += J * J.transpose();
        ne.gradient += J * residual;
        ne.sum_sq_m2 += residual * residual;
    }
    return ne;
}

/// Geometric least-squares circle (Gauss–Newton on the radial residual) from `circle`.
Circle gauss_newton(const Projection& p, const std::vector<std::size_t>& inliers, Circle circle) {
    for (int step = 0; step < kMaxGaussNewtonSteps; ++step) {
        const NormalEquations ne = normal_equations(p, inliers, circle);
        const Eigen::LDLT<Eigen::Matrix3d> ldlt(ne.H);
        if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0.0)) break;
        const Eigen::Vector3d delta = -ldlt.solve(ne.gradient);
        if (!delta.allFinite()) break;
        circle.centre_m += delta.head<2>();
        circle.radius_m += delta.z();
        if (delta.norm() < kStepToleranceM) break;
    }
    return circle;
}

Cylinder make_cylinder(const Projection& p, const Circle& circle,
                       std::vector<std::size_t> inliers) {
    const NormalEquations ne = normal_equations(p, inliers, circle);
    const double n = static_cast<double>(inliers.size());
    Cylinder cyl;
    cyl.axis = p.axis;
    cyl.centre = circle.centre_m.x() * p.e1 + circle.centre_m.y() * p.e2;
    cyl.radius_m = circle.radius_m;
    cyl.rms_m = std::sqrt(ne.sum_sq_m2 / n);
    // σ² (JᵀJ)⁻¹ with σ² = Σr²/(n − 3): three parameters were fitted.
    const double sigma2 = ne.sum_sq_m2 / std::max(n - 3.0, 1.0);
    cyl.covariance = sigma2 * ne.H.ldlt().solve(Eigen::Matrix3d::Identity());
    cyl.inliers = std::move(inliers);
    return cyl;
}

std::optional<Cylinder> refine(const Projection& p, Circle circle,
                               const CylinderRansacConfig& config, const Criteria& c) {
    std::vector<std::size_t> inliers = collect(p, circle, c);
    for (int round = 0; round < kMaxRefitRounds; ++round) {
        if (inliers.size() < config.min_inliers) return std::nullopt;
        circle = gauss_newton(p, inliers, circle);
        std::vector<std::size_t> recollected = collect(p, circle, c);
        const bool settled = recollected == inliers;
        inliers = std::move(recollected);
        if (settled) break;
    }
    // The refit, not just the hypothesis, must respect the bounds and the support.
    if (inliers.size() < config.min_inliers || !in_bounds(circle, config)) return std::nullopt;
    return make_cylinder(p, circle, std::move(inliers));
}

}  // namespace

void CylinderRansacConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(distance_threshold_m, prefix, "distance_threshold_m");
    require(std::isfinite(normal_threshold_deg) && normal_threshold_deg > 0.0 &&
                normal_threshold_deg <= 90.0,
            prefix, "normal_threshold_deg", normal_threshold_deg, "in (0, 90]");
    require_positive(min_radius_m, prefix, "min_radius_m");
    require(std::isfinite(max_radius_m) && max_radius_m > min_radius_m, prefix, "max_radius_m",
            max_radius_m, fmt::format("finite > min_radius_m ({})", min_radius_m));
    config_checks::require_count_at_least(min_inliers, 3, prefix, "min_inliers");
    require_at_least(iterations, 1, prefix, "iterations");
}

std::optional<Cylinder> fit_cylinder(const PointCloud& cloud, const Eigen::Vector3d& axis,
                                     const CylinderRansacConfig& config) {
    config.validate();
    check_axis(axis);
    check_consistent(cloud, "fit_cylinder");
    check_finite(cloud, "fit_cylinder");
    if (cloud.size() < config.min_inliers) return std::nullopt;  // an empty cloud too
    const Projection p = project(cloud, axis);
    const Criteria criteria{config.distance_threshold_m,
                            std::cos(config.normal_threshold_deg * std::numbers::pi / 180.0),
                            cloud.has_normals()};
    Rng rng(config.seed);
    const auto circle = best_circle(p, config, criteria, rng);
    if (!circle) return std::nullopt;
    return refine(p, *circle, config, criteria);
}

}  // namespace scantling::perception
