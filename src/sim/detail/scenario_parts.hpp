#pragma once
// Private parts of the scenario runner: the vehicle history and the sensors it drives.
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <scantling/core/random.hpp>
#include <scantling/core/surface_projector.hpp>
#include <scantling/sim/motion_state.hpp>
#include <scantling/sim/recording_writer.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/sensor_mount.hpp>
#include <scantling/sim/sensor_reading.hpp>

namespace scantling::sim::detail {

/// Vehicle states at ticks 0 .. num_ticks − 1 (t = k · dt), with pose interpolation between.
class VehicleHistory {
  public:
    VehicleHistory(std::vector<MotionState> states, double dt_s)
        : states_(std::move(states)), dt_s_(dt_s) {}
    /// The state of the next tick (the closed loop's vehicle grows its history as it goes).
    void append(const MotionState& state) { states_.push_back(state); }
    const MotionState& last() const { return states_.back(); }
    const MotionState& at_tick(std::int64_t k) const {
        return states_[static_cast<std::size_t>(k)];
    }
    std::int64_t num_ticks() const { return static_cast<std::int64_t>(states_.size()); }
    /// Pose at any time, interpolated between ticks, clamped to the first and last tick.
    Eigen::Isometry3d pose_at(double t_s) const;

  private:
    std::vector<MotionState> states_;
    double dt_s_;
};

/// Simulates the vehicle of `spec` for `num_ticks` ticks of `dt_s` (seeded by `rng`); a
/// crawler drives on the surface of `world` (built from `world_spec`).
VehicleHistory simulate_vehicle(const VehicleSpec& spec, const WorldSpec& world_spec,
                                const World& world, double dt_s, std::int64_t num_ticks, Rng& rng);

/// The surface a crawler drives on (scenario.hpp, VehicleType::kCrawler).
std::unique_ptr<SurfaceProjector> crawler_surface(const WorldSpec& spec, const World& world);

/// Crawler states at the ticks: pursuit of the trajectory projected on `surface`.
std::vector<MotionState> crawler_states(const VehicleSpec& spec, const Trajectory& trajectory,
                                        const SurfaceProjector& surface, double dt_s,
                                        std::int64_t num_ticks, Rng& rng);

/// What a sensor needs when it fires.
struct FireContext {
    const SceneView& scene;
    const VehicleHistory& vehicle;
    std::int64_t tick;  ///< the tick at or after the stamp (motion sensors sample its state)
    double stamp_s;     ///< nominal firing time
    const ParallelConfig& parallel;
};

/// A scheduled sensor of the scenario: returns its data, never writes it.
class ScenarioSensor {
  public:
    virtual ~ScenarioSensor() = default;
    virtual double rate_hz() const = 0;
    /// How far past its stamp the sensor needs the vehicle's motion: a motion-distorted sweep
    /// is cast along its whole revolution, so it can only fire once that has been simulated.
    virtual double lookahead_s() const { return 0.0; }
    virtual SensorData fire(const FireContext& context) = 0;
};

/// Random streams of a scenario run: Rng(seed).split(k) (scenario_runner.hpp).
inline constexpr std::uint64_t kVehicleStream = 0;
inline constexpr std::uint64_t kFirstSensorStream = 1;  ///< sensor i draws from 1 + i
inline constexpr std::uint64_t kMapStream = 100;

using ScenarioSensors = std::vector<std::unique_ptr<ScenarioSensor>>;

/// The sensors of `scenario` in order, each on its stream of `root`. Throws ConfigError naming
/// "sensors[i]" for a bad sensor or a motion sensor faster than the clock (it samples the
/// tick's state: at most once per tick).
ScenarioSensors make_scenario_sensors(const Scenario& scenario, const Rng& root);

/// The sensor of `spec`, drawing from `rng` (ConfigError for a bad preset or parameter).
std::unique_ptr<ScenarioSensor> make_sensor(const SensorSpec& spec, Rng rng,
                                            const std::string& prefix);
/// Sonar, rosette LiDAR and stereo (scenario_sensors_extra.cpp); other types go on to
/// make_ranging_sensor.
std::unique_ptr<ScenarioSensor> make_imaging_sensor(const SensorSpec& spec, Rng rng,
                                                    const std::string& prefix);
/// Range finder, UWB, pressure, DVL, wheel odometry (scenario_sensors_ranging.cpp).
std::unique_ptr<ScenarioSensor> make_ranging_sensor(const SensorSpec& spec, Rng rng,
                                                    const std::string& prefix);

}  // namespace scantling::sim::detail
