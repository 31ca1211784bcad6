#include <scantling/safety/collision_prevention.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

#include "detail/prevent_collision_on.hpp"

namespace scantling::safety {
namespace {

// Below this |z × f| the velocity is vertical and "horizontal" needs another reference.
constexpr double kVerticalTolerance = 1e-9;

void require_half_angle(double deg, std::string_view prefix, std::string_view field) {
    config_checks::require(std::isfinite(deg) && deg > 0.0 && deg < 90.0, prefix, field, deg,
                           "in (0, 90) degrees");
}

/// Running totals of the one pass over a sweep.
struct SweepScan {
    double d2_o_m2 = std::numeric_limits<double>::infinity();  // nearest frustum point, squared
    Eigen::Vector3d rep_sum_mps = Eigen::Vector3d::Zero();
    std::size_t valid = 0;
    std::size_t in_frustum = 0;
    std::size_t repelling = 0;
};

/// The repulsion of one point closer than d_min (SPEC §3: away from p, K (d_min − d_p)).
void add_repulsion(const Eigen::Vector3d& p, double d2, const CollisionPreventionConfig& config,
                   SweepScan& scan) {
    const double d = std::sqrt(d2);
    scan.rep_sum_mps -= p * (config.repulsion_gain_per_s * (config.d_min_m - d) / d);
    ++scan.repelling;
}

/// Squared distances throughout, so that only the few repelling points pay a sqrt.
template <bool kHasFrustum>
SweepScan scan_sweep(std::span<const Eigen::Vector3d> points, const Frustum& frustum,
                     const CollisionPreventionConfig& config) {
    SweepScan scan;
    const double d_min2 = config.d_min_m * config.d_min_m;
    for (const Eigen::Vector3d& p : points) {
        const double d2 = p.squaredNorm();
        // A non-finite coordinate (a no-return) makes d2 non-finite; the origin has no direction.
        if (!std::isfinite(d2) || d2 == 0.0) continue;
        ++scan.valid;
        if (d2 < d_min2) add_repulsion(p, d2, config, scan);
        if constexpr (kHasFrustum) {
            if (frustum.contains(p)) {
                scan.d2_o_m2 = std::min(scan.d2_o_m2, d2);
                ++scan.in_frustum;
            }
        }
    }
    return scan;
}

/// vel_rep: the mean of the repulsions, its magnitude clamped to v_max.
Eigen::Vector3d mean_repulsion(const SweepScan& scan, const CollisionPreventionConfig& config,
                               bool& clamped) {
    clamped = false;
    if (scan.repelling == 0) return Eigen::Vector3d::Zero();
    Eigen::Vector3d v_rep = scan.rep_sum_mps / static_cast<double>(scan.repelling);
    const double speed = v_rep.norm();
    if (speed > config.max_speed_mps) {
        v_rep *= config.max_speed_mps / speed;
        clamped = true;
    }
    return v_rep;
}

AttenuationStatus status_of(const CollisionPreventionResult& result) {
    if (result.num_valid_points == 0) return AttenuationStatus::kNoData;
    if (result.lambda >= 1.0) return AttenuationStatus::kClear;
    return result.lambda > 0.0 ? AttenuationStatus::kAttenuated : AttenuationStatus::kStopped;
}

}  // namespace

void CollisionPreventionConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_non_negative(robot_radius_m, prefix, "robot_radius_m");
    require(std::isfinite(d_min_m) && d_min_m > robot_radius_m, prefix, "d_min_m", d_min_m,
            fmt::format("finite > robot_radius_m = {}", robot_radius_m));
    require(std::isfinite(d_att_m) && d_att_m > d_min_m, prefix, "d_att_m", d_att_m,
            fmt::format("finite > d_min_m = {}", d_min_m));
    require_positive(repulsion_gain_per_s, prefix, "repulsion_gain_per_s");
    require_positive(max_speed_mps, prefix, "max_speed_mps");
    require_half_angle(half_fov_horizontal_deg, prefix, "half_fov_horizontal_deg");
    require_half_angle(half_fov_vertical_deg, prefix, "half_fov_vertical_deg");
}

double attenuation_factor(std::optional<double> d_o_m, const CollisionPreventionConfig& config) {
    if (!d_o_m) return 1.0;
    return std::clamp((*d_o_m - config.d_min_m) / (config.d_att_m - config.d_min_m), 0.0, 1.0);
}

std::optional<Frustum> make_frustum(const Eigen::Vector3d& v_desired_body_mps,
                                    const CollisionPreventionConfig& config) {
    const double speed_mps = v_desired_body_mps.norm();
    if (!(speed_mps > 0.0)) return std::nullopt;
    Frustum frustum;
    frustum.axis_f = v_desired_body_mps / speed_mps;
    const Eigen::Vector3d h = Eigen::Vector3d::UnitZ().cross(frustum.axis_f);
    // Climbing or descending straight: body y keeps the pyramid square to the body.
    frustum.horizontal_h =
        h.norm() > kVerticalTolerance ? h.normalized() : Eigen::Vector3d::UnitY();
    frustum.vertical_u = frustum.axis_f.cross(frustum.horizontal_h);
    frustum.near_m = config.robot_radius_m;
    frustum.far_m = config.d_att_m;
    frustum.tan_half_h = detail::tan_deg(config.half_fov_horizontal_deg);
    frustum.tan_half_v = detail::tan_deg(config.half_fov_vertical_deg);
    return frustum;
}

namespace detail {

CollisionPreventionResult prevent_collision_on(const Eigen::Vector3d& v_desired_body_mps,
                                               std::span<const Eigen::Vector3d> points_body,
                                               const CollisionPreventionConfig& config,
                                               std::optional<std::size_t> num_valid_points) {
    config.validate();
    if (!v_desired_body_mps.allFinite()) {
        throw InputError(
            fmt::format("prevent_collision: desired velocity ({}, {}, {}) m/s is not "
                        "finite",
                        v_desired_body_mps.x(), v_desired_body_mps.y(), v_desired_body_mps.z()));
    }
    const auto frustum = make_frustum(v_desired_body_mps, config);
    const SweepScan scan = frustum ? scan_sweep<true>(points_body, *frustum, config)
                                   : scan_sweep<false>(points_body, Frustum{}, config);
    CollisionPreventionResult result;
    result.num_valid_points = num_valid_points.value_or(scan.valid);
    result.num_frustum_points = scan.in_frustum;
    result.num_points_within_d_min = scan.repelling;
    if (scan.in_frustum > 0) result.d_o_m = std::sqrt(scan.d2_o_m2);
    result.lambda = attenuation_factor(result.d_o_m, config);
    result.v_att_body_mps = result.lambda * v_desired_body_mps;
    result.v_rep_body_mps = mean_repulsion(scan, config, result.repulsion_clamped);
    result.v_cmd_body_mps = result.v_att_body_mps + result.v_rep_body_mps;
    result.status = status_of(result);
    return result;
}

}  // namespace detail

CollisionPreventionResult prevent_collision(const Eigen::Vector3d& v_desired_body_mps,
                                            const PointCloud& cloud_body,
                                            const CollisionPreventionConfig& config) {
    return detail::prevent_collision_on(v_desired_body_mps, cloud_body.points, config,
                                        std::nullopt);
}

std::string_view to_string(AttenuationStatus status) {
    switch (status) {
        case AttenuationStatus::kNoData:
            return "no data";
        case AttenuationStatus::kClear:
            return "clear";
        case AttenuationStatus::kAttenuated:
            return "attenuated";
        case AttenuationStatus::kStopped:
            return "stopped";
    }
    return "unknown";
}

std::string describe(const CollisionPreventionResult& result,
                     const CollisionPreventionConfig& config) {
    std::string line = std::string(to_string(result.status));
    if (result.status == AttenuationStatus::kNoData) line += ": no usable point, command unchanged";
    if (result.status == AttenuationStatus::kClear) {
        line += fmt::format(": no frustum point closer than d_att = {:.2f} m", config.d_att_m);
    }
    if (result.d_o_m && result.lambda < 1.0) {
        line += fmt::format(": d_o = {:.2f} m, lambda = {:.2f}", *result.d_o_m, result.lambda);
    }
    if (result.num_points_within_d_min > 0) {
        line += fmt::format(
            "; repelled by {} points closer than d_min = {:.2f} m (|v_rep| = "
            "{:.2f} m/s{})",
            result.num_points_within_d_min, config.d_min_m, result.v_rep_body_mps.norm(),
            result.repulsion_clamped ? ", clamped" : "");
    }
    return line;
}

}  // namespace scantling::safety
