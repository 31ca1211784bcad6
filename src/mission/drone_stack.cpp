// The drone's autonomy stack (drone_stack.hpp).
#include <scantling/mission/drone_stack.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>

#include "detail/frames.hpp"

namespace scantling::mission {
namespace {

using namespace scantling::config_checks;

using detail::yaw_of;

Eigen::Isometry3d levelled(const Eigen::Isometry3d& T_world_body) {
    return detail::levelled(T_world_body, "drone stack");
}

PointCloud to_body(const PointCloud& sweep_lidar, const Eigen::Isometry3d& T_body_lidar) {
    PointCloud cloud;
    cloud.stamp_s = sweep_lidar.stamp_s;
    cloud.points.reserve(sweep_lidar.points.size());
    for (const Eigen::Vector3d& p : sweep_lidar.points) {
        if (p.allFinite()) cloud.points.push_back(T_body_lidar * p);
    }
    return cloud;
}

/// `information` with its eigenvalues capped at 1/σ_min², rotations compared at `lever_m`
/// metres per radian (drone_stack.hpp, odometry_min_sigma_m).
Matrix6d capped(const Matrix6d& information, double min_sigma_m, double lever_m) {
    Vector6d scale;
    scale << 1.0, 1.0, 1.0, lever_m, lever_m, lever_m;  // ξ_scaled = S ξ
    const Matrix6d scaled =
        scale.cwiseInverse().asDiagonal() * information * scale.cwiseInverse().asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(0.5 * (scaled + scaled.transpose()));
    const Vector6d values =
        eigen.eigenvalues().cwiseMax(0.0).cwiseMin(1.0 / (min_sigma_m * min_sigma_m));
    const Matrix6d capped_scaled =
        eigen.eigenvectors() * values.asDiagonal() * eigen.eigenvectors().transpose();
    return scale.asDiagonal() * capped_scaled * scale.asDiagonal();
}

bool has_finite_point(const PointCloud& cloud) {
    return std::any_of(cloud.points.begin(), cloud.points.end(),
                       [](const Eigen::Vector3d& p) { return p.allFinite(); });
}

bool moving(control::MissionState state) {
    return state == control::MissionState::kRunning || state == control::MissionState::kGoingHome;
}

bool registered(odometry::FrameStatus status) {
    return status == odometry::FrameStatus::kOk || status == odometry::FrameStatus::kDegenerate;
}

}  // namespace

odometry::LiodomConfig drone_odometry_defaults() {
    odometry::LiodomConfig config = odometry::liodom_preset("os1_drone");
    config.registration.degeneracy_ratio = 0.05;
    return config;
}

void DroneStackConfig::validate(std::string_view prefix) const {
    odometry.validate(std::string(prefix) + ".odometry");
    require_positive(odometry_sigma_m, prefix, "odometry_sigma_m");
    require_positive(odometry_min_sigma_m, prefix, "odometry_min_sigma_m");
    require_positive(odometry_lever_m, prefix, "odometry_lever_m");
    local_ekf.validate(std::string(prefix) + ".local_ekf");
    require_positive(barometer_sigma_m, prefix, "barometer_sigma_m");
    global_ekf.validate(std::string(prefix) + ".global_ekf");
    collision.validate(std::string(prefix) + ".collision");
    height.validate(std::string(prefix) + ".height");
    require_positive(max_sweep_age_s, prefix, "max_sweep_age_s");
    require_positive(max_imu_age_s, prefix, "max_imu_age_s");
    require_non_negative(imu_coast_s, prefix, "imu_coast_s");
    require_positive(max_position_sigma_m, prefix, "max_position_sigma_m");
    manager.validate(std::string(prefix) + ".manager");
    wind.validate(std::string(prefix) + ".wind");
    if (!T_body_lidar.matrix().allFinite()) {
        throw ConfigError(std::string(prefix) + ".T_body_lidar is not finite");
    }
}

DroneStack::DroneStack(DroneStackConfig config, planning::WaypointPath path,
                       const Eigen::Isometry3d& T_world_body_start, double start_s)
    : config_((config.validate(), std::move(config))),
      T_world_odom_start_(levelled(T_world_body_start)),
      local_(config_.local_ekf),
      global_(config_.global_ekf, T_world_odom_start_),
      odometry_(config_.odometry,
                T_world_odom_start_.inverse() * T_world_body_start * config_.T_body_lidar),
      manager_(std::move(path), config_.manager),
      wind_observer_(config_.wind),
      imu_watchdog_("imu", config_.max_imu_age_s, start_s),
      lidar_watchdog_("lidar", config_.max_sweep_age_s, start_s) {
    local_.initialize(start_s, T_world_odom_start_.inverse() * T_world_body_start);
    global_.add_local(local_.state());
    odometry_.set_motion_prior(
        [this](double t0_s, double t1_s) { return odometry_prior(t0_s, t1_s); });
}

void DroneStack::reject(const std::string& sensor, double stamp_s) {
    ++inputs_rejected_;
    if (std::find(rejecting_.begin(), rejecting_.end(), sensor) != rejecting_.end()) return;
    rejecting_.push_back(sensor);
    pending_events_.push_back(
        {.type = control::MissionEventType::kInputRejected,
         .t_s = stamp_s,
         .from = manager_.state(),
         .to = manager_.state(),
         .reason = "a sample with non-finite values was dropped before the estimators",
         .sensor = sensor});
}

void DroneStack::accept(const std::string& sensor) { std::erase(rejecting_, sensor); }

void DroneStack::add_imu(const io::ImuRecord& sample) {
    if (!std::isfinite(sample.stamp_s) || !sample.specific_force_mps2.allFinite() ||
        !sample.angular_rate_radps.allFinite()) {
        return reject("imu", sample.stamp_s);
    }
    accept("imu");
    local_.add_imu(sample);
    global_.add_local(local_.state());
    imu_watchdog_.feed(sample.stamp_s);
}

Eigen::Isometry3d DroneStack::local_pose_in_world() const {
    return global_.T_world_odom() * local_.state().T_odom_body;
}

std::optional<Eigen::Isometry3d> DroneStack::odometry_prior(double t0_s, double t1_s) const {
    // The global estimate's motion of the LiDAR since the previous sweep (the filters are at
    // t1 already): the local EKF's motion carried by the global EKF's T_world_odom, whose
    // drift velocity moves it between the sweeps. Not the local EKF's motion alone: along the hull
    // LiODOM observes little, nothing aids the local filter's velocity there, and it wanders (7 m/s
    // after 60 s on one seed), while the global EKF's drift velocity, held by UWB, cancels that.
    // LiODOM keeps the prior along its degenerate directions, so with the local motion its map slid
    // along the hull at the local filter's speed until no map cell was within reach
    // (docs/results.md). Without absolute fixes the two motions are the same.
    if (!previous_sweep_stamp_s_ || std::abs(*previous_sweep_stamp_s_ - t0_s) > 1e-6 ||
        std::abs(local_.stamp_s() - t1_s) > 0.02) {
        return std::nullopt;
    }
    const Eigen::Isometry3d& T_bl = config_.T_body_lidar;
    return (T_world_body_previous_sweep_ * T_bl).inverse() * (local_pose_in_world() * T_bl);
}

std::optional<odometry::FrameReport> DroneStack::add_sweep(const PointCloud& sweep_lidar,
                                                           double stamp_s) {
    // A sweep of NaNs (a dead link rather than an empty scene) is not a LiDAR sample: LiODOM
    // is not told, so the next good sweep is predicted over the whole gap by the EKF.
    if (!std::isfinite(stamp_s) || !has_finite_point(sweep_lidar)) {
        reject("lidar", stamp_s);
        return std::nullopt;
    }
    accept("lidar");
    lidar_watchdog_.feed(stamp_s);
    PointCloud sweep = sweep_lidar;
    sweep.stamp_s = stamp_s;
    const odometry::FrameReport report = odometry_.process(sweep);
    fuse_increment(report, stamp_s);
    const PointCloud sweep_body = to_body(sweep_lidar, config_.T_body_lidar);
    latest_obstacles_ = safety::gather_obstacle_points(sweep_body, config_.collision);
    latest_clearance_ = safety::clearance_from_cloud(sweep_body, config_.height);
    latest_sweep_stamp_s_ = stamp_s;
    return report;
}

void DroneStack::fuse_increment(const odometry::FrameReport& report, double stamp_s) {
    const bool chained = registered(report.status) && T_lodom_lidar_previous_.has_value();
    if (chained) {
        const Eigen::Isometry3d& T_bl = config_.T_body_lidar;
        const Eigen::Isometry3d T_l0_l1 = T_lodom_lidar_previous_->inverse() * report.T_odom_sensor;
        // LiODOM's information is of exp(δ) · T_lodom_lidar1 (odom frame); the increment's
        // is of exp(ε) · T_b0_b1 (body0 frame): δ = Ad(T_lodom_b0) ε.
        const Matrix6d B = se3_adjoint(*T_lodom_lidar_previous_ * T_bl.inverse());
        const double scale = 1.0 / (config_.odometry_sigma_m * config_.odometry_sigma_m);
        localization::PoseIncrement increment{
            .start_stamp_s = *previous_sweep_stamp_s_,
            .end_stamp_s = stamp_s,
            .T_body0_body1 = T_bl * T_l0_l1 * T_bl.inverse(),
            .information = capped(scale * B.transpose() * report.information * B,
                                  config_.odometry_min_sigma_m, config_.odometry_lever_m)};
        local_.update_increment(increment);
    } else {
        local_.clone_pose(stamp_s);  // start (or restart) the chain of increments here
    }
    const bool usable = registered(report.status) || report.status == odometry::FrameStatus::kFirst;
    T_lodom_lidar_previous_ = usable ? std::optional(report.T_odom_sensor) : std::nullopt;
    previous_sweep_stamp_s_ = stamp_s;
    // The local pose after this sweep's increment (the global EKF has not seen it yet: its
    // state would count the correction again as motion before the next sweep).
    T_world_body_previous_sweep_ = local_pose_in_world();
}

void DroneStack::add_range(const io::RangeRecord& range) {
    if (!std::isfinite(range.stamp_s) || (range.valid && !std::isfinite(range.range_m))) {
        return reject("range_finder", range.stamp_s);
    }
    if (range.valid) accept("range_finder");  // a no-return says nothing of the link
    local_.update_range(range);
}

void DroneStack::add_barometer(const io::BarometerRecord& altitude) {
    if (!std::isfinite(altitude.stamp_s) || !std::isfinite(altitude.altitude_m)) {
        return reject("barometer", altitude.stamp_s);
    }
    accept("barometer");
    local_.update_barometer({.stamp_s = altitude.stamp_s,
                             .altitude_m = altitude.altitude_m,
                             .sigma_m = config_.barometer_sigma_m});
}

void DroneStack::add_uwb(const io::UwbRecord& range) {
    if (!std::isfinite(range.stamp_s) || (range.valid && !std::isfinite(range.range_m))) {
        return reject("uwb", range.stamp_s);
    }
    if (range.valid) accept("uwb");
    global_.update_uwb(range);
}

bool DroneStack::estimate_valid() const {
    const localization::DroneState state = global_.state();
    const double horizontal_variance = state.covariance(0, 0) + state.covariance(1, 1);
    return local_.initialized() && state.T_odom_body.matrix().allFinite() &&
           std::isfinite(horizontal_variance) &&
           horizontal_variance <= config_.max_position_sigma_m * config_.max_position_sigma_m;
}

void DroneStack::watch_streams(double t_s, std::vector<control::OperatorCommand>& commands) {
    for (safety::StreamWatchdog* watchdog : {&imu_watchdog_, &lidar_watchdog_}) {
        if (watchdog == &lidar_watchdog_ && !config_.lidar_expected) continue;
        const auto change = watchdog->check(t_s);
        if (!change) continue;
        const bool lost = change->change == safety::StreamChange::kLost;
        pending_events_.push_back(
            {.type = lost ? control::MissionEventType::kSensorLost
                          : control::MissionEventType::kSensorRestored,
             .t_s = t_s,
             .from = manager_.state(),
             .to = manager_.state(),
             .reason = fmt::format("{}: no sample for {:.3f} s", watchdog->name(), change->age_s),
             .sensor = watchdog->name()});
    }
    // The operator's own commands take precedence over the stack's pause and resume.
    if (!commands.empty()) lidar_paused_ = false;
    if (!config_.collision_prevention || !config_.lidar_expected) return;
    if (lidar_watchdog_.lost() && commands.empty() && moving(manager_.state())) {
        commands.push_back({.type = control::OperatorCommandType::kPause});
        lidar_paused_ = true;
    } else if (!lidar_watchdog_.lost() && lidar_paused_ && commands.empty()) {
        if (manager_.state() == control::MissionState::kPaused) {
            commands.push_back({.type = control::OperatorCommandType::kResume});
        }
        lidar_paused_ = false;
    }
}

StackCommand DroneStack::command(double t_s,
                                 std::span<const control::OperatorCommand> operator_commands) {
    std::vector<control::OperatorCommand> commands(operator_commands.begin(),
                                                   operator_commands.end());
    watch_streams(t_s, commands);
    const localization::DroneState state = global_.state();
    const control::EstimatedState estimate{.p_world_m = state.T_odom_body.translation(),
                                           .yaw_rad = yaw_of(state.T_odom_body.linear()),
                                           .v_world_mps = state.v_odom_mps,
                                           .valid = estimate_valid() && !imu_watchdog_.lost(),
                                           .holdable = !imu_watchdog_.lost()};
    // Observed only on a valid estimate, at its own stamp: an estimate the IMU has stopped
    // updating is not seen again as a vehicle standing still, and one that has been declared
    // invalid (an IMU gap, a lost position) may carry a velocity that is metres per second
    // off, which the observer would turn into a real motion (measured after a 0.2 s IMU gap,
    // docs/results.md). Nor once the manager has failed safe, which trusts the estimate no
    // more. Meanwhile the last wind estimate is held.
    const bool failed_safe = manager_.state() == control::MissionState::kFailsafe;
    if (config_.wind_compensation && estimate.valid && !failed_safe &&
        estimate.v_world_mps.allFinite() && std::isfinite(state.stamp_s)) {
        wind_observer_.observe(estimate.v_world_mps, state.stamp_s);
    }
    const control::MissionState state_before = manager_.state();
    control::MissionTick tick = manager_.update(estimate, t_s, commands);
    coast(t_s, !commands.empty(), state_before, tick);
    // A rejected sample may not even have a finite stamp: such events take the tick's time.
    for (control::MissionEvent& e : pending_events_) {
        if (!std::isfinite(e.t_s)) e.t_s = t_s;
    }
    tick.events.insert(tick.events.begin(), pending_events_.begin(), pending_events_.end());
    pending_events_.clear();
    StackCommand out{.v_world_mps = tick.v_cmd_world_mps,
                     .yaw_rate_radps = tick.yaw_rate_cmd_radps,
                     .v_requested_world_mps = tick.v_cmd_world_mps,
                     .limited = false,
                     .collision = std::nullopt,
                     .state = tick.state,
                     .events = std::move(tick.events)};
    // The safety layer needs only the attitude (levelled by gravity, valid even when the
    // position is lost): a failsafe's zero command still drifts downwind, and the repulsion
    // keeps that drift off the structure.
    if (state.T_odom_body.linear().allFinite()) {
        out.v_world_mps = apply_safety(out.v_requested_world_mps, t_s, out);
    }
    out.limited = (out.v_world_mps - out.v_requested_world_mps).norm() > 1e-9;
    if (!out.v_world_mps.allFinite() || !std::isfinite(out.yaw_rate_radps)) {
        out.events.push_back({.type = control::MissionEventType::kCommandReplaced,
                              .t_s = t_s,
                              .from = tick.state,
                              .to = tick.state,
                              .reason = "the safety layer gave a non-finite command: hover"});
        out.v_world_mps.setZero();
        out.yaw_rate_radps = 0.0;
    }
    if (config_.wind_compensation) {
        const Eigen::Vector3d v_safe_world_mps = out.v_world_mps;
        out.v_world_mps = wind_observer_.command(v_safe_world_mps);
        out.wind_compensation_mps = out.v_world_mps - v_safe_world_mps;
    }
    return out;
}

void DroneStack::coast(double t_s, bool operator_acted, control::MissionState state_before,
                       control::MissionTick& tick) {
    if (!imu_watchdog_.lost()) {
        coast_over_ = false;
    } else if (!coast_over_) {
        const double lost_for_s = imu_watchdog_.age_s(t_s) - config_.max_imu_age_s;
        coast_over_ =
            operator_acted || tick.state != state_before || lost_for_s >= config_.imu_coast_s;
        if (!coast_over_) {
            tick.v_cmd_world_mps = last_v_cmd_world_mps_;
            tick.yaw_rate_cmd_radps = last_yaw_rate_cmd_radps_;
        }
    }
    last_v_cmd_world_mps_ = tick.v_cmd_world_mps;
    last_yaw_rate_cmd_radps_ = tick.yaw_rate_cmd_radps;
}

Eigen::Vector3d DroneStack::apply_safety(const Eigen::Vector3d& v_world_mps, double t_s,
                                         StackCommand& out) const {
    const bool fresh =
        latest_sweep_stamp_s_ && t_s - *latest_sweep_stamp_s_ <= config_.max_sweep_age_s;
    // No obstacle data: no motion at all once the LiDAR has been lost (before its first sweep
    // the vehicle is on the ground and the manager commands nothing).
    if (!fresh) {
        const bool blocked =
            lidar_watchdog_.lost() && config_.collision_prevention && config_.lidar_expected;
        return blocked ? Eigen::Vector3d::Zero() : v_world_mps;
    }
    const Eigen::Matrix3d R_world_body = global_.state().T_odom_body.linear();
    Eigen::Vector3d v = v_world_mps;
    if (config_.collision_prevention) {
        out.collision = safety::prevent_collision(R_world_body.transpose() * v, latest_obstacles_,
                                                  config_.collision);
        v = R_world_body * out.collision->v_cmd_body_mps;
    }
    if (config_.height_keeping) {
        v.z() = safety::keep_height(v.z(), latest_clearance_, config_.height).v_z_cmd_mps;
    }
    return v;
}

}  // namespace scantling::mission
