#pragma once
/// @file
/// The magnetic crawler's autonomy stack as one plain object (issue 15; SPEC §6): fed with the
/// io types a recording gives (IMU, wheel odometry, UWB ranges), it returns the wheel command
/// (forward speed, turn rate about the surface normal). It never sees the simulator.
///
/// Pipeline:
///   IMU, wheels → the particle filter's prediction on the known surface
///                 (localization/surface_particle_filter.hpp); UWB → its update;
///   at the start the crawler stands still for gyro_calibration_s: the gyro's mean is its
///   bias, taken off every later sample;
///   per command tick: the PF pose → the segment follower (control/segment_follower.hpp) on
///   the current leg → command.
/// The mission is a list of tasks (planning/surface_tasks.hpp: go_to, rectangle, vertical and
/// horizontal transects, the three stiffener drives), each laid on the surface as legs when it
/// begins, from the estimate then. Every task but the corridor ones is laid once at
/// construction, chained from the start, so an invalid request is refused before the crawler
/// moves. A leg is done when the follower has passed its last segment: a `waypoint_reached`
/// event. A stiffener drive first stops to map (or uses the stop just made at its start): the
/// face corridor of the stop's cloud (perception/face_corridor.hpp) is its centre line. A task
/// that cannot be laid (no corridor found, a leg leaving the surface from where the crawler
/// is) raises `task_failed` and pauses: the operator's resume skips it, an abort ends the
/// mission. The mission completes after the last task (`task_started` / `task_done` events).
/// The operator may pause (stand still), resume, and abort (stand still for good). A sample
/// with a non-finite value is dropped before the filter with an `input_rejected` event (once
/// per episode); the wheels silent for longer than `max_wheel_age_s` stop the crawler (a
/// `sensor_lost` event; it goes on when they are back): without them the PF is blind to its
/// own motion. Anchors silent for max_uwb_age_s are a `sensor_lost` event (the filter
/// dead-reckons), and a position σ above max_position_sigma_m stops the crawler until it is
/// back (`estimate_invalid`). A command is never NaN.
///
/// Stop-and-map (SPEC §6; perception/stop_and_map.hpp), when a LiDAR is mounted: after every
/// stop_spacing_m driven on a leg (the estimate's path) and at every waypoint the crawler stands
/// still for stop_duration_s. stop_settle_s into the stop it captures the PF pose and starts
/// accumulating the LiDAR frames; at the end the stop's cloud is labelled, registered against
/// the previous stop's and its obstacles mapped: the command carries the StopMap and a
/// `stop_mapped` event. The stop-and-map's map pose is reported beside the PF's, not fed back
/// into the filter (docs/results.md compares both against the truth).
///
/// Texture map (SPEC §6; perception/texture_map.hpp), when enabled with a camera mounted: every
/// image is drawn on the live layer at the PF pose; a stop's images, at the stop's map pose with
/// its obstacle cells in red, replace the clean layer when the stop ends.
///
/// Frames: world; body x forward, z the surface normal. Thread-safety: not thread-safe, one
/// stack per vehicle. Deterministic for a seed and an input sequence.

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/control/mission_manager.hpp>
#include <scantling/control/segment_follower.hpp>
#include <scantling/core/surface_projector.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/localization/surface_particle_filter.hpp>
#include <scantling/mission/stack_event.hpp>
#include <scantling/perception/face_corridor.hpp>
#include <scantling/perception/stop_and_map.hpp>
#include <scantling/perception/texture_map.hpp>
#include <scantling/planning/detour.hpp>
#include <scantling/planning/surface_rectangle.hpp>
#include <scantling/planning/surface_tasks.hpp>

namespace scantling::mission {

/// The operators' texture map (perception/texture_map.hpp), YAML: texture_map.
struct CrawlerTextureConfig {
    bool enabled = false;  ///< needs a camera mounted (T_body_camera)
    perception::TextureMapConfig map{};
};

struct CrawlerStackConfig {
    localization::SurfaceParticleFilterConfig particle_filter{};  ///< YAML: stack.particle_filter
    control::SegmentFollowerConfig follower{};                    ///< YAML: stack.follower
    planning::SurfaceWalkConfig walk{};                           ///< YAML: stack.walk
    /// The wheels silent longer than this stop the crawler, s, > 0 (five periods at 50 Hz).
    double max_wheel_age_s = 0.1;
    /// Standing still this long after the start, s, >= 0 (0: off), the gyro's mean is its
    /// turn-on bias, subtracted from every later sample. A consumer MEMS gyro's is up to
    /// 0.5°/s, 30° of heading a minute, which the filter's heading diffusion cannot follow:
    /// measured on the tank rectangle, its heading otherwise left by 111° with a 0.005 rad/√s
    /// diffusion (docs/results.md).
    double gyro_calibration_s = 2.0;
    /// With UWB anchors configured, no valid range for this long is a `sensor_lost` event, s,
    /// > 0: the filter dead-reckons on the IMU and the wheels meanwhile (no anchor in range,
    /// the link down).
    double max_uwb_age_s = 2.0;
    /// The crawler stands still while the filter's position σ (√ of the covariance's trace)
    /// exceeds this, m, > 0, with an `estimate_invalid` event (`estimate_valid` when it is
    /// back): dead reckoning grows it by a few centimetres per metre driven.
    double max_position_sigma_m = 0.5;
    /// A range from an anchor more than this behind the surface's tangent plane at the estimate
    /// is dropped (a `uwb_anchor_hidden` event per anchor and episode), m, >= 0. Why: a magnetic
    /// crawler drives on steel, which UWB does not cross; the range of an anchor under a plate
    /// or beyond a tank's shell is the path around it, consistently long, which the filter's
    /// NLOS mixture takes for line of sight when every anchor is hidden (measured: four anchors
    /// under the 5 × 2 m plate gave 0.114 m RMS and no event). Exact on a plate and outside a
    /// convex shell; inside a tank every anchor is in front.
    double anchor_hidden_margin_m = 0.05;
    /// Obstacles mapped at the stops slow the crawler down in proportion to their distance ahead
    /// (SPEC §6: no swerving), from obstacle_slow_distance_m to a stop at
    /// obstacle_stop_distance_m, m (slow 0: off; stop >= 0, slow > stop), counting those whose
    /// footprint comes within corridor_half_width_m of the body's x axis, m, > 0.
    double obstacle_slow_distance_m = 0.5;
    double obstacle_stop_distance_m = 0.1;
    double corridor_half_width_m = 0.12;
    /// Stopped by an obstacle, the crawler replans the rest of its leg around it
    /// (planning/detour.hpp: on the side that stays on the surface and clear of every mapped
    /// obstacle, a `path_replanned` event); without a detour, or off, it pauses for the
    /// operator (SPEC §6: "replan a globally valid path or ask the operator").
    bool replan_around_obstacles = true;
    planning::DetourConfig detour{};  ///< YAML: stack.detour
    /// Stop-and-map (SPEC §6), with a LiDAR mounted (T_body_lidar): the crawler stops after
    /// every stop_spacing_m driven on a leg and at every waypoint, m, >= 0 (0: at waypoints only).
    double stop_spacing_m = 1.0;
    double stop_settle_s = 0.5;    ///< the pose is taken, and the accumulation starts, s, >= 0
    double stop_duration_s = 3.0;  ///< standing still in all, s, > stop_settle_s (SPEC: >= 3 s)
    perception::StopAndMapConfig stop_and_map{};  ///< YAML: stack.stop_and_map
    /// The LiDAR's mount (body ← LiDAR), from the calibration; none: no stop-and-map.
    std::optional<Eigen::Isometry3d> T_body_lidar;
    /// The stiffener drives' corridor, from a stop's cloud (YAML: stack.corridor).
    perception::FaceCorridorConfig corridor{};
    /// A stiffener drive joins the corridor's centre line this far ahead of the crawler's foot
    /// on it, m, >= 0: the follower converges on the way instead of turning on the spot.
    double corridor_join_m = 0.15;
    CrawlerTextureConfig texture{};
    /// The camera's mount (body ← optical frame), from the calibration; none: no texture map.
    std::optional<Eigen::Isometry3d> T_body_camera;

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "stack") const;
};

/// What the stack did with a command tick.
struct CrawlerStackCommand {
    double forward_mps = 0.0;
    double yaw_rate_radps = 0.0;
    control::MissionState state = control::MissionState::kIdle;
    std::size_t leg = 0;  ///< the leg followed (the number of legs laid once past them)
    /// The follower's error in the current segment (estimate, not truth).
    control::SegmentFrameError error;
    std::vector<StackEvent> events;
    std::optional<perception::StopMap> stop;  ///< a stop that ended this tick
};

class CrawlerStack {
  public:
    /// `surface`: the known surface the filter keeps its particles on and the tasks are laid
    /// on; `mesh`: its triangle mesh when it is one (go_to takes the geodesic), else null (both
    /// not owned, must outlive the stack). `tasks`: the mission, in order (at least one).
    /// ConfigError for a bad config; InputError naming "mission.tasks[i]" for a bad task, a
    /// stiffener drive without a LiDAR, or a task that leaves the surface.
    CrawlerStack(const CrawlerStackConfig& config, const SurfaceProjector& surface,
                 const TriangleMesh* mesh, std::vector<planning::SurfaceTask> tasks,
                 const Eigen::Isometry3d& T_world_body_start, std::uint64_t seed);

    void add_imu(const io::ImuRecord& sample);
    void add_wheel_odometry(const io::WheelOdometryRecord& sample);
    void add_uwb(const io::UwbRecord& range);
    /// A LiDAR frame (LiDAR frame): kept while a stop accumulates, otherwise ignored.
    void add_lidar_frame(const PointCloud& frame_lidar);
    /// A camera image: painted on the texture map's live layer at the PF pose, and staged for
    /// its clean layer while a stop accumulates. Ignored without a texture map.
    void add_image(const io::RgbImage& image, const PinholeIntrinsics& intrinsics);
    /// The texture map, when enabled and a camera is mounted.
    const perception::TextureMap* texture_map() const { return texture_ ? &*texture_ : nullptr; }
    /// True while a stop accumulates LiDAR frames (a recorder may keep only those).
    bool mapping() const { return mapper_ && mapper_->collecting(); }

    /// The command at `t_s` after the operator's commands (start, pause, resume, abort).
    CrawlerStackCommand command(double t_s,
                                std::span<const control::OperatorCommand> operator_commands);

    localization::SurfaceParticleEstimate estimate() const { return filter_.estimate(); }
    const localization::SurfaceParticleFilter& filter() const { return filter_; }
    /// Every leg laid so far, in order (the corridor tasks' once their stop is mapped; a leg
    /// replanned around an obstacle replaced).
    const std::vector<planning::TaskLeg>& legs() const { return legs_; }
    /// Grows whenever legs() changes (laid or replanned).
    std::size_t legs_revision() const { return legs_revision_; }
    /// Every leg's end, in order.
    const std::vector<Eigen::Vector3d>& waypoints() const { return waypoints_; }
    /// The rectangle tasks' transects and spacing (the first rectangle's), for the summary.
    std::size_t transects() const { return transects_; }
    double step_m() const { return step_m_; }
    control::MissionState state() const { return state_; }
    std::size_t inputs_rejected() const { return inputs_rejected_; }

  private:
    bool screen(bool finite, const std::string& sensor, double stamp_s);
    void apply(const control::OperatorCommand& command, double t_s,
               std::vector<StackEvent>& events);
    void change_state(control::MissionState to, const std::string& reason, double t_s,
                      std::vector<StackEvent>& events);
    void watch_wheels(double t_s, std::vector<StackEvent>& events);
    void watch_uwb(double t_s, std::vector<StackEvent>& events);
    /// True (with an event when it becomes so) when the range's anchor is behind the surface.
    bool anchor_hidden(const io::UwbRecord& range);
    /// False (with the events of a change) while the position σ is above the limit.
    bool estimate_usable(double t_s, std::vector<StackEvent>& events);
    void follow(CrawlerStackCommand& out, double t_s);
    /// Lays every task but the corridor ones, chained from the start (InputError if one fails).
    void check_tasks(const Eigen::Vector3d& p_start_world_m) const;
    /// Lays the next task's legs; false while none can be followed (a corridor task waits for
    /// its stop, the task failed, or the mission is complete).
    bool next_task(CrawlerStackCommand& out, double t_s);
    void add_plan(const planning::TaskPlan& plan);
    /// A corridor task's legs from the stop just made; false (task_failed) without a corridor.
    bool lay_corridor(double t_s, std::vector<StackEvent>& events);
    void fail_task(const std::string& reason, double t_s, std::vector<StackEvent>& events);
    /// The corridor of `cloud_body` for the current task, placed in the world at the newest
    /// estimate (the crawler stands still).
    perception::FaceCorridor corridor_of(const PointCloud& cloud_body,
                                         Eigen::Vector3d& origin_world,
                                         Eigen::Vector3d& direction_world) const;
    /// At a stop on a stiffener drive: the rest of its leg re-laid on the corridor measured
    /// now (a `corridor_remeasured` event).
    void remeasure_corridor(const perception::StopMap& stop, double t_s,
                            std::vector<StackEvent>& events);
    std::string task_name(std::size_t i) const;
    /// True while the start's gyro calibration runs (standing still); ends it when due.
    bool calibrating(double t_s, std::vector<StackEvent>& events);
    /// True while a stop-and-map stop holds the crawler; opens, feeds and closes the stops.
    bool stopped_to_map(CrawlerStackCommand& out, double t_s);
    /// Scales the command for the obstacles ahead; replans or pauses with an event when
    /// blocked.
    void slow_for_obstacles(CrawlerStackCommand& out, double t_s);
    /// True when the operator let the crawler pass where `o` was mapped.
    bool cleared(const perception::MappedObstacle& o) const;
    /// True (a `path_replanned` event) when the current leg was replanned around obstacle
    /// `blocking`; else `why` says why not.
    bool replan_around(std::size_t blocking, double t_s, std::vector<StackEvent>& events,
                       std::string& why);
    void count_distance();

    CrawlerStackConfig config_;
    localization::SurfaceParticleFilter filter_;
    const SurfaceProjector& surface_;
    const TriangleMesh* mesh_;
    std::vector<planning::SurfaceTask> tasks_;
    std::size_t task_ = 0;      ///< the next task to lay
    bool task_open_ = false;    ///< task_ - 1 is laid and not done yet
    bool task_failed_ = false;  ///< paused on task_failed: a resume skips it
    std::size_t tasks_skipped_ = 0;
    std::optional<std::size_t> corridor_leg_;  ///< the open stiffener drive's leg
    std::vector<planning::TaskLeg> legs_;
    std::size_t legs_revision_ = 0;
    std::vector<Eigen::Vector3d> waypoints_;
    std::size_t transects_ = 0;
    double step_m_ = 0.0;
    /// The last stop's cloud (body frame) while the crawler has not moved since and a
    /// stiffener drive is ahead: the drive's corridor is taken from it.
    std::optional<PointCloud> stop_cloud_here_;
    std::size_t leg_ = 0;
    std::optional<control::SegmentFollower> follower_;
    control::MissionState state_ = control::MissionState::kIdle;
    std::optional<double> last_wheel_s_;
    /// The gyro's turn-on bias (IMU frame), once calibrated; the running sum until then.
    std::optional<Eigen::Vector3d> gyro_bias_radps_;
    Eigen::Vector3d gyro_sum_radps_ = Eigen::Vector3d::Zero();
    std::size_t gyro_samples_ = 0;
    std::optional<double> started_s_;
    double start_s_ = 0.0;
    bool wheels_lost_ = false;
    std::optional<double> last_uwb_s_;
    bool uwb_lost_ = false;
    bool estimate_invalid_ = false;
    std::vector<std::string> rejecting_;
    std::size_t inputs_rejected_ = 0;
    std::vector<StackEvent> pending_;
    std::optional<perception::StopMapper> mapper_;
    std::optional<perception::TextureMap> texture_;
    std::optional<double> stop_began_s_;  ///< the open stop's start
    bool stop_due_ = false;               ///< a waypoint was reached: stop before going on
    std::vector<int> hidden_anchors_;     ///< anchors behind the surface now (event sent)
    /// Obstacles of the stops, and the one that paused the crawler, if any.
    std::vector<perception::MappedObstacle> obstacles_;
    std::optional<std::size_t> blocking_;
    /// Where the operator let the crawler go on: obstacles mapped there (at any stop) no
    /// longer count.
    std::vector<Eigen::Vector3d> cleared_world_m_;
    /// Obstacles the current leg was replanned around: they no longer slow the crawler while it
    /// passes them (its heading still points at them as it turns away); cleared with the leg.
    std::vector<Eigen::Vector3d> passing_world_m_;
    double driven_m_ = 0.0;  ///< estimated distance since the last stop
    std::optional<Eigen::Vector3d> last_p_;
};

}  // namespace scantling::mission
