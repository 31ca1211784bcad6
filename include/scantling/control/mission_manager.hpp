#pragma once
/// @file
/// The MAV's high-level mission manager (SPEC §4 "layered control ... high level mission
/// manager"; D5.2 §II.1 supervised autonomy): flies one waypoint mission and obeys the
/// operator. A plain object: per tick it takes the state estimate and the time, applies the
/// operator's commands of that tick, and returns a velocity command plus what happened (state
/// changes with their reason, waypoints reached, refused commands). It never sees a simulator,
/// a sensor or the collision prevention: the caller passes the command through the safety layer
/// (safety/collision_prevention.hpp), in every state, the operator's included.
///
/// States and what each commands:
///   kIdle       not started: zero velocity
///   kRunning    flying the mission: WaypointSequencer (VTP follower) + PositionController
///   kPaused     hovering in place: the controller holds the position where it paused
///   kOperator   taken over: the operator's velocity (clamped to the controller's limits) passes
///   kGoingHome  flying straight to home (+ the height offset), the VTP following that leg
///   kCompleted  the mission (or the home leg) done: holding at its last waypoint
///   kAborted    stopped for good: holding where it aborted
///   kFailsafe   the estimate was invalid for estimate_timeout_s: zero velocity, for good
///
/// Commands (a command that does not apply is refused with an event naming why, never thrown):
///   state ＼ cmd | start    pause    resume   take_over  hand_back  go_home    abort
///   kIdle        | Running  -        -        Operator   -          -          Aborted
///   kRunning     | -        Paused   -        Operator   -          GoingHome  Aborted
///   kPaused      | -        -        (from)   Operator   -          GoingHome  Aborted
///   kOperator    | -        -        -        (new vel.) (from)     GoingHome  Aborted
///   kGoingHome   | -        Paused   -        Operator   -          -          Aborted
///   kCompleted   | -        -        -        Operator   -          GoingHome  Aborted
///   kAborted     | -        -        -        Operator   -          GoingHome  -
///   kFailsafe    | -        -        -        Operator   -          -          -
/// "(from)": resume returns to the state it paused from (kRunning or kGoingHome); hand back
/// returns to the state it was taken from, except that a pause becomes kRunning (hand back
/// resumes the mission from the current waypoint). `start` records home = the position then.
///
/// Resume and hand back keep the sequencer's segment: the VTP segment still runs from the
/// original WP_prev to the current waypoint, so the follower first pulls the vehicle back onto
/// the intended path (VTP case 2: VTP = C) rather than flying a new straight line from wherever
/// it stopped or was flown to. The controller's PIDs are reset at every state change: their
/// integrals and derivative histories belong to the previous target and time step.
///
/// Estimate: an estimate not `valid` or with a non-finite field is ignored; while it lasts
/// (and the operator has not taken over) the command is zero velocity (hover), or, when the
/// estimate is `holdable` and finite, the position hold at the point where it became invalid;
/// once it has lasted estimate_timeout_s the manager enters kFailsafe (which holds likewise). The
/// command is checked last: a non-finite one is replaced by zero with a kCommandReplaced event, so
/// no NaN ever leaves. The first tick has no time step: it commands zero velocity whatever the
/// state.
///
/// Frames: world (z up; metres, m/s, radians); the yaw rate is about world z.
/// Thread-safety: mutable; one instance per vehicle, ticked from one thread. Cost: O(1) per
/// tick plus the events. Deterministic.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/control/position_controller.hpp>
#include <scantling/control/waypoint_sequencer.hpp>
#include <scantling/planning/waypoints.hpp>

namespace scantling::control {

/// Defaults: the position controller's and the follower's own; the rest chosen (SPEC gives none).
struct MissionManagerConfig {
    PositionControllerConfig position_controller{};  ///< gains and the 1 m/s speed limit
    TrackingConfig tracking{};                       ///< follower on, δ 2 m, λ 0.2 m
    /// How long an invalid estimate is tolerated before the failsafe, s (≥ 0). Five periods of
    /// 10 Hz LiDAR odometry: one late or rejected sweep does not end a mission, while the
    /// vehicle, commanded to zero, coasts ≤ τ · 1 m/s = 0.3 m meanwhile.
    double estimate_timeout_s = 0.5;
    /// Go-home target = home + this along world z, m (≥ 0): hover above the take-off point (the
    /// landing is the low level's). 0: home itself.
    double home_height_offset_m = 0.0;
    double home_tolerance_m = planning::kDefaultWaypointToleranceM;  ///< WP_tol of home, > 0

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "mission_manager") const;
};

enum class MissionState {
    kIdle,
    kRunning,
    kPaused,
    kOperator,
    kGoingHome,
    kCompleted,
    kAborted,
    kFailsafe,
};

enum class OperatorCommandType { kStart, kPause, kResume, kTakeOver, kHandBack, kGoHome, kAbort };

/// One operator command; the velocity only matters for kTakeOver.
struct OperatorCommand {
    OperatorCommandType type = OperatorCommandType::kPause;
    Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();  ///< take-over velocity, world
    double yaw_rate_radps = 0.0;                            ///< take-over yaw rate, world z
};

/// The state estimate of one tick.
struct EstimatedState {
    Eigen::Vector3d p_world_m = Eigen::Vector3d::Zero();
    double yaw_rad = 0.0;  ///< about world z
    Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();
    bool valid = true;  ///< the estimator's own verdict (e.g. localisation lost)
    /// Invalid as an absolute position, yet its motion over seconds is still good (the IMU
    /// runs; only the world position's uncertainty grew): the manager then holds the position
    /// where the estimate became invalid, on it, instead of commanding zero velocity, which
    /// in wind is a drift downwind (0.54 m/s in 5 m/s with the simulator's drag).
    bool holdable = false;
};

enum class MissionEventType {
    kStateChanged,     ///< from → to, with the reason
    kWaypointReached,  ///< waypoint_index of the mission (or of the home leg: home_leg)
    kCommandRefused,   ///< command, with why
    kEstimateInvalid,  ///< the first tick of an invalid estimate (hovering from now on)
    kCommandReplaced,  ///< a non-finite command was replaced by zero
    // Raised by the stack around the manager (mission/drone_stack.hpp), not by the manager:
    kSensorLost,      ///< `sensor` has been silent for longer than its maximum age
    kSensorRestored,  ///< `sensor` delivers again
    kInputRejected,   ///< a non-finite sample of `sensor` was dropped before the estimators
};

struct MissionEvent {
    MissionEventType type = MissionEventType::kStateChanged;
    double t_s = 0.0;
    MissionState from = MissionState::kIdle;  ///< the state before the tick's change
    MissionState to = MissionState::kIdle;    ///< the state after it
    std::optional<std::size_t> waypoint_index{};
    bool home_leg = false;  ///< the waypoint reached is home's
    std::optional<OperatorCommandType> command{};
    std::string reason{};
    std::string sensor{};  ///< the input stream of the sensor events ("imu", "lidar", ...)
};

/// What one tick produced.
struct MissionTick {
    Eigen::Vector3d v_cmd_world_mps = Eigen::Vector3d::Zero();
    double yaw_rate_cmd_radps = 0.0;  ///< about world z
    MissionState state = MissionState::kIdle;
    std::vector<MissionEvent> events;
};

class MissionManager {
  public:
    /// Validates the config and the path (ConfigError).
    explicit MissionManager(planning::WaypointPath path, const MissionManagerConfig& config = {});

    /// One tick at time `t_s` (strictly increasing; InputError otherwise, or non-finite):
    /// applies `commands` in order, then commands the vehicle.
    MissionTick update(const EstimatedState& estimate, double t_s,
                       std::span<const OperatorCommand> commands = {});

    MissionState state() const { return state_; }
    /// The home recorded at `start`, if started.
    const std::optional<Eigen::Vector3d>& home_world_m() const { return home_world_m_; }
    /// The mission's current waypoint index (== size when all are reached).
    std::size_t current_waypoint() const;
    const MissionManagerConfig& config() const { return config_; }

  private:
    void apply(const OperatorCommand& command, MissionTick& tick);
    MissionEvent event(MissionEventType type, std::string reason) const;  // at t_s_, in state_
    void refuse(OperatorCommandType command, std::string reason, MissionTick& tick) const;
    void change_state(MissionState to, std::string reason, MissionTick& tick);
    void start(MissionTick& tick);
    void pause(MissionTick& tick);
    void resume(MissionTick& tick);
    void take_over(const OperatorCommand& command, MissionTick& tick);
    void hand_back(MissionTick& tick);
    void go_home(MissionTick& tick);
    void abort(MissionTick& tick);
    bool track_estimate(const EstimatedState& estimate, MissionTick& tick);
    void command_vehicle(const EstimatedState& estimate, double dt_s, MissionTick& tick);
    void fly_sequence(const EstimatedState& estimate, double dt_s, MissionTick& tick);
    void hold(const EstimatedState& estimate, const Eigen::Vector3d& p_hold_world_m, double dt_s,
              MissionTick& tick);
    void report_reached(const std::vector<std::size_t>& reached, MissionTick& tick) const;
    void replace_non_finite(MissionTick& tick) const;
    WaypointSequencer* active_sequencer();

    MissionManagerConfig config_;
    planning::WaypointPath path_;
    std::optional<WaypointSequencer> mission_;  // from `start` (its WP_prev is home)
    std::optional<WaypointSequencer> home_leg_;
    PositionController controller_;
    MissionState state_ = MissionState::kIdle;
    MissionState paused_from_ = MissionState::kRunning;
    MissionState taken_from_ = MissionState::kIdle;
    OperatorCommand operator_command_;
    std::optional<Eigen::Vector3d> home_world_m_;
    std::optional<Eigen::Vector3d> last_valid_p_world_m_;
    Eigen::Vector3d p_hold_world_m_ = Eigen::Vector3d::Zero();
    std::optional<double> last_t_s_;
    std::optional<double> invalid_since_t_s_;
    /// Where an invalid but holdable estimate holds the vehicle (EstimatedState::holdable).
    std::optional<Eigen::Vector3d> p_invalid_hold_world_m_;
    double t_s_ = 0.0;
};

std::string_view to_string(MissionState state);
std::string_view to_string(OperatorCommandType command);
std::string_view to_string(MissionEventType type);

}  // namespace scantling::control
