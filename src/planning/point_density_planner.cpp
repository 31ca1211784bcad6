#include <scantling/planning/point_density_planner.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <tuple>

#include <fmt/format.h>

#include <scantling/core/angles.hpp>
#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::planning {
namespace {

constexpr double kSectorWidth_rad = std::numbers::pi / 2.0;

int wrap_sector(int s) { return ((s % kNumSectors) + kNumSectors) % kNumSectors; }

void require_finite(std::span<const Eigen::Vector3d> points, std::string_view what) {
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!points[i].allFinite()) {
            throw InputError(fmt::format("{}: point {} is not finite", what, i));
        }
    }
}

/// `angle_rad` in [0, 2π).
double positive_angle(double angle_rad) {
    const double a = std::fmod(angle_rad, 2.0 * std::numbers::pi);
    return a < 0.0 ? a + 2.0 * std::numbers::pi : a;
}

}  // namespace

void PointDensityPlannerConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(voxel_edge_m, prefix, "voxel_edge_m");
    require_non_negative(standoff_m, prefix, "standoff_m");
    require_non_negative(fixed_flight_radius_m, prefix, "fixed_flight_radius_m");
    if (fixed_centre_xy_m && !fixed_centre_xy_m->allFinite()) {
        throw ConfigError(fmt::format("{}.fixed_centre_xy_m is not finite", prefix));
    }
    if (flight_height_m)
        require(std::isfinite(*flight_height_m), prefix, "flight_height_m", *flight_height_m,
                "finite");
    require(std::isfinite(start_angle_rad), prefix, "start_angle_rad", start_angle_rad, "finite");
    require_positive(half_height_band_m, prefix, "half_height_band_m");
    require_count_at_least(max_steps, 1, prefix, "max_steps");
}

ObjectEstimate locate_object(std::span<const Eigen::Vector3d> points_world,
                             const PointDensityPlannerConfig& config) {
    config.validate();
    require_finite(points_world, "locate_object");
    ObjectEstimate object;
    object.object_radius_m = 0.5 * config.voxel_edge_m;
    object.flight_radius_m = config.fixed_flight_radius_m > 0.0
                                 ? config.fixed_flight_radius_m
                                 : config.standoff_m + object.object_radius_m;
    // Ordered map: the densest voxel's tie goes to the lowest (x, y, z) index.
    std::map<std::tuple<long, long, long>, std::size_t> counts;
    for (const Eigen::Vector3d& p : points_world) {
        const Eigen::Vector3d c = (p / config.voxel_edge_m).array().floor();
        ++counts[{static_cast<long>(c.x()), static_cast<long>(c.y()), static_cast<long>(c.z())}];
    }
    const auto densest =
        std::max_element(counts.begin(), counts.end(),
                         [](const auto& a, const auto& b) { return a.second < b.second; });
    if (densest != counts.end()) {
        object.points_in_voxel = densest->second;
        Eigen::Vector2d sum = Eigen::Vector2d::Zero();
        for (const Eigen::Vector3d& p : points_world) {
            const Eigen::Vector3d c = (p / config.voxel_edge_m).array().floor();
            if (std::tuple<long, long, long>{static_cast<long>(c.x()), static_cast<long>(c.y()),
                                             static_cast<long>(c.z())} == densest->first) {
                sum += p.head<2>();
            }
        }
        object.centre_xy_m = sum / static_cast<double>(densest->second);
        object.found = true;
    }
    if (config.fixed_centre_xy_m) {
        object.centre_xy_m = *config.fixed_centre_xy_m;
        object.found = true;
    }
    return object;
}

int sector_of(const Eigen::Vector3d& p_world, const Eigen::Vector2d& centre_xy_m,
              double start_angle_rad) {
    const Eigen::Vector2d d = p_world.head<2>() - centre_xy_m;
    const double a = positive_angle(std::atan2(d.y(), d.x()) - start_angle_rad);
    return std::min(kNumSectors - 1, static_cast<int>(a / kSectorWidth_rad));
}

SectorCounts count_sectors(std::span<const Eigen::Vector3d> points_world,
                           const Eigen::Vector2d& centre_xy_m, double start_angle_rad) {
    SectorCounts counts{};
    for (const Eigen::Vector3d& p : points_world) {
        ++counts[static_cast<std::size_t>(sector_of(p, centre_xy_m, start_angle_rad))];
    }
    return counts;
}

PointDensityPlanner::PointDensityPlanner(PointDensityPlannerConfig config)
    : config_(std::move(config)) {
    config_.validate();
}

void PointDensityPlanner::aim(std::span<const Eigen::Vector3d> points_world,
                              const ObjectEstimate& object, double current_angle_rad,
                              DensityStep& step) const {
    // The sector's points at half height (004 l.61): within a band about its mid height.
    double z_min = std::numeric_limits<double>::infinity();
    double z_max = -z_min;
    for (const Eigen::Vector3d& p : points_world) {
        if (sector_of(p, object.centre_xy_m, config_.start_angle_rad) != step.sector) continue;
        z_min = std::min(z_min, p.z());
        z_max = std::max(z_max, p.z());
    }
    const double z_mid = std::isfinite(z_min) ? 0.5 * (z_min + z_max) : 0.0;
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    std::size_t n = 0;
    for (const Eigen::Vector3d& p : points_world) {
        if (sector_of(p, object.centre_xy_m, config_.start_angle_rad) != step.sector) continue;
        if (std::abs(p.z() - z_mid) > config_.half_height_band_m) continue;
        sum += p.head<2>() - object.centre_xy_m;
        ++n;
    }
    step.target_angle_rad = n > 0 && sum.norm() > 0.0
                                ? std::atan2(sum.y(), sum.x())
                                : config_.start_angle_rad + (step.sector + 0.5) * kSectorWidth_rad;
    const double z = config_.flight_height_m.value_or(z_mid);
    step.target_world_m = Eigen::Vector3d(
        object.centre_xy_m.x() + object.flight_radius_m * std::cos(step.target_angle_rad),
        object.centre_xy_m.y() + object.flight_radius_m * std::sin(step.target_angle_rad), z);
    const double delta = step.target_angle_rad - current_angle_rad;
    if (step.direction == 0) {  // the shorter way round; a half turn goes counter-clockwise
        step.arc_rad = wrap_angle_rad(delta);
        if (step.arc_rad == -std::numbers::pi) step.arc_rad = std::numbers::pi;
        step.direction = step.arc_rad >= 0.0 ? 1 : -1;
    } else {
        step.arc_rad = step.direction * positive_angle(step.direction * delta);
    }
}

DensityStep PointDensityPlanner::next(std::span<const Eigen::Vector3d> points_world,
                                      const ObjectEstimate& object, double current_angle_rad) {
    if (!std::isfinite(current_angle_rad)) {
        throw InputError("point_density_planner.next: current_angle_rad is not finite");
    }
    require_finite(points_world, "point_density_planner.next");
    DensityStep step;
    step.step = steps_ + 1;
    if (!object.found) return step;
    step.counts = count_sectors(points_world, object.centre_xy_m, config_.start_angle_rad);
    if (std::all_of(step.counts.begin(), step.counts.end(),
                    [&](std::size_t c) { return c >= config_.density_threshold_points; })) {
        step.status = PlannerStatus::kThresholdReached;
        return step;
    }
    if (steps_ >= config_.max_steps) {
        step.status = PlannerStatus::kMaxSteps;
        return step;
    }
    const int round_position = static_cast<int>(steps_ % kNumSectors);
    if (round_position == 0) {
        step.sector = static_cast<int>(std::min_element(step.counts.begin(), step.counts.end()) -
                                       step.counts.begin());
    } else {
        step.sector = wrap_sector(first_sector_ + round_position * order_);
        step.direction = order_;
    }
    aim(points_world, object, current_angle_rad, step);
    if (round_position == 0) {
        // 004 l.118: the neighbour with fewer points is next; the rest follow the same way.
        first_sector_ = step.sector;
        const std::size_t ccw = step.counts[wrap_sector(step.sector + 1)];
        const std::size_t cw = step.counts[wrap_sector(step.sector - 1)];
        order_ = ccw < cw ? 1 : (cw < ccw ? -1 : step.direction);
    }
    step.next_sector = round_position < kNumSectors - 1
                           ? wrap_sector(first_sector_ + (round_position + 1) * order_)
                           : -1;
    step.status = PlannerStatus::kTarget;
    ++steps_;
    return step;
}

}  // namespace scantling::planning
