#include "scantling/localize_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include <scantling/core/se3.hpp>

namespace scantling::app {
namespace {

namespace loc = localization;

/// Wilson–Hilferty approximation of the χ²(k) quantile (accurate to <1 % for k >= 6).
double chi2_quantile(double k, double z) {
    const double a = 2.0 / (9.0 * k);
    return k * std::pow(1.0 - a + z * std::sqrt(a), 3);
}

nlohmann::ordered_json to_json(const ErrorStats& s) {
    return {{"count", s.count}, {"mean", s.mean}, {"std", s.std}, {"p95", s.p95}, {"max", s.max}};
}

double yaw_error_deg(const Eigen::Isometry3d& truth, const Eigen::Isometry3d& estimate) {
    const Eigen::Vector3d a = truth.linear() * Eigen::Vector3d::UnitX();
    const Eigen::Vector3d b = estimate.linear() * Eigen::Vector3d::UnitX();
    return std::abs(std::remainder(std::atan2(a.y(), a.x()) - std::atan2(b.y(), b.x()), 2 * M_PI)) *
           180.0 / M_PI;
}

void count_events(const LocalizeRun& run, LocalizeMetrics& m, const GroundTruth& truth) {
    std::vector<double> accepted, all, tracking, relocalization;
    double first_frame = -1.0;
    for (const loc::FrameEvent& e : run.events) {
        if (first_frame < 0) first_frame = e.stamp_s;
        const bool ok = e.outcome == loc::FrameOutcome::kRegistered ||
                        e.outcome == loc::FrameOutcome::kRelocalized;
        ++m.outcomes[ok ? std::string(loc::to_string(e.outcome))
                        : fmt::format("{}:{}", loc::to_string(e.outcome), e.gate)];
        if (ok && m.first_fix_s < 0) m.first_fix_s = e.stamp_s - first_frame;
        if (e.mode == loc::LocalizerMode::kTracking) tracking.push_back(e.compute_ms);
        if (e.mode == loc::LocalizerMode::kRelocalization) relocalization.push_back(e.compute_ms);
        if (!e.T_world_body) continue;
        const double error =
            (e.T_world_body->translation() - truth.at(e.stamp_s).translation()).norm();
        all.push_back(error);
        if (ok) accepted.push_back(error);
    }
    m.accepted_registration_m = error_stats(accepted);
    m.all_registrations_m = error_stats(all);
    m.tracking_ms = error_stats(tracking);
    m.relocalization_ms = error_stats(relocalization);
}

}  // namespace

ErrorStats error_stats(std::vector<double> values) {
    ErrorStats s;
    s.count = values.size();
    if (values.empty()) return s;
    std::sort(values.begin(), values.end());
    double sum = 0.0, sum2 = 0.0;
    for (double v : values) {
        sum += v;
        sum2 += v * v;
    }
    s.mean = sum / static_cast<double>(values.size());
    s.std = std::sqrt(std::max(sum2 / static_cast<double>(values.size()) - s.mean * s.mean, 0.0));
    s.p95 = values[std::min(values.size() - 1,
                            static_cast<std::size_t>(std::ceil(0.95 * values.size())) - 1)];
    s.max = values.back();
    return s;
}

Eigen::Isometry3d GroundTruth::at(double stamp_s) const {
    const auto it =
        std::lower_bound(poses_.begin(), poses_.end(), stamp_s,
                         [](const io::StampedPose& p, double t) { return p.stamp_s < t; });
    if (it == poses_.begin()) return poses_.front().T_world_body;
    if (it == poses_.end()) return poses_.back().T_world_body;
    const auto& a = *(it - 1);
    const auto& b = *it;
    return interpolate(a.T_world_body, b.T_world_body,
                       (stamp_s - a.stamp_s) / (b.stamp_s - a.stamp_s));
}

LocalizeMetrics measure(const LocalizeRun& run, const GroundTruth& truth) {
    LocalizeMetrics m;
    std::vector<double> fused, yaw, vio;
    double nees_sum = 0.0, next_nees_s = -INFINITY;
    for (const loc::FusedState& s : run.fused) {
        const Eigen::Isometry3d T = truth.at(s.stamp_s);
        fused.push_back((s.T_world_body.translation() - T.translation()).norm());
        yaw.push_back(yaw_error_deg(T, s.T_world_body));
        if (s.stamp_s >= next_nees_s) {
            const Vector6d e = loc::position_attitude_error(T, s.T_world_body);
            nees_sum += e.dot(s.covariance.ldlt().solve(e));
            ++m.nees_samples;
            next_nees_s = s.stamp_s + 1.0;
        }
    }
    for (const io::StampedPose& p : run.vio_alone) {
        vio.push_back((p.T_world_body.translation() - truth.at(p.stamp_s).translation()).norm());
    }
    m.fused_m = error_stats(fused);
    m.fused_yaw_deg = error_stats(yaw);
    m.vio_m = error_stats(vio);
    if (m.nees_samples > 0) {
        const double n = static_cast<double>(m.nees_samples);
        m.nees_mean = nees_sum / n;
        m.nees_low = chi2_quantile(6.0 * n, -1.959964) / n;
        m.nees_high = chi2_quantile(6.0 * n, 1.959964) / n;
    }
    count_events(run, m, truth);
    return m;
}

void write_events_csv(std::ostream& out, const LocalizeRun& run, const GroundTruth& truth) {
    out << "stamp_s,kind,index,outcome,mode,gate,compartment,points,overlap,mahalanobis_sq,"
           "landmarks_seen,landmarks_matched,x,y,z,yaw_deg,error_m,compute_ms,message\n";
    std::size_t w = 0;
    auto clean = [](std::string s) {
        std::replace(s.begin(), s.end(), ',', ';');
        std::replace(s.begin(), s.end(), '\n', ' ');
        return s;
    };
    auto flush_warnings = [&](double until) {
        for (; w < run.warnings.size() && run.warnings[w].stamp_s <= until; ++w) {
            const auto& x = run.warnings[w];
            out << fmt::format("{:.6f},warning,,,,{},,,,,,,,,,,,,{}\n", x.stamp_s, x.source,
                               clean(x.message));
        }
    };
    for (const loc::FrameEvent& e : run.events) {
        flush_warnings(e.stamp_s);
        std::string pose = ",,,,";
        if (e.T_world_body) {
            const Eigen::Vector3d p = e.T_world_body->translation();
            const Eigen::Vector3d x = e.T_world_body->linear() * Eigen::Vector3d::UnitX();
            pose = fmt::format("{:.4f},{:.4f},{:.4f},{:.3f},{:.4f}", p.x(), p.y(), p.z(),
                               std::atan2(x.y(), x.x()) * 180.0 / M_PI,
                               (p - truth.at(e.stamp_s).translation()).norm());
        }
        out << fmt::format("{:.6f},frame,{},{},{},{},{},{},{:.4f},{:.3f},{},{},{},{:.2f},{}\n",
                           e.stamp_s, e.index, loc::to_string(e.outcome), loc::to_string(e.mode),
                           e.gate, e.compartment, e.num_points, e.overlap, e.mahalanobis_squared,
                           e.landmarks_seen, e.landmarks_matched, pose, e.compute_ms,
                           clean(e.reason));
    }
    flush_warnings(INFINITY);
}

std::string summary_json(const LocalizeMetrics& m, const LocalizeRun& run,
                         const std::map<std::string, std::string>& settings) {
    nlohmann::ordered_json j;
    j["settings"] = settings;
    j["fused_error_m"] = to_json(m.fused_m);
    j["fused_yaw_error_deg"] = to_json(m.fused_yaw_deg);
    j["vio_alone_error_m"] = to_json(m.vio_m);
    j["accepted_registration_error_m"] = to_json(m.accepted_registration_m);
    j["all_registrations_error_m"] = to_json(m.all_registrations_m);
    j["nees"] = {{"mean", m.nees_mean},
                 {"samples", m.nees_samples},
                 {"band_95", {m.nees_low, m.nees_high}},
                 {"dimension", 6}};
    j["frames"] = m.outcomes;
    j["warnings"] = run.warnings.size();
    j["first_fix_s"] = m.first_fix_s;
    j["tracking_ms"] = to_json(m.tracking_ms);
    j["relocalization_ms"] = to_json(m.relocalization_ms);
    j["duration_s"] = run.duration_s;
    j["wall_s"] = run.wall_s;
    j["real_time_factor"] = run.wall_s > 0 ? run.duration_s / run.wall_s : 0.0;
    return j.dump(2) + "\n";
}

void print_summary(std::ostream& out, const LocalizeMetrics& m, const LocalizeRun& run) {
    auto line = [&](std::string_view name, const ErrorStats& s, std::string_view unit) {
        out << fmt::format("{:<30} mean {:.4f} std {:.4f} p95 {:.4f} max {:.4f} {} (n = {})\n",
                           name, s.mean, s.std, s.p95, s.max, unit, s.count);
    };
    line("fused position error", m.fused_m, "m");
    line("fused yaw error", m.fused_yaw_deg, "deg");
    line("VIO alone position error", m.vio_m, "m");
    line("accepted registrations error", m.accepted_registration_m, "m");
    line("all registrations error", m.all_registrations_m, "m");
    out << fmt::format(
        "NEES (6-DoF, 1 Hz): mean {:.2f}, 95 % band of the mean [{:.2f}, {:.2f}], "
        "{} samples\n",
        m.nees_mean, m.nees_low, m.nees_high, m.nees_samples);
    out << "frames:";
    for (const auto& [name, count] : m.outcomes) out << fmt::format(" {} {}", name, count);
    out << fmt::format("\nwarnings: {}\n", run.warnings.size());
    line("tracking time", m.tracking_ms, "ms");
    line("re-localisation time", m.relocalization_ms, "ms");
    out << fmt::format(
        "first fix after {:.2f} s; {:.1f} s of data in {:.1f} s ({:.1f}x real time)\n",
        m.first_fix_s, run.duration_s, run.wall_s,
        run.wall_s > 0 ? run.duration_s / run.wall_s : 0.0);
}

}  // namespace scantling::app
