#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/quality.hpp>

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "detail/config_checks.hpp"

namespace scantling::registration {
namespace {

using detail::require_positive;

constexpr std::size_t kGrain = 512;  // points per reduction chunk, fixed for determinism

struct Sums {
    std::size_t count = 0;
    double distance_sq_m2 = 0.0;
};

double wrap_angle(double angle_rad) { return std::remainder(angle_rad, 2.0 * std::numbers::pi); }

GateResult pass() { return {true, ""}; }

}  // namespace

CorrespondenceQuality evaluate_correspondences(const PointCloud& source_in_target,
                                               const KdTree& target_tree, double max_distance_m,
                                               const ParallelConfig& parallel) {
    require_positive(max_distance_m, "quality", "max_distance_m");
    check_consistent(source_in_target, "quality source");
    check_finite(source_in_target, "quality source");
    const double max_sq = max_distance_m * max_distance_m;
    const Sums sums = parallel_reduce_ordered(
        parallel, source_in_target.size(), kGrain, Sums{},
        [&](std::size_t begin, std::size_t end) {
            Sums s;
            for (std::size_t i = begin; i < end; ++i) {
                const auto nn = target_tree.nearest(source_in_target.points[i]);
                if (!nn || nn->distance_sq_m2 > max_sq) continue;
                ++s.count;
                s.distance_sq_m2 += nn->distance_sq_m2;
            }
            return s;
        },
        [](Sums a, const Sums& b) {
            return Sums{a.count + b.count, a.distance_sq_m2 + b.distance_sq_m2};
        });
    CorrespondenceQuality q;
    q.num_inliers = sums.count;
    if (source_in_target.empty() || sums.count == 0) return q;
    q.fitness = static_cast<double>(sums.count) / static_cast<double>(source_in_target.size());
    q.rmse_m = std::sqrt(sums.distance_sq_m2 / static_cast<double>(sums.count));
    return q;
}

double overlap_ratio(const PointCloud& source_in_target, const KdTree& target_tree, double voxel_m,
                     const ParallelConfig& parallel) {
    return evaluate_correspondences(source_in_target, target_tree, voxel_m, parallel).fitness;
}

double rmse(const PointCloud& source_in_target, const KdTree& target_tree, double max_distance_m,
            const ParallelConfig& parallel) {
    return evaluate_correspondences(source_in_target, target_tree, max_distance_m, parallel).rmse_m;
}

void AttitudeGateConfig::validate(std::string_view prefix) const {
    require_positive(max_difference_rad, prefix, "max_difference_rad");
}

void SpeedGateConfig::validate(std::string_view prefix) const {
    require_positive(max_speed_mps, prefix, "max_speed_mps");
}

void OverlapGateConfig::validate(std::string_view prefix) const {
    if (!(min_overlap > 0.0 && min_overlap <= 1.0)) {
        throw ConfigError(
            fmt::format("{}.min_overlap = {}, expected in (0, 1]", prefix, min_overlap));
    }
    require_positive(voxel_size_m, prefix, "voxel_size_m");
}

GateResult check_attitude(const Eigen::Matrix3d& R_world_body_registration,
                          const Eigen::Matrix3d& R_world_body_imu,
                          const AttitudeGateConfig& config) {
    config.validate();
    if (!R_world_body_registration.allFinite() || !R_world_body_imu.allFinite()) {
        throw InputError("attitude_gate: a rotation is not finite");
    }
    const Eigen::Vector3d reg = euler_zyx_from_rotation(R_world_body_registration);
    const Eigen::Vector3d imu = euler_zyx_from_rotation(R_world_body_imu);
    const double roll_diff = std::abs(wrap_angle(reg(0) - imu(0)));
    const double pitch_diff = std::abs(wrap_angle(reg(1) - imu(1)));
    if (roll_diff <= config.max_difference_rad && pitch_diff <= config.max_difference_rad) {
        return pass();
    }
    return {false, fmt::format("attitude: roll differs from the IMU by {:.4f} rad, pitch by "
                               "{:.4f} rad, max_difference_rad = {}",
                               roll_diff, pitch_diff, config.max_difference_rad)};
}

GateResult check_speed(const Eigen::Isometry3d& T_world_body_previous, double previous_stamp_s,
                       const Eigen::Isometry3d& T_world_body_current, double current_stamp_s,
                       const SpeedGateConfig& config) {
    config.validate();
    if (!T_world_body_previous.matrix().allFinite() || !T_world_body_current.matrix().allFinite()) {
        throw InputError("speed_gate: a pose is not finite");
    }
    if (!std::isfinite(previous_stamp_s) || !std::isfinite(current_stamp_s) ||
        !(current_stamp_s > previous_stamp_s)) {
        throw InputError(fmt::format(
            "speed_gate: current_stamp_s = {} must be finite and after previous_stamp_s = {}",
            current_stamp_s, previous_stamp_s));
    }
    const double distance_m =
        (T_world_body_current.translation() - T_world_body_previous.translation()).norm();
    const double speed_mps = distance_m / (current_stamp_s - previous_stamp_s);
    if (speed_mps <= config.max_speed_mps) return pass();
    return {false,
            fmt::format("speed: {:.3f} m in {:.3f} s = {:.3f} m/s > max_speed_mps = {}", distance_m,
                        current_stamp_s - previous_stamp_s, speed_mps, config.max_speed_mps)};
}

GateResult check_overlap(double overlap, const OverlapGateConfig& config) {
    config.validate();
    if (!(overlap >= 0.0 && overlap <= 1.0)) {
        throw InputError(fmt::format("overlap_gate: overlap = {}, expected in [0, 1]", overlap));
    }
    if (overlap >= config.min_overlap) return pass();
    return {false, fmt::format("overlap: {:.3f} of the scan points within {} m of the map < "
                               "min_overlap = {}",
                               overlap, config.voxel_size_m, config.min_overlap)};
}

GateResult check_overlap(const PointCloud& scan_in_map, const KdTree& map_tree,
                         const OverlapGateConfig& config, const ParallelConfig& parallel) {
    config.validate();
    return check_overlap(overlap_ratio(scan_in_map, map_tree, config.voxel_size_m, parallel),
                         config);
}

}  // namespace scantling::registration
