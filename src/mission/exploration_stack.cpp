// The exploring drone's estimation and mapping inputs (exploration_stack.hpp); its guidance is
// in exploration_guidance.cpp.
#include <scantling/mission/exploration_stack.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/safety/obstacle_points.hpp>

#include "detail/frames.hpp"

namespace scantling::mission {
namespace {

bool finite(const Eigen::Isometry3d& T) { return T.matrix().allFinite(); }

}  // namespace

const char* to_string(ExplorationPhase phase) {
    switch (phase) {
        case ExplorationPhase::kTakeOff:
            return "take_off";
        case ExplorationPhase::kSurvey:
            return "survey";
        case ExplorationPhase::kExplore:
            return "explore";
        case ExplorationPhase::kDone:
            return "done";
    }
    return "unknown";
}

void ExplorationStackConfig::validate(std::string_view prefix) const {
    using config_checks::require_at_least;
    using config_checks::require_non_negative;
    using config_checks::require_positive;
    local_ekf.validate(fmt::format("{}.local_ekf", prefix));
    map.validate(fmt::format("{}.map", prefix));
    nbv.validate(fmt::format("{}.nbv", prefix));
    defects.validate(fmt::format("{}.defects", prefix));
    defect_map.validate(fmt::format("{}.defect_map", prefix));
    position_controller.validate(fmt::format("{}.position_controller", prefix));
    vtp.validate(fmt::format("{}.vtp", prefix));
    require_positive(vio_increment_sigma_m, prefix, "vio_increment_sigma_m");
    require_positive(vio_increment_sigma_rad, prefix, "vio_increment_sigma_rad");
    require_positive(vio_period_s, prefix, "vio_period_s");
    require_positive(vio_yaw_period_s, prefix, "vio_yaw_period_s");
    require_positive(barometer_sigma_m, prefix, "barometer_sigma_m");
    require_positive(takeoff_height_m, prefix, "takeoff_height_m");
    require_positive(max_speed_mps, prefix, "max_speed_mps");
    require_positive(max_yaw_rate_radps, prefix, "max_yaw_rate_radps");
    require_positive(goal_tolerance_m, prefix, "goal_tolerance_m");
    require_positive(yaw_tolerance_rad, prefix, "yaw_tolerance_rad");
    require_positive(goal_timeout_s, prefix, "goal_timeout_s");
    require_positive(max_depth_age_s, prefix, "max_depth_age_s");
    require_positive(obstacle_memory_s, prefix, "obstacle_memory_s");
    if (!(max_travel_heading_error_rad > 0.0 &&
          max_travel_heading_error_rad <= 1.5707963267948966)) {
        throw ConfigError(fmt::format("{}.max_travel_heading_error_rad = {}, expected in (0, pi/2]",
                                      prefix, max_travel_heading_error_rad));
    }
    collision.validate(fmt::format("{}.collision", prefix));
    require_positive(depth_lost_abort_s, prefix, "depth_lost_abort_s");
    if (max_nodes_when_exhausted < nbv.max_nodes) {
        throw ConfigError(
            fmt::format("{}.max_nodes_when_exhausted = {}, expected >= {}.nbv.max_nodes = {}",
                        prefix, max_nodes_when_exhausted, prefix, nbv.max_nodes));
    }
    require_at_least(max_failed_plans, 1, prefix, "max_failed_plans");
    require_at_least(exhausted_plans_to_finish, 1, prefix, "exhausted_plans_to_finish");
    require_non_negative(takeoff_clearance_m, prefix, "takeoff_clearance_m");
    require_non_negative(self_clearance_m, prefix, "self_clearance_m");
    if (!finite(T_body_depth) || !finite(T_body_camera)) {
        throw ConfigError(fmt::format("{}.T_body_depth / T_body_camera: expected finite", prefix));
    }
}

namespace {

/// The planner's config with N_max nodes and its own seed.
planning::NbvPlannerConfig wide(planning::NbvPlannerConfig config, int max_nodes) {
    config.max_nodes = max_nodes;
    config.seed = Rng(config.seed).split(1).next_u64();
    return config;
}

/// The config with the controller's limits taken from the stack's (written once: table G.1).
ExplorationStackConfig validated(ExplorationStackConfig config) {
    config.position_controller.max_speed_mps = config.max_speed_mps;
    config.position_controller.max_yaw_rate_radps = config.max_yaw_rate_radps;
    config.collision.max_speed_mps = config.max_speed_mps;
    config.validate();
    return config;
}

}  // namespace

ExplorationStack::ExplorationStack(ExplorationStackConfig config,
                                   const Eigen::Isometry3d& T_world_body_start, double start_s)
    : config_(validated(std::move(config))),
      T_world_odom_(detail::levelled(T_world_body_start, "exploration stack")),
      local_(config_.local_ekf),
      map_(config_.map),
      planner_(config_.nbv),
      wide_planner_(wide(config_.nbv, config_.max_nodes_when_exhausted)),
      controller_(config_.position_controller),
      defect_map_(config_.defect_map) {
    if (!finite(T_world_body_start) || !std::isfinite(start_s)) {
        throw InputError("exploration stack: the start pose and time must be finite");
    }
    local_.initialize(start_s, T_world_odom_.inverse() * T_world_body_start);
    p_start_world_m_ = T_world_body_start.translation();
    p_hold_world_m_ = p_start_world_m_;
    yaw_hold_rad_ = detail::yaw_of(T_world_body_start.linear());
}

void ExplorationStack::reject(const std::string& sensor, double stamp_s) {
    ++inputs_rejected_;
    if (std::find(rejecting_.begin(), rejecting_.end(), sensor) != rejecting_.end()) return;
    rejecting_.push_back(sensor);
    pending_events_.push_back(
        {.t_s = stamp_s,
         .type = "input_rejected",
         .json = fmt::format(R"({{"sensor":"{}","reason":"non-finite values"}})", sensor)});
}

void ExplorationStack::add_imu(const io::ImuRecord& sample) {
    if (!std::isfinite(sample.stamp_s) || !sample.specific_force_mps2.allFinite() ||
        !sample.angular_rate_radps.allFinite()) {
        return reject("imu", sample.stamp_s);
    }
    std::erase(rejecting_, std::string("imu"));
    local_.add_imu(sample);
}

void ExplorationStack::add_vio(const io::VioRecord& sample) {
    if (!std::isfinite(sample.stamp_s) || !finite(sample.T_odom_body)) {
        return reject("vio", sample.stamp_s);
    }
    std::erase(rejecting_, std::string("vio"));
    // A dropout keeps the last valid sample: the VIO's odom frame carries on through it (it
    // relocalises in its own map), so the increment across the gap is fused on its return,
    // with its variance grown by the samples it spans.
    if (!sample.valid) return;
    if (!vio_previous_ || sample.stamp_s <= vio_previous_->stamp_s) {
        local_.clone_pose(sample.stamp_s);
        vio_previous_ = sample;
        return;
    }
    const double samples =
        std::max(1.0, (sample.stamp_s - vio_previous_->stamp_s) / config_.vio_period_s);
    Matrix6d information = Matrix6d::Zero();
    information.topLeftCorner<3, 3>().diagonal().setConstant(
        1.0 / (samples * config_.vio_increment_sigma_m * config_.vio_increment_sigma_m));
    information.bottomRightCorner<3, 3>().diagonal().setConstant(
        1.0 / (samples * config_.vio_increment_sigma_rad * config_.vio_increment_sigma_rad));
    local_.update_increment(
        {.start_stamp_s = vio_previous_->stamp_s,
         .end_stamp_s = sample.stamp_s,
         .T_body0_body1 = vio_previous_->T_odom_body.inverse() * sample.T_odom_body,
         .information = information});
    vio_previous_ = sample;
    fuse_vio_yaw(sample);
}

void ExplorationStack::fuse_vio_yaw(const io::VioRecord& sample) {
    if (vio_yaw_stamp_s_ && sample.stamp_s < *vio_yaw_stamp_s_ + config_.vio_yaw_period_s) return;
    const Eigen::Matrix3d R = sample.T_odom_body.rotation();
    const double sigma_rad =
        std::max(std::sqrt(std::max(sample.variances[5], 0.0)), config_.vio_increment_sigma_rad);
    local_.update_yaw(
        {.stamp_s = sample.stamp_s, .yaw_odom_rad = detail::yaw_of(R), .sigma_rad = sigma_rad});
    vio_yaw_stamp_s_ = sample.stamp_s;
}

void ExplorationStack::add_barometer(const io::BarometerRecord& altitude) {
    if (!std::isfinite(altitude.stamp_s) || !std::isfinite(altitude.altitude_m)) {
        return reject("barometer", altitude.stamp_s);
    }
    std::erase(rejecting_, std::string("barometer"));
    local_.update_barometer({.stamp_s = altitude.stamp_s,
                             .altitude_m = altitude.altitude_m,
                             .sigma_m = config_.barometer_sigma_m});
}

void ExplorationStack::add_depth(const PointCloud& frame_sensor, double stamp_s) {
    if (!std::isfinite(stamp_s)) return reject("depth_camera", stamp_s);
    // The frame at the current estimate: depth frames arrive within a tick of their stamp,
    // and the map's voxels are coarser than what the vehicle moves in a tick.
    const Eigen::Isometry3d T_world_depth = T_world_body_estimate() * config_.T_body_depth;
    map_.insert_depth_frame(frame_sensor, T_world_depth);
    clear_vehicle_box(config_.self_clearance_m);
    remember_obstacles(stamp_s);
    latest_depth_world_.points.clear();
    for (const Eigen::Vector3d& p : frame_sensor.points) {
        if (p.allFinite()) latest_depth_world_.points.push_back(T_world_depth * p);
    }
    latest_depth_stamp_s_ = stamp_s;
}

void ExplorationStack::add_sightings(std::span<const io::DefectSighting> sightings,
                                     double stamp_s) {
    if (sightings.empty() || latest_depth_world_.empty()) return;
    const localization::DroneState s = local_.state();
    const Eigen::Isometry3d T_world_body = T_world_body_estimate();
    const localization::LiftingView view{.intrinsics = config_.camera,
                                         .T_world_camera = T_world_body * config_.T_body_camera,
                                         .p_world_body = T_world_body.translation(),
                                         .body_covariance = s.covariance.topLeftCorner<6, 6>()};
    for (const io::DefectSighting& sighting : sightings) {
        if (!sighting.pixel.allFinite() || !std::isfinite(sighting.stamp_s)) {
            reject("camera", stamp_s);
            continue;
        }
        localization::LiftResult lifted =
            localization::lift_defect(sighting, view, latest_depth_world_, config_.defects);
        if (lifted.observation) defect_map_.add(std::move(*lifted.observation));
    }
}

void ExplorationStack::remember_obstacles(double stamp_s) {
    constexpr double kVoxel_m = 0.05;  // finer than the frustum's resolution at 1 m
    recent_obstacles_world_.emplace_back(stamp_s, voxel_downsample(latest_depth_world_, kVoxel_m));
    while (!recent_obstacles_world_.empty() &&
           recent_obstacles_world_.front().first < stamp_s - config_.obstacle_memory_s) {
        recent_obstacles_world_.pop_front();
    }
    // The points the next ticks can need: within reach of the vehicle plus what it flies in
    // a camera period (1 m at most), merged across the frames.
    constexpr double kMotionMargin_m = 1.0;
    const Eigen::Vector3d p = T_world_body_estimate().translation();
    const double reach_m = safety::obstacle_reach_m(config_.collision) + kMotionMargin_m;
    PointCloud near_world;
    for (const auto& [stamp, frame] : recent_obstacles_world_) {
        for (const Eigen::Vector3d& q : frame.points) {
            if ((q - p).norm() <= reach_m) near_world.points.push_back(q);
        }
    }
    near_obstacles_world_ = voxel_downsample(near_world, kVoxel_m);
}

Eigen::Vector3d ExplorationStack::safe_velocity(const Eigen::Vector3d& v_world_mps,
                                                ExplorationCommand& out) const {
    if (!config_.collision_prevention || near_obstacles_world_.empty()) return v_world_mps;
    const Eigen::Isometry3d T_body_world = T_world_body_estimate().inverse();
    const double reach_m = safety::obstacle_reach_m(config_.collision);
    PointCloud near_body;
    for (const Eigen::Vector3d& p : near_obstacles_world_.points) {
        const Eigen::Vector3d q = T_body_world * p;
        if (q.norm() <= reach_m) near_body.points.push_back(q);
    }
    const safety::ObstaclePoints obstacles =
        safety::gather_obstacle_points(near_body, config_.collision);
    const Eigen::Matrix3d R_world_body = T_body_world.linear().transpose();
    const safety::CollisionPreventionResult r = safety::prevent_collision(
        R_world_body.transpose() * v_world_mps, obstacles, config_.collision);
    const Eigen::Vector3d v = R_world_body * r.v_cmd_body_mps;
    out.limited = (v - v_world_mps).norm() > 1e-9;
    return v;
}

void ExplorationStack::clear_vehicle_box(double margin_m) {
    const Eigen::Vector3d p = T_world_body_estimate().translation();
    const Eigen::Vector3d half =
        0.5 * config_.nbv.vehicle_box_m + Eigen::Vector3d::Constant(margin_m);
    map_.mark_free(Eigen::AlignedBox3d(p - half, p + half));
}

Eigen::Isometry3d ExplorationStack::T_world_body_estimate() const {
    return T_world_odom_ * local_.state().T_odom_body;
}

localization::DroneState ExplorationStack::estimate() const {
    localization::DroneState s = local_.state();
    s.T_odom_body = T_world_odom_ * s.T_odom_body;
    s.v_odom_mps = T_world_odom_.linear() * s.v_odom_mps;
    s.a_odom_mps2 = T_world_odom_.linear() * s.a_odom_mps2;
    localization::Matrix9d R =
        localization::Matrix9d::Zero();  // (δp, δθ, δv) each turned into the world frame
    for (int i = 0; i < 3; ++i) R.block<3, 3>(3 * i, 3 * i) = T_world_odom_.linear();
    s.covariance = R * s.covariance * R.transpose();
    return s;
}

}  // namespace scantling::mission
