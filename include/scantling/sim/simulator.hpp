#pragma once
/// @file
/// The steppable simulator of the closed loop (issue 13, item 0): the world, the vehicle and
/// the sensors of a scenario, advanced one clock tick at a time under the robot's command.
///
/// Each `step(command)` holds the command over one tick of `dt_s`, moves the vehicle with its
/// dynamics (a MAV or an ROV: mav_dynamics.hpp, rov_dynamics.hpp; its wind and currents
/// included), and returns the ground truth at the new tick and every reading due there, as
/// the same types the scenario runner hands to the RecordingWriter (sensor_reading.hpp). Due
/// times follow SimClock exactly as in run_scenario; a sensor that needs motion past its stamp
/// (a motion-distorted sweep, ScenarioSensor::lookahead_s) is delivered at the first tick that
/// covers its whole revolution, still stamped at its start, as a LiDAR driver publishes a
/// sweep once it is complete. `start()` returns the readings of tick 0 (t = 0) and must come
/// first.
///
/// Moving obstacles (scenario.moving_obstacles) move on their own clock-time paths whatever the
/// vehicle does; each firing sees them where they are at its stamp (sensor_mount.hpp).
///
/// The scenario's trajectory is not flown: only its start pose is used (the robot's own
/// controllers decide the motion). Scripted, legged and crawler vehicles are refused (their
/// motion is not a velocity command to a free body).
///
/// Determinism: the vehicle and each sensor draw from the streams run_scenario uses
/// (Rng(seed).split(k)), so the same scenario, seed and command sequence give the same
/// readings bit for bit, for any thread count. Not thread-safe; one simulator per run.
/// Memory: the vehicle's history is kept (a few hundred bytes per tick: 24 MB for 10 min at
/// 200 Hz) so that frames and interpolated poses can be produced at any stamp.

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <vector>

#include <scantling/core/surface_projector.hpp>
#include <scantling/sim/motion_state.hpp>
#include <scantling/sim/moving_obstacles.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/sensor_mount.hpp>
#include <scantling/sim/sensor_reading.hpp>
#include <scantling/sim/world.hpp>

namespace scantling::sim {

/// The robot's command to the simulated vehicle. A MAV takes a world-frame velocity and a yaw
/// rate about world z; an ROV receives the same rotated into its yawed body frame. A crawler
/// (on its surface) takes `forward_mps` along its heading and `yaw_rate_radps` about the
/// surface normal, and ignores `v_world_mps`: its wheels know only their own frame.
struct VehicleCommand {
    Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();
    double yaw_rate_radps = 0.0;
    double forward_mps = 0.0;  ///< crawler only
};

/// What one tick produced.
struct SimStep {
    MotionState truth;                                         ///< the vehicle at the tick
    Eigen::Vector3d wind_world_mps = Eigen::Vector3d::Zero();  ///< acting over the next step
    std::vector<SensorReading> readings;  ///< in stamp order, then sensor order
};

/// The surface a crawler of `scenario` drives on, as a robot's map of it: the plate's plane,
/// the cylinder's or the storage tank's shell (analytic), otherwise the world mesh (`world`
/// must then outlive the result).
std::unique_ptr<SurfaceProjector> crawler_surface(const Scenario& scenario, const World& world);

class Simulator {
  public:
    /// Builds the world and the sensors of `scenario` (validated: ConfigError) and puts the
    /// vehicle at rest at `T_world_body_start` (a crawler: projected onto its surface, the
    /// world's plate, cylinder, tank wall or mesh). Throws ConfigError for a scripted or legged
    /// vehicle, InputError for a non-finite start.
    Simulator(const Scenario& scenario, const Eigen::Isometry3d& T_world_body_start);
    ~Simulator();
    Simulator(const Simulator&) = delete;
    Simulator& operator=(const Simulator&) = delete;

    /// The readings of tick 0. Call once, before step (LogicError otherwise).
    SimStep start();
    /// One tick under `command` (InputError when it is not finite: the vehicle is never given
    /// a NaN). Throws LogicError before start().
    SimStep step(const VehicleCommand& command);

    double now_s() const;
    double dt_s() const;
    std::int64_t tick() const;
    const MotionState& truth() const;
    const World& world() const;
    /// The world as the sensors see it, with the moving obstacles placed at now_s().
    const SceneView& scene() const;
    const Scenario& scenario() const;
    /// The scenario's moving obstacles (validated), e.g. for the true distance from the
    /// vehicle to one at any time: `moving_obstacles()[i].distance_m(p_world, t_s)`.
    const MovingObstacles& moving_obstacles() const;
    /// Sensor i's nominal rate, Hz (as in summary.json).
    double sensor_rate_hz(std::size_t i) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace scantling::sim
