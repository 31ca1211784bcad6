#include "tls_estimators.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "rigid_fit.hpp"

namespace scantling::registration::detail {
namespace {

std::vector<double> squared_residuals(std::span<const Eigen::Vector3d> source,
                                      std::span<const Eigen::Vector3d> target,
                                      const Eigen::Matrix3d& R) {
    std::vector<double> r2(source.size());
    for (std::size_t k = 0; k < source.size(); ++k)
        r2[k] = (target[k] - R * source[k]).squaredNorm();
    return r2;
}

/// Closed-form TLS weights of the GNC surrogate at μ; returns the cost with the old weights.
double update_weights(const std::vector<double>& r2, double bound2, double mu,
                      std::vector<double>& weights) {
    const double upper = (mu + 1.0) / mu * bound2;
    const double lower = mu / (mu + 1.0) * bound2;
    double cost = 0.0;
    for (std::size_t k = 0; k < r2.size(); ++k) {
        cost += weights[k] * r2[k];
        if (r2[k] >= upper) {
            weights[k] = 0.0;
        } else if (r2[k] <= lower) {
            weights[k] = 1.0;
        } else {
            weights[k] = std::sqrt(bound2 * mu * (mu + 1.0) / r2[k]) - mu;
        }
    }
    return cost;
}

/// An interval end of the voting sweeps: `enter` ends sort before `exit` ends at equal
/// positions, so closed intervals that touch overlap.
struct SweepEvent {
    double position;
    bool enter;
    std::size_t index;
};

void sort_events(std::vector<SweepEvent>& events) {
    std::sort(events.begin(), events.end(), [](const SweepEvent& a, const SweepEvent& b) {
        if (a.position != b.position) return a.position < b.position;
        if (a.enter != b.enter) return a.enter;
        return a.index < b.index;
    });
}

/// Running sums of a yaw consensus set: Σ a_k, Σ ρ_k e^{iφ_k}, count.
struct YawSums {
    double a = 0.0;
    double c = 0.0;
    double s = 0.0;
    double count = 0.0;

    void add(double sign, double ak, double rho, double phi) {
        a += sign * ak;
        c += sign * rho * std::cos(phi);
        s += sign * rho * std::sin(phi);
        count += sign;
    }
};

/// Where each measurement fits as a function of the yaw θ: |t − R_z(θ) s|² = a − 2 ρ cos(θ − φ)
/// is within bound² on the arc |θ − φ| <= acos((a − bound²) / 2ρ). Arc ends become sweep events
/// over (−π, π]; measurements that fit at every yaw, or on an arc through ±π (present at the
/// sweep's start), start in `always`.
struct YawArcs {
    std::vector<double> a, rho, phi;
    std::vector<SweepEvent> events;
    YawSums always;
};

YawArcs yaw_arcs(std::span<const Eigen::Vector3d> source, std::span<const Eigen::Vector3d> target,
                 double bound) {
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    const double bound2 = bound * bound;
    YawArcs arcs;
    for (std::size_t k = 0; k < source.size(); ++k) {
        const Eigen::Vector3d& s = source[k];
        const Eigen::Vector3d& t = target[k];
        const double a = t.squaredNorm() + s.squaredNorm() - 2.0 * t.z() * s.z();
        const double rho = t.head<2>().norm() * s.head<2>().norm();
        const double phi = std::atan2(t.y(), t.x()) - std::atan2(s.y(), s.x());
        arcs.a.push_back(a);
        arcs.rho.push_back(rho);
        arcs.phi.push_back(phi);
        const double c = rho > 0.0 ? (a - bound2) / (2.0 * rho) : (a <= bound2 ? -1.0 : 2.0);
        if (c > 1.0) continue;  // never fits
        if (c <= -1.0) {        // fits at every yaw
            arcs.always.add(1.0, a, rho, phi);
            continue;
        }
        const double lo = std::remainder(phi - std::acos(c), kTwoPi);
        const double hi = std::remainder(phi + std::acos(c), kTwoPi);
        if (lo > hi) arcs.always.add(1.0, a, rho, phi);  // the arc wraps through ±π
        arcs.events.push_back({lo, true, k});
        arcs.events.push_back({hi, false, k});
    }
    sort_events(arcs.events);
    return arcs;
}

}  // namespace

RotationEstimate gnc_tls_rotation(std::span<const Eigen::Vector3d> source,
                                  std::span<const Eigen::Vector3d> target,
                                  const GncSettings& settings) {
    RotationEstimate est;
    const double bound2 = settings.noise_bound * settings.noise_bound;
    std::vector<double> weights(source.size(), 1.0);
    double mu = 1.0;
    double previous_cost = std::numeric_limits<double>::infinity();
    for (int i = 0; i < settings.max_iterations; ++i) {
        est.R = fit_rotation(source, target, weights);
        est.iterations = i + 1;
        const auto r2 = squared_residuals(source, target, est.R);
        if (i == 0) {
            // TEASER++'s initial μ makes the surrogate convex over the largest residual; μ <= 0
            // means every residual is already within the bound: the first fit is the answer.
            mu = 1.0 / (2.0 * *std::max_element(r2.begin(), r2.end()) / bound2 - 1.0);
            if (mu <= 0.0) break;
        }
        const double cost = update_weights(r2, bound2, mu, weights);
        mu *= settings.factor;
        if (std::abs(cost - std::exchange(previous_cost, cost)) < settings.cost_threshold) break;
    }
    est.inliers.resize(weights.size());
    for (std::size_t k = 0; k < weights.size(); ++k) est.inliers[k] = weights[k] > 0.0 ? 1 : 0;
    return est;
}

double scalar_tls(std::span<const double> values, double bound) {
    const double ref = values[values.size() / 2];  // shift for accurate running sums
    std::vector<SweepEvent> events;
    for (std::size_t k = 0; k < values.size(); ++k) {
        events.push_back({values[k] - bound, true, k});
        events.push_back({values[k] + bound, false, k});
    }
    sort_events(events);
    const double n = static_cast<double>(values.size());
    double sum = 0.0, sum_sq = 0.0, count = 0.0;
    double best_cost = std::numeric_limits<double>::infinity();
    double best = values[0];
    for (const SweepEvent& e : events) {
        const double x = values[e.index] - ref;
        const double sign = e.enter ? 1.0 : -1.0;
        sum += sign * x;
        sum_sq += sign * x * x;
        count += sign;
        if (count < 0.5) continue;
        const double mean = sum / count;
        // Σ_S (x − mean)² / c² + |not S| bounds the TLS cost at `mean` from above and equals
        // the TLS minimum for the best S, so minimising it over the sweep's sets is exact.
        const double cost =
            std::max(sum_sq - count * mean * mean, 0.0) / (bound * bound) + n - count;
        if (cost < best_cost) {
            best_cost = cost;
            best = mean + ref;
        }
    }
    return best;
}

double yaw_tls(std::span<const Eigen::Vector3d> source, std::span<const Eigen::Vector3d> target,
               double bound) {
    const YawArcs arcs = yaw_arcs(source, target, bound);
    YawSums sums = arcs.always;
    const double n = static_cast<double>(source.size());
    double best_cost = std::numeric_limits<double>::infinity();
    double best = 0.0;
    auto consider = [&]() {
        // Σ_S |t − R s|² at the set's best yaw is Σ a − 2 |Σ ρ e^{iφ}|; as in scalar_tls this
        // surrogate is exact at the optimum.
        const double norm = std::hypot(sums.c, sums.s);
        const double cost = std::max(sums.a - 2.0 * norm, 0.0) / (bound * bound) + n - sums.count;
        if (cost < best_cost) {
            best_cost = cost;
            best = norm > 0.0 ? std::atan2(sums.s, sums.c) : 0.0;
        }
    };
    consider();
    for (const SweepEvent& e : arcs.events) {
        const std::size_t k = e.index;
        sums.add(e.enter ? 1.0 : -1.0, arcs.a[k], arcs.rho[k], arcs.phi[k]);
        consider();
    }
    return best;
}

}  // namespace scantling::registration::detail
