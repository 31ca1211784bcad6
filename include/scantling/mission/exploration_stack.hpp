#pragma once
/// @file
/// The exploring drone's stack (issue 16 item 3; SPEC §8, thesis art. G) as one plain object:
/// fed with the io/core types a recording gives, it returns the velocity command. It never
/// sees the simulator (exploration_mission.hpp joins them).
///
/// Per measurement:
///   IMU          → local EKF prediction (local_ekf.hpp);
///   VIO          → the pose increment between consecutive valid samples, fused with a fixed
///                  per-increment noise (the tracking camera's drift: VIO's own covariance is
///                  that of its absolute, drifting pose); across a dropout, the increment from
///                  the last valid sample with its variance grown by the samples missed; and
///                  once a second its heading (the VIO's frame is the start's);
///   barometer    → the local EKF's altitude;
///   depth frame  → the occupancy octree (mapping/occupancy_octree.hpp) at the estimate of the
///                  frame's stamp, and kept for lifting defects;
///   camera image → each defect sighting lifted with the latest depth frame
///                  (localization/defect_lifting.hpp) into the defect map, whose defects are the
///                  defect-aware planner's interest points.
/// Per command tick, by phase:
///   take-off  → climb to takeoff_height_m above the start;
///   survey    → a full turn in place, so that the map holds the space around the vehicle;
///   explore   → at each goal reached (or none yet): the vehicle's own box is marked free (it
///                occupies it), the next-best-view planner grows its tree from the estimate,
///                and the first node of the best branch becomes the goal; the vehicle turns to
///                face along the straight edge, flies it (VTP follower on the edge, position
///                PIDs limited to max_speed_mps) and turns to the node's yaw at the goal, at
///                max_yaw_rate_radps;
///   done      → the planner found no gain left (or a start not in free space twice in a
///                row): hover; the mission is completed.
/// The operator's commands: pause (and go_home: the way home is the operator's) hover where
/// the vehicle is; resume and hand_back continue; take_over flies the operator's velocity;
/// abort hovers for good.
/// No plan is made without a recent depth frame: the vehicle hovers (sensor_lost), and the
/// exploration is aborted when the camera stays silent (depth_lost_abort_s).
/// Events: phase, state_changed, nbv_planned (nodes, gain, time), plan_failed, back_track,
/// sensor_lost, sensor_restored, input_rejected.
///
/// Frames: world (the mission's; the local EKF's odom frame is the start pose, levelled).
/// Thread-safety: not thread-safe; one stack per vehicle. Deterministic for a given input
/// sequence and config (the planner's seed).

#include <Eigen/Geometry>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <scantling/control/mission_manager.hpp>
#include <scantling/control/position_controller.hpp>
#include <scantling/control/vtp_follower.hpp>
#include <scantling/core/pinhole_intrinsics.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/localization/defect_lifting.hpp>
#include <scantling/localization/defect_map.hpp>
#include <scantling/localization/local_ekf.hpp>
#include <scantling/mapping/occupancy_octree.hpp>
#include <scantling/mission/stack_event.hpp>
#include <scantling/planning/nbv_planner.hpp>
#include <scantling/safety/collision_prevention.hpp>

namespace scantling::mission {

/// Table G.1 of the thesis (RESULTS-TO-REPRODUCE §4.6) where it speaks; the rest chosen.
struct ExplorationStackConfig {
    localization::LocalEkfConfig local_ekf{};
    /// 1σ of one VIO increment's translation, m, and rotation, rad (> 0). A tracking camera's
    /// poses carry white jitter (T265 class: 2 mm, 2 mrad per sample, sim/vio.hpp), so the
    /// increment between two samples carries √2 of it, plus the drift (1-2 % of the 8 mm
    /// flown between 30 Hz samples at 0.25 m/s). Measured on the test room (seed 4): 2 mm /
    /// 1 mrad claimed too much, the EKF's gate refused increments and the estimate left the VIO
    /// by 0.68 m (0.45 m RMS); 5 mm / 4 mrad held it at 0.10 m RMS.
    double vio_increment_sigma_m = 0.005;
    double vio_increment_sigma_rad = 0.004;
    /// The VIO's sample period, s, > 0: an increment spanning n periods (across a dropout)
    /// has n times the variance.
    double vio_period_s = 1.0 / 30.0;
    /// The VIO's heading is also fused as a heading in odom (its frame is the start's, as the
    /// local EKF's), at most once per this period, s, > 0, with the VIO's own yaw σ: the
    /// increments alone let the gyro's bias turn the estimate (−0.1 rad in 300 s in the large
    /// tank, 0.6 m of cross-track error) while the VIO's heading stayed within 0.01 rad.
    double vio_yaw_period_s = 1.0;
    double barometer_sigma_m = 0.3;  ///< 1σ of one barometer sample, m, > 0
    mapping::OccupancyOctreeConfig map{};
    planning::NbvPlannerConfig nbv{};
    /// The depth camera's mount (set from the simulated sensor by a mission scenario).
    Eigen::Isometry3d T_body_depth = Eigen::Isometry3d::Identity();
    /// The inspection camera's mount and intrinsics (set from the simulated sensor).
    Eigen::Isometry3d T_body_camera = Eigen::Isometry3d::Identity();
    PinholeIntrinsics camera{};
    localization::DefectLiftingConfig defects{};
    localization::DefectMapConfig defect_map{};
    double takeoff_height_m = 1.0;  ///< climb above the start before exploring, m, > 0
    /// Thesis table G.1: v_max 0.25 m/s, yaw rate 0.3 rad/s.
    double max_speed_mps = 0.25;
    double max_yaw_rate_radps = 0.3;
    double goal_tolerance_m = 0.15;   ///< a goal is reached within this distance, m, > 0
    double yaw_tolerance_rad = 0.15;  ///< ... and this heading error, rad, > 0
    control::PositionControllerConfig position_controller{};  ///< speed/yaw limits from above
    control::VtpConfig vtp{.max_vtp_distance_m = 0.5, .max_path_separation_m = 0.2};
    /// Mark the vehicle's box (grown by this margin, m, ≥ 0) free at every depth frame and
    /// before each plan: the space the vehicle occupies, and so all it has flown through, is
    /// free whatever the camera saw there.
    double self_clearance_m = 0.05;
    /// After the survey turn, the box around the take-off point grown by this, m, ≥ 0, is
    /// marked free: the operator put the vehicle in a clear spot, and the camera never sees the
    /// layers just above and below itself (min depth 0.25 m, ±27° vertically), so no edge
    /// could leave the start otherwise (NBVP's initial clearing, Bircher et al. 2016). 0.5 m:
    /// with 0.3 m the test room's first plan found no free edge (seeds 1-4).
    double takeoff_clearance_m = 0.5;
    /// A goal not reached within this long is given up and a new plan made, s, > 0.
    double goal_timeout_s = 60.0;
    /// SPEC §3's collision prevention under the guidance, on the depth frames of the last
    /// obstacle_memory_s (the camera sees only ahead; the frames taken while the vehicle
    /// turned keep the sides). Why: the map is built at the estimate, which drifts (0.4 m RMS
    /// over a 400 m exploration of the large tank): a plan in the map's free space can still
    /// run the true vehicle into a wall. The SPEC §3 defaults (d_min 0.8 m) are a LiDAR
    /// drone's in open holds; here d_min = the planner's box half-diagonal and clearance
    /// (0.45 m) and d_att 1 m, so that 1.2 m passages and 0.35 m wall stand-offs still pass,
    /// and v_max = max_speed_mps.
    bool collision_prevention = true;
    safety::CollisionPreventionConfig collision{
        .d_att_m = 1.0, .d_min_m = 0.45, .robot_radius_m = 0.35, .repulsion_gain_per_s = 1.0};
    double obstacle_memory_s = 3.0;  ///< > 0
    /// An edge is flown facing along it: farther off this heading, rad, in (0, π/2], the
    /// vehicle turns in place first (closer, its horizontal speed is scaled by the cosine).
    double max_travel_heading_error_rad = 0.5;
    /// No plan without a depth frame younger than this, s, > 0: the map would not see what the
    /// next edge flies into (the vehicle hovers, `sensor_lost`).
    double max_depth_age_s = 1.0;
    /// The exploration is aborted after the depth camera has been silent this long, s, > 0.
    double depth_lost_abort_s = 10.0;
    /// Exploration is done after this many plans in a row found no gain, >= 1. Each plan grows
    /// a new random tree; one tree of N_T = 30 nodes can miss the last gain behind an obstacle
    /// (the test room's seed 1 stopped at 85 % of the reachable volume after one).
    int exhausted_plans_to_finish = 3;
    /// The exploration stops after this many failed plans in a row (no free start or edge),
    /// >= 1; each failure first backs off to the previous plan's start (see back_track).
    int max_failed_plans = 10;
    /// After a plan without gain the next trees grow up to this many nodes, >= nbv.max_nodes
    /// (RH-NBVP's cutoff iterations, N_max, beside its initial N_T): a tree of 30 nodes with
    /// 2 m edges reaches a few metres, and in the large tank every compartment near the
    /// vehicle was mapped while the rest lay beyond the passages (40 % of the reachable volume
    /// when the planner gave up). The wide tree's plan is flown like any other, and the next
    /// plan is N_T's again.
    int max_nodes_when_exhausted = 300;

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "stack") const;
};

enum class ExplorationPhase { kTakeOff, kSurvey, kExplore, kDone };
const char* to_string(ExplorationPhase phase);
/// "ok", "exhausted", "start_not_free", "no_free_edge" (events and plans.csv).
const char* to_string(planning::NbvStatus status);

struct ExplorationCommand {
    Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();
    double yaw_rate_radps = 0.0;
    Eigen::Vector3d v_requested_world_mps = Eigen::Vector3d::Zero();  ///< the guidance's
    bool limited = false;  ///< the collision prevention changed the request
    control::MissionState state = control::MissionState::kIdle;
    std::vector<StackEvent> events;
};

/// One planning iteration, for the figures.
struct PlanRecord {
    double t_s = 0.0;
    double wall_s = 0.0;      ///< plan() wall time
    std::size_t nodes = 0;    ///< tree size
    double best_gain = 0.0;   ///< Q of the best node
    double first_gain = 0.0;  ///< E of the goal (first node of the best branch), m³
    planning::NbvStatus status = planning::NbvStatus::kOk;
    std::size_t gain_evaluations = 0;
};

class ExplorationStack {
  public:
    /// InputError for a non-finite start, ConfigError for a bad config.
    ExplorationStack(ExplorationStackConfig config, const Eigen::Isometry3d& T_world_body_start,
                     double start_s = 0.0);

    void add_imu(const io::ImuRecord& sample);
    void add_vio(const io::VioRecord& sample);
    void add_barometer(const io::BarometerRecord& altitude);
    /// An organised or unorganised depth frame in the depth camera's frame (NaN: no return).
    void add_depth(const PointCloud& frame_sensor, double stamp_s);
    /// The inspection camera's defect sightings of one image.
    void add_sightings(std::span<const io::DefectSighting> sightings, double stamp_s);

    ExplorationCommand command(double t_s,
                               std::span<const control::OperatorCommand> operator_commands);

    localization::DroneState estimate() const;  ///< in the world frame
    bool estimate_valid() const { return local_.initialized(); }
    ExplorationPhase phase() const { return phase_; }
    /// The planner found no gain left (exploration finished, not stopped for lack of a plan).
    bool no_gain_left() const { return no_gain_left_; }
    control::MissionState state() const { return state_; }
    const mapping::OccupancyOctree& map() const { return map_; }
    std::vector<localization::MappedDefect> defects() const { return defect_map_.defects(); }
    const std::vector<PlanRecord>& plans() const { return plans_; }
    /// The goals flown, in order (the exploration's path as planned).
    const std::vector<Eigen::Vector3d>& goals() const { return goals_; }
    std::size_t inputs_rejected() const { return inputs_rejected_; }
    const ExplorationStackConfig& config() const { return config_; }

  private:
    Eigen::Isometry3d T_world_body_estimate() const;
    void reject(const std::string& sensor, double stamp_s);
    void fuse_vio_yaw(const io::VioRecord& sample);
    void apply_operator(const control::OperatorCommand& command, double t_s);
    void set_phase(ExplorationPhase phase, double t_s, const std::string& reason);
    void set_state(control::MissionState state, double t_s, const std::string& reason);
    /// The command of the phase, from the estimate.
    void guide(double t_s, ExplorationCommand& out);
    void take_off(double t_s, ExplorationCommand& out);
    void survey(double t_s, ExplorationCommand& out);
    void explore(double t_s, ExplorationCommand& out);
    /// False (hovering, with the events) while the depth camera is silent.
    bool depth_fresh(double t_s);
    bool goal_reached(double t_s) const;
    void plan_next(double t_s);
    /// Keeps the latest depth frame (decimated) for the collision prevention.
    void remember_obstacles(double stamp_s);
    /// Marks the vehicle's box at the estimate, grown by `margin_m`, free in the map.
    void clear_vehicle_box(double margin_m);
    void on_plan(const planning::NbvPlan& plan, PlanRecord& record, double t_s);
    /// After a failed plan: back to the latest earlier plan's start, else hover here.
    void back_track(double t_s);
    std::vector<Eigen::Vector3d> interest_points() const;
    void fly_to_goal(double t_s, ExplorationCommand& out);
    void hold(double t_s, ExplorationCommand& out);
    /// `horizontal_scale` multiplies the controller's horizontal velocity (0 turns in place).
    void steer(const Eigen::Vector3d& target, std::optional<double> yaw, double t_s,
               ExplorationCommand& out, double horizontal_scale = 1.0);
    /// The velocity after collision prevention on the recent depth frames.
    Eigen::Vector3d safe_velocity(const Eigen::Vector3d& v_world_mps,
                                  ExplorationCommand& out) const;

    ExplorationStackConfig config_;
    Eigen::Isometry3d T_world_odom_;
    localization::LocalEkf local_;
    mapping::OccupancyOctree map_;
    planning::NbvPlanner planner_;
    planning::NbvPlanner wide_planner_;  ///< max_nodes_when_exhausted nodes
    control::PositionController controller_;
    localization::DefectMap defect_map_;
    std::optional<io::VioRecord> vio_previous_;
    std::optional<double> vio_yaw_stamp_s_;
    PointCloud latest_depth_world_;
    /// Recent depth frames, world frame, decimated: the collision prevention's obstacles.
    std::deque<std::pair<double, PointCloud>> recent_obstacles_world_;
    PointCloud near_obstacles_world_;  ///< of those, near the vehicle: what each tick checks
    std::optional<double> latest_depth_stamp_s_;
    bool depth_lost_ = false;
    ExplorationPhase phase_ = ExplorationPhase::kTakeOff;
    control::MissionState state_ = control::MissionState::kIdle;
    Eigen::Vector3d p_start_world_m_ = Eigen::Vector3d::Zero();
    Eigen::Vector3d p_hold_world_m_ = Eigen::Vector3d::Zero();
    double yaw_hold_rad_ = 0.0;
    std::optional<double> survey_start_yaw_rad_;
    double survey_turned_rad_ = 0.0;
    double survey_last_yaw_rad_ = 0.0;
    std::optional<Eigen::Vector3d> goal_world_m_;
    std::optional<double> goal_yaw_rad_;
    Eigen::Vector3d leg_start_world_m_ = Eigen::Vector3d::Zero();
    double goal_set_s_ = 0.0;
    double next_plan_s_ = 0.0;
    double explore_start_s_ = 0.0;  ///< no plan before this (after a failed one)
    Eigen::Vector3d operator_velocity_ = Eigen::Vector3d::Zero();
    std::optional<double> last_command_s_;
    int failed_plans_in_row_ = 0;
    int exhausted_plans_in_row_ = 0;
    bool no_gain_left_ = false;
    std::vector<PlanRecord> plans_;
    std::vector<Eigen::Vector3d> goals_;
    std::vector<Eigen::Vector3d> plan_roots_;  ///< where the successful plans started
    std::vector<std::string> rejecting_;
    std::size_t inputs_rejected_ = 0;
    std::vector<StackEvent> pending_events_;
};

}  // namespace scantling::mission
