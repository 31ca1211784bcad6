#include "consistency_stats.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace scantling::bench {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kYawHitRad = 10 * kDeg;  // "within 10° of the true yaw" (issue 5, item 8)

/// Wilson–Hilferty: χ²_p(k) ≈ k (1 − 2/(9k) + z_p √(2/(9k)))³.
double chi2_quantile(double k, double z_p) {
    const double a = 2.0 / (9.0 * k);
    return k * std::pow(1.0 - a + z_p * std::sqrt(a), 3.0);
}

double mean_of(const std::vector<double>& v) {
    if (v.empty()) return std::nan("");
    return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double median_of(std::vector<double> v) {
    if (v.empty()) return std::nan("");
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

double percent(int part, int whole) { return whole > 0 ? 100.0 * part / whole : 0.0; }

}  // namespace

double nees(const Vector6d& e, const Matrix6d& cov, const std::vector<int>& dofs) {
    const int d = static_cast<int>(dofs.size());
    Eigen::MatrixXd s(d, d);
    Eigen::VectorXd v(d);
    for (int i = 0; i < d; ++i) {
        v[i] = e[dofs[i]];
        for (int j = 0; j < d; ++j) s(i, j) = cov(dofs[i], dofs[j]);
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(s);
    return llt.info() == Eigen::Success ? v.dot(llt.solve(v)) : std::nan("");
}

void NeesStats::add(bool ok, double n, const Eigen::Isometry3d& T_est,
                    const Eigen::Isometry3d& T_true) {
    ++trials;
    if (!ok) return;
    ++accepted;
    const PoseError pe = pose_error(T_est, T_true);
    trans_err_m.push_back(pe.translation_m);
    rot_err_deg.push_back(pe.rotation_rad / kDeg);
    if (std::isfinite(n)) {
        nees.push_back(n);
    } else {
        ++no_covariance;
    }
}

void print_header() {
    fmt::print(
        "| case | d | accepted (no covariance) | NEES n | mean NEES | median NEES | 95 % band "
        "of mean | trials ≤ χ²₀.₉₅(d) | median trans err m | median rot err ° |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n");
}

void print_row(const NeesStats& s) {
    const double n = static_cast<double>(s.nees.size());
    const double k = n * s.dof;
    const double lo = n > 0 ? chi2_quantile(k, -1.959964) / n : std::nan("");
    const double hi = n > 0 ? chi2_quantile(k, 1.959964) / n : std::nan("");
    const double per_trial_95 = chi2_quantile(s.dof, 1.644854);
    const auto inside =
        std::count_if(s.nees.begin(), s.nees.end(), [&](double x) { return x <= per_trial_95; });
    fmt::print(
        "| {} | {} | {}/{} ({}) | {} | {:.3g} | {:.3g} | [{:.2f}, {:.2f}] | {:.0f} % | {:.4f} | "
        "{:.3f} |\n",
        s.label, s.dof, s.accepted, s.trials, s.no_covariance, s.nees.size(), mean_of(s.nees),
        median_of(s.nees), lo, hi, n > 0 ? 100.0 * static_cast<double>(inside) / n : 0.0,
        median_of(s.trans_err_m), median_of(s.rot_err_deg));
}

void YawStats::add(double mode_err_rad, double mean_err_rad, int num_modes) {
    ++trials;
    const bool multi = num_modes > 1;
    multi_modal += multi;
    mode_hits += mode_err_rad < kYawHitRad;
    mean_hits += mean_err_rad < kYawHitRad;
    multi_mode_hits += multi && mode_err_rad < kYawHitRad;
    multi_mean_hits += multi && mean_err_rad < kYawHitRad;
    mode_abs_sum_rad += mode_err_rad;
    mean_abs_sum_rad += mean_err_rad;
    ++num_modes_histogram[static_cast<std::size_t>(std::clamp(num_modes, 1, 6) - 1)];
}

void print_yaw(const YawStats& y) {
    const double n = std::max(1, y.trials);
    fmt::print(
        "\ncolumn yaw, Stein-ICP ({} trials): >= 2 KDE modes in {:.0f} % (modes 1/2/3/4/5/6+: "
        "{}); within 10° of the true yaw: KDE mode {:.0f} %, particle mean {:.0f} %; in the "
        "trials with >= 2 modes ({}): KDE mode {:.0f} %, particle mean {:.0f} %; mean |yaw "
        "error|: KDE mode {:.1f}°, particle mean {:.1f}°\n",
        y.trials, percent(y.multi_modal, y.trials), fmt::join(y.num_modes_histogram, "/"),
        percent(y.mode_hits, y.trials), percent(y.mean_hits, y.trials), y.multi_modal,
        percent(y.multi_mode_hits, y.multi_modal), percent(y.multi_mean_hits, y.multi_modal),
        y.mode_abs_sum_rad / n / kDeg, y.mean_abs_sum_rad / n / kDeg);
}

}  // namespace scantling::bench
