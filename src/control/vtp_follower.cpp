#include <scantling/control/vtp_follower.hpp>

#include <cmath>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::control {
namespace {

// Shorter segments have no usable direction: treated as WP_prev = WP (case 5).
constexpr double kMinSegmentLengthM = 1e-6;

void require_finite(const Eigen::Vector3d& v, std::string_view what) {
    if (!v.allFinite()) {
        throw InputError(fmt::format("virtual_target_point: {} = ({}, {}, {}), expected finite",
                                     what, v.x(), v.y(), v.z()));
    }
}

/// Cases 1 and 2 (and 4, which behaves as them): ahead along the path, or back onto it.
Eigen::Vector3d approach_point(const Eigen::Vector3d& c, const Eigen::Vector3d& wp,
                               const Eigen::Vector3d& direction, double d_m,
                               const VtpConfig& config) {
    if (d_m >= config.max_path_separation_m) return c;
    const double lead_m = config.max_vtp_distance_m * (1.0 - d_m / config.max_path_separation_m);
    return lead_m > (wp - c).norm() ? wp : Eigen::Vector3d(c + lead_m * direction);
}

/// SPEC §4's case from t (C's position along WP_prev → WP), |C − WP_prev| and d.
VtpCase classify(double t, double c_from_prev_m, double d_m, double waypoint_tolerance_m,
                 const VtpConfig& config) {
    if (t > 1.0) return VtpCase::kBeyondWaypoint;
    if (t < 0.0) {
        return c_from_prev_m > waypoint_tolerance_m ? VtpCase::kBeforeStart : VtpCase::kNearStart;
    }
    return d_m < config.max_path_separation_m ? VtpCase::kOnPath : VtpCase::kOffPath;
}

}  // namespace

void VtpConfig::validate(std::string_view prefix) const {
    config_checks::require_positive(max_vtp_distance_m, prefix, "max_vtp_distance_m");
    config_checks::require_positive(max_path_separation_m, prefix, "max_path_separation_m");
}

VtpResult virtual_target_point(const Eigen::Vector3d& p_world_m,
                               const Eigen::Vector3d& wp_prev_world_m,
                               const Eigen::Vector3d& wp_world_m, double waypoint_tolerance_m,
                               const VtpConfig& config) {
    config.validate();
    require_finite(p_world_m, "p_world_m");
    require_finite(wp_prev_world_m, "wp_prev_world_m");
    require_finite(wp_world_m, "wp_world_m");
    config_checks::require_positive(waypoint_tolerance_m, "virtual_target_point",
                                    "waypoint_tolerance_m");
    const Eigen::Vector3d segment = wp_world_m - wp_prev_world_m;
    const double length_m = segment.norm();
    if (length_m < kMinSegmentLengthM) {
        return {wp_world_m, wp_world_m, (p_world_m - wp_world_m).norm(), 0.0,
                VtpCase::kBeyondWaypoint};
    }
    const Eigen::Vector3d direction = segment / length_m;
    const double t = (p_world_m - wp_prev_world_m).dot(direction) / length_m;
    const Eigen::Vector3d c = wp_prev_world_m + t * segment;
    const double d_m = (p_world_m - c).norm();
    const VtpCase vtp_case =
        classify(t, (c - wp_prev_world_m).norm(), d_m, waypoint_tolerance_m, config);
    if (vtp_case == VtpCase::kBeyondWaypoint) return {wp_world_m, c, d_m, t, vtp_case};
    if (vtp_case == VtpCase::kBeforeStart) return {wp_prev_world_m, c, d_m, t, vtp_case};
    return {approach_point(c, wp_world_m, direction, d_m, config), c, d_m, t, vtp_case};
}

std::string_view to_string(VtpCase vtp_case) {
    switch (vtp_case) {
        case VtpCase::kOnPath:
            return "1: on the path, VTP ahead";
        case VtpCase::kOffPath:
            return "2: off the path, VTP = C";
        case VtpCase::kBeforeStart:
            return "3: before WP_prev, VTP = WP_prev";
        case VtpCase::kNearStart:
            return "4: before WP_prev within WP_tol";
        case VtpCase::kBeyondWaypoint:
            return "5: beyond WP, VTP = WP";
    }
    return "unknown";
}

}  // namespace scantling::control
