#include <scantling/core/error.hpp>
#include <scantling/registration/stein_icp.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "detail/stein_summary.hpp"

namespace scantling::registration {
namespace {

using detail::difference;

constexpr int kMeanShiftIterations = 50;
constexpr double kShiftTolerance = 1e-4;  // of the bandwidth: far below any mode separation

double circular_mean(std::span<const double> values) {
    double s = 0.0, c = 0.0;
    for (const double v : values) {
        s += std::sin(v);
        c += std::cos(v);
    }
    // Points spread evenly round the circle have no mean direction; any sample will do.
    return std::hypot(s, c) < 1e-9 * static_cast<double>(values.size()) ? values[0]
                                                                        : std::atan2(s, c);
}

double centre_of(std::span<const double> values, bool circular) {
    if (circular) return circular_mean(values);
    double sum = 0.0;
    for (const double v : values) sum += v;
    return sum / static_cast<double>(values.size());
}

/// Silverman's rule with the robust spread min(σ, IQR / 1.34), deviations about `centre`.
double silverman_bandwidth(std::span<const double> values, double centre, bool circular) {
    std::vector<double> d;
    d.reserve(values.size());
    double sq = 0.0;
    for (const double v : values) {
        d.push_back(difference(v, centre, circular));
        sq += d.back() * d.back();
    }
    const double n = static_cast<double>(values.size());
    const double sigma = std::sqrt(sq / n);
    std::sort(d.begin(), d.end());
    const double iqr = d[(d.size() * 3) / 4] - d[d.size() / 4];
    const double spread = iqr > 0.0 ? std::min(sigma, iqr / 1.34) : sigma;
    return 1.06 * spread * std::pow(n, -0.2);
}

/// Unnormalised KDE density at `x` and the mean-shift target.
std::pair<double, double> density_and_shift(std::span<const double> values, double x, double bw,
                                            bool circular) {
    double w_sum = 0.0, shift = 0.0;
    for (const double v : values) {
        const double d = difference(v, x, circular);
        const double w = std::exp(-0.5 * d * d / (bw * bw));
        w_sum += w;
        shift += w * d;
    }
    return {w_sum, w_sum > 0.0 ? shift / w_sum : 0.0};
}

double climb(std::span<const double> values, double x, double bw, bool circular) {
    for (int it = 0; it < kMeanShiftIterations; ++it) {
        const double shift = density_and_shift(values, x, bw, circular).second;
        x = circular ? detail::wrap_angle(x + shift) : x + shift;
        if (std::abs(shift) < kShiftTolerance * bw) break;
    }
    return x;
}

struct Peak {
    double location = 0.0;
    int members = 0;
};

}  // namespace

KdeModes kde_modes(std::span<const double> values, bool circular, double min_fraction) {
    if (values.empty()) throw InputError("kde_modes: no values");
    for (const double v : values) {
        if (!std::isfinite(v)) throw InputError("kde_modes: non-finite value");
    }
    const double centre = centre_of(values, circular);
    const double bw = silverman_bandwidth(values, centre, circular);
    if (!(bw > 1e-12)) return {centre, 1, 0.0};  // all samples (nearly) equal
    std::vector<Peak> peaks;
    for (const double v : values) {
        const double top = climb(values, v, bw, circular);
        auto it = std::find_if(peaks.begin(), peaks.end(), [&](const Peak& p) {
            return std::abs(difference(p.location, top, circular)) < bw;
        });
        if (it == peaks.end()) it = peaks.insert(peaks.end(), Peak{top, 0});
        ++it->members;
    }
    KdeModes out{peaks[0].location, 0, bw};
    double best = -1.0;
    for (const Peak& p : peaks) {
        if (p.members >= min_fraction * static_cast<double>(values.size())) ++out.num_modes;
        const double density = density_and_shift(values, p.location, bw, circular).first;
        if (density > best) {
            best = density;
            out.mode = p.location;
        }
    }
    return out;
}

Vector6d pose_params_from_isometry(const Eigen::Isometry3d& T) {
    const Eigen::Vector3d rpy = euler_zyx_from_rotation(T.linear());
    Vector6d params;
    params << T.translation(), rpy;
    return params;
}

Eigen::Isometry3d isometry_from_pose_params(const Vector6d& params) {
    return make_isometry(rotation_from_euler_zyx(params[3], params[4], params[5]),
                         params.head<3>());
}

namespace detail {

double wrap_angle(double angle_rad) { return std::remainder(angle_rad, 2.0 * std::numbers::pi); }

void summarize_particles(SteinIcpResult& result, std::span<const int> free_dofs,
                         double min_mode_fraction) {
    const auto& particles = result.particles;
    const std::size_t k = particles.size();
    result.mean = particles[0];
    result.mode = particles[0];
    result.num_modes = 1;
    std::vector<double> values(k);
    for (const int dof : free_dofs) {
        for (std::size_t i = 0; i < k; ++i) values[i] = particles[i][dof];
        result.mean[dof] = centre_of(values, is_angle(dof));
        const KdeModes m = kde_modes(values, is_angle(dof), min_mode_fraction);
        result.mode[dof] = m.mode;
        result.num_modes = std::max(result.num_modes, m.num_modes);
    }
    result.covariance.setZero();
    for (const Vector6d& x : particles) {
        Vector6d d = Vector6d::Zero();
        for (const int dof : free_dofs)
            d[dof] = difference(x[dof], result.mean[dof], is_angle(dof));
        result.covariance += d * d.transpose();
    }
    result.covariance /= static_cast<double>(std::max<std::size_t>(k - 1, 1));
    result.T_target_source = isometry_from_pose_params(result.mode);
}

}  // namespace detail
}  // namespace scantling::registration
