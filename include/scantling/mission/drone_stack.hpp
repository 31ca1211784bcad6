#pragma once
/// @file
/// The drone's autonomy stack as one plain object (issue 13; SPEC §3, §4): what runs on the
/// robot, fed with the same io/core types a recording gives and returning the velocity command
/// for the vehicle. It never sees the simulator: the closed loop (closed_loop.hpp) feeds it
/// from `sim`, a ROS node would feed it from topics, a replay from a recording.
///
/// Pipeline per measurement:
///   IMU        → local EKF prediction (local_ekf.hpp), then the global EKF's prediction;
///   LiDAR      → LiODOM (odometry/liodom.hpp) predicted by the global estimate's motion between
///                sweeps (so a direction the hull leaves unobserved keeps the IMU's motion),
///                its pose increment fused into the local EKF with the registration's
///                information (JᵀWJ / odometry_sigma_m², taken to the body frame), and the
///                sweep kept for the safety layer;
///   range      → local EKF height above the floor; barometer → local EKF altitude;
///   UWB        → global EKF (global_ekf.hpp).
/// Inputs are screened first: a sample with a non-finite value (or a sweep without one finite
/// point) is dropped with an input_rejected event (once per episode of bad samples), so the
/// estimators, which throw on such input, never see it.
/// Stream watchdogs (safety/stream_watchdog.hpp) turn silence into events and a safe reaction:
///   IMU silent > max_imu_age_s    → the estimate is invalid (it is no longer propagated): the
///                                   vehicle coasts on the last command for imu_coast_s (what
///                                   the estimate assumes), then the manager's hover applies;
///                                   it fails safe after the manager's timeout;
///   LiDAR silent > max_sweep_age_s → with collision prevention on, the vehicle holds: the
///                                   stack pauses a running mission (resumed when sweeps come
///                                   back, unless the operator acted meanwhile) and blocks
///                                   any other motion, as PX4 does without obstacle data.
/// Per command tick: the global estimate → mission manager (control/mission_manager.hpp:
/// VTP follower and position PIDs) → collision prevention and height keeping on the latest
/// sweep (safety/, in the body frame of the estimate; the sweep's nearby points and vertical
/// clearances are gathered once when it arrives, safety/obstacle_points.hpp) → wind
/// compensation (the disturbance observer, fed with the estimate's velocity while the
/// estimate is valid; its last wind is held while it is not) → command. A command
/// is never NaN: the manager replaces one with a hover, and so does this stack (with an event)
/// after the safety layer.
///
/// Frames: world (the mission's), odom (the local EKF's: the levelled start pose), body.
/// Thread-safety: not thread-safe; one stack per vehicle. Deterministic for a given input
/// sequence (LiODOM runs single-threaded inside the loop).

#include <Eigen/Geometry>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <scantling/control/disturbance_observer.hpp>
#include <scantling/control/mission_manager.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/localization/global_ekf.hpp>
#include <scantling/localization/local_ekf.hpp>
#include <scantling/odometry/liodom.hpp>
#include <scantling/planning/waypoints.hpp>
#include <scantling/safety/collision_prevention.hpp>
#include <scantling/safety/height_keeping.hpp>
#include <scantling/safety/obstacle_points.hpp>
#include <scantling/safety/stream_watchdog.hpp>

namespace scantling::mission {

/// LiODOM as the drone flies it: the os1_drone preset with every direction weaker than 5 % of
/// the strongest treated as degenerate. In the loop LiODOM always has the EKF's motion as its
/// prior, so along such a direction (motion parallel to a prismatic hull: ratio ≈ 1e-3, where
/// the preset's 1e-3 test misses it) the sweep keeps the IMU's motion and reports no
/// information, instead of holding the estimate in place with centimetre confidence
/// (docs/results.md, "Closed-loop hull-side sweep"). The preset's tight convergence (0.1 mm,
/// 0.01 mrad) and a refit of every line at every iteration are kept although they cost the
/// loop its speed: along the hull the pose slides by less than a millimetre per iteration, and
/// only fully converged registrations with fresh correspondences recover the weak information
/// there. With 0.5 mm / 0.05 mrad and a 1 cm refit distance the loop runs 5.8× real time with
/// the same error while UWB holds the estimate, but without UWB the estimate ran away by
/// 350–980 m instead of 6–17 m (docs/benchmarks.md, "Closed loop"). Those overrides remain
/// available (stack.odometry.registration) for a site with absolute positioning.
odometry::LiodomConfig drone_odometry_defaults();

struct DroneStackConfig {
    odometry::LiodomConfig odometry = drone_odometry_defaults();  ///< YAML: stack.odometry
    /// Point-to-line noise that turns LiODOM's JᵀWJ (unit noise) into 1/m², m, > 0. Larger
    /// than the LiDAR's range noise (≈ 3 cm): neighbouring residuals share the map's errors.
    double odometry_sigma_m = 0.1;
    /// Floor of one increment's uncertainty, m, > 0: thousands of residuals make JᵀWJ claim
    /// millimetres per sweep, but the map's own errors repeat from sweep to sweep. Applied to
    /// the information's eigenvalues with rotations taken at `odometry_lever_m` metres per
    /// radian: 3 cm and 2 mrad per sweep. Measured on `make run` (docs/results.md): 1 cm / 2 mrad
    /// let a sweep sliding along the hull hold the estimate (0.150 m RMS, yaw 6.4°; 9 m with
    /// the degeneracy test below); 3 cm / 6 mrad 0.082 m but yaw 3.6°; 3 cm / 2 mrad 0.096 m,
    /// yaw 0.9°, NEES 2.6.
    double odometry_min_sigma_m = 0.03;
    double odometry_lever_m = 15.0;  ///< m per rad when comparing rotations with translations
    localization::LocalEkfConfig local_ekf{};
    /// 1σ of one barometer sample, m, > 0 (a flight controller's filtered altitude: 0.1 m of
    /// noise plus the propellers' downwash).
    double barometer_sigma_m = 0.3;
    localization::GlobalEkfConfig global_ekf{};
    bool collision_prevention = true;  ///< SPEC §3 on the latest sweep
    safety::CollisionPreventionConfig collision{};
    bool height_keeping = true;
    safety::HeightKeepingConfig height{};
    /// A sweep older than this gives the safety layer no data, s, > 0; the LiDAR is then lost
    /// (three periods of a 10 Hz LiDAR whose sweep arrives one period after its stamp).
    double max_sweep_age_s = 0.3;
    /// The IMU is lost (the estimate invalid) after this long without a sample, s, > 0: the
    /// local EKF's own gap threshold (10 periods at 200 Hz).
    double max_imu_age_s = 0.05;
    /// For this long after the IMU is lost, s, ≥ 0, the vehicle keeps the last command
    /// (coasts) instead of hovering at once. The local EKF predicts a gap on its last sample:
    /// the motion the last command holds. A brake inside the gap is motion it never sees, and
    /// along the hull nothing local corrects the velocity afterwards: after a 0.2 s gap with
    /// an immediate hover the estimate left by 2.6-9.5 m (seeds 1-6), coasting 0.07-0.09 m RMS
    /// (docs/results.md). 0.3 s is 0.3 m of blind flight at 1 m/s, inside collision
    /// prevention's d_min, which still acts on the last sweep. An operator command ends it.
    double imu_coast_s = 0.3;
    /// The vehicle carries the LiDAR (set from the sensors by a mission scenario): only then
    /// does its silence pause the mission and block motion.
    bool lidar_expected = true;
    /// The estimate is declared invalid when its horizontal position σ exceeds this, m, > 0.
    double max_position_sigma_m = 2.0;
    control::MissionManagerConfig manager{};
    /// Wind compensation under the safety layer (control/disturbance_observer.hpp): the
    /// vehicle flies the velocity the safety layer let through, whatever the wind. Off, the
    /// position PIDs' integral alone learns the wind from the position error it lets grow.
    bool wind_compensation = true;
    control::DisturbanceObserverConfig wind{};                       ///< YAML: stack.wind
    Eigen::Isometry3d T_body_lidar = Eigen::Isometry3d::Identity();  ///< LiDAR mount

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "stack") const;
};

/// What the stack did with a command tick (for the recording and the dashboard).
struct StackCommand {
    Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();  ///< to the vehicle
    double yaw_rate_radps = 0.0;
    Eigen::Vector3d v_requested_world_mps = Eigen::Vector3d::Zero();  ///< the manager's
    bool limited = false;  ///< the safety layer changed the request
    /// What the wind compensation added to the safety layer's output (v_world_mps includes it).
    Eigen::Vector3d wind_compensation_mps = Eigen::Vector3d::Zero();
    std::optional<safety::CollisionPreventionResult> collision;
    control::MissionState state = control::MissionState::kIdle;
    std::vector<control::MissionEvent> events;
};

class DroneStack {
  public:
    /// `T_world_body_start`: where the robot starts (its odom frame is this pose, levelled).
    /// ConfigError for a bad config or path, InputError for a non-finite start.
    DroneStack(DroneStackConfig config, planning::WaypointPath path,
               const Eigen::Isometry3d& T_world_body_start, double start_s = 0.0);

    void add_imu(const io::ImuRecord& sample);
    /// A sweep in the LiDAR frame, stamped at its start. Returns LiODOM's report, or nothing
    /// for a rejected sweep (no finite point, non-finite stamp).
    std::optional<odometry::FrameReport> add_sweep(const PointCloud& sweep_lidar, double stamp_s);
    void add_range(const io::RangeRecord& range);
    void add_barometer(const io::BarometerRecord& altitude);
    void add_uwb(const io::UwbRecord& range);

    /// The command at `t_s` after applying the operator's commands.
    StackCommand command(double t_s, std::span<const control::OperatorCommand> operator_commands);

    /// The world estimate (global EKF output) at the last IMU sample.
    localization::DroneState estimate() const { return global_.state(); }
    bool estimate_valid() const;
    const localization::LocalEkf& local_ekf() const { return local_; }
    const localization::GlobalEkf& global_ekf() const { return global_; }
    const control::MissionManager& manager() const { return manager_; }
    const DroneStackConfig& config() const { return config_; }

    /// Samples dropped by the input screening, all sensors.
    std::size_t inputs_rejected() const { return inputs_rejected_; }

  private:
    /// Counts a rejected sample; the first of an episode becomes an event.
    void reject(const std::string& sensor, double stamp_s);
    void accept(const std::string& sensor);
    /// Watchdog transitions at `t_s` as events, and the operator commands the stack adds (the
    /// LiDAR's pause and resume).
    void watch_streams(double t_s, std::vector<control::OperatorCommand>& commands);
    std::optional<Eigen::Isometry3d> odometry_prior(double t0_s, double t1_s) const;
    /// The local EKF's current pose carried into the world by the global EKF's T_world_odom
    /// (the global state itself lags: it has not seen the local filter's latest update).
    Eigen::Isometry3d local_pose_in_world() const;
    void fuse_increment(const odometry::FrameReport& report, double stamp_s);
    /// Replaces the manager's command by the last one while the IMU's silence is within
    /// imu_coast_s and nothing else changed (no operator command, the same state).
    void coast(double t_s, bool operator_acted, control::MissionState state_before,
               control::MissionTick& tick);
    Eigen::Vector3d apply_safety(const Eigen::Vector3d& v_world_mps, double t_s,
                                 StackCommand& out) const;

    DroneStackConfig config_;
    Eigen::Isometry3d T_world_odom_start_;
    localization::LocalEkf local_;
    localization::GlobalEkf global_;
    odometry::LidarOdometry odometry_;
    control::MissionManager manager_;
    control::DisturbanceObserver wind_observer_;
    /// LiODOM's pose at the previous registered sweep, and the global estimate of the body pose
    /// there.
    std::optional<Eigen::Isometry3d> T_lodom_lidar_previous_;
    std::optional<double> previous_sweep_stamp_s_;
    Eigen::Isometry3d T_world_body_previous_sweep_ = Eigen::Isometry3d::Identity();
    /// The safety layer's view of the latest sweep, gathered once when it arrives (the
    /// commands outpace the sweeps): the points that can attenuate or repel, and the
    /// clearances above and below.
    safety::ObstaclePoints latest_obstacles_;
    safety::VerticalClearance latest_clearance_;
    std::optional<double> latest_sweep_stamp_s_;
    safety::StreamWatchdog imu_watchdog_;
    safety::StreamWatchdog lidar_watchdog_;
    bool lidar_paused_ = false;  ///< the stack paused the mission for the LiDAR
    /// The command of the previous tick (what a coast holds), and whether this loss of the IMU
    /// has stopped coasting (the coast ended or was broken).
    Eigen::Vector3d last_v_cmd_world_mps_ = Eigen::Vector3d::Zero();
    double last_yaw_rate_cmd_radps_ = 0.0;
    bool coast_over_ = false;
    std::vector<std::string> rejecting_;  ///< sensors inside an episode of rejected samples
    std::size_t inputs_rejected_ = 0;
    std::vector<control::MissionEvent> pending_events_;  ///< returned by the next command
};

}  // namespace scantling::mission
