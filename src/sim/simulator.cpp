// The steppable simulator of the closed loop (simulator.hpp).
#include <scantling/sim/simulator.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include <scantling/core/error.hpp>
#include <scantling/sim/crawler_dynamics.hpp>
#include <scantling/sim/mav_dynamics.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/rov_dynamics.hpp>
#include <scantling/sim/sim_clock.hpp>

#include "detail/scenario_parts.hpp"

namespace scantling::sim {
namespace {

constexpr double kStampTolerance_s = 1e-9;

/// A firing whose sensor needs motion past its stamp (ScenarioSensor::lookahead_s).
struct PendingFiring {
    std::size_t sensor = 0;
    std::int64_t tick = 0;
    double stamp_s = 0.0;
    double ready_s = 0.0;  ///< the firing is cast once the clock reaches this
};

/// MAV or ROV under a world-frame velocity command, or a crawler on its surface.
class Vehicle {
  public:
    Vehicle(const Scenario& scenario, const World& world,
            const Eigen::Isometry3d& T_world_body_start, std::uint64_t seed) {
        const VehicleSpec& spec = scenario.vehicle;
        if (spec.type == VehicleType::kMav) {
            MavDynamicsConfig config = spec.mav;
            config.dt_s = scenario.dt_s;
            mav_.emplace(config, T_world_body_start, seed);
        } else if (spec.type == VehicleType::kRov) {
            RovDynamicsConfig config = spec.rov;
            config.dt_s = scenario.dt_s;
            rov_.emplace(config, T_world_body_start, seed);
        } else if (spec.type == VehicleType::kCrawler) {
            CrawlerDynamicsConfig config = spec.crawler;
            config.dt_s = scenario.dt_s;
            surface_ = detail::crawler_surface(scenario.world, world);
            crawler_.emplace(config, *surface_, T_world_body_start, seed);
        } else {
            throw ConfigError(
                "vehicle.type: expected mav, rov or crawler in the closed loop (scripted and "
                "legged vehicles do not follow commands)");
        }
    }

    MotionState step(const VehicleCommand& command) {
        if (mav_) return mav_->step(MavCommand{command.v_world_mps, command.yaw_rate_radps});
        if (crawler_) {
            return crawler_->step(CrawlerCommand{.v_mps = command.forward_mps,
                                                 .yaw_rate_radps = command.yaw_rate_radps});
        }
        // The ROV takes surge, sway, heave in its yawed frame.
        const Eigen::Vector3d v =
            Eigen::AngleAxisd(-rov_->yaw_rad(), Eigen::Vector3d::UnitZ()) * command.v_world_mps;
        return rov_->step(RovCommand{v.x(), v.y(), v.z(), command.yaw_rate_radps});
    }

    const MotionState& state() const {
        if (mav_) return mav_->state();
        return crawler_ ? crawler_->state() : rov_->state();
    }
    Eigen::Vector3d wind_world_mps() const {
        return mav_ ? mav_->wind_world_mps() : Eigen::Vector3d::Zero();
    }

  private:
    std::optional<MavDynamics> mav_;
    std::optional<RovDynamics> rov_;
    std::unique_ptr<SurfaceProjector> surface_;  ///< the crawler's, outlives it
    std::optional<CrawlerDynamics> crawler_;
};

}  // namespace

std::unique_ptr<SurfaceProjector> crawler_surface(const Scenario& scenario, const World& world) {
    return detail::crawler_surface(scenario.world, world);
}

struct Simulator::Impl {
    Scenario scenario;
    Rng root;
    detail::ScenarioSensors sensors;
    World world;
    RayCaster caster;
    MovingObstacles obstacles;
    SceneView scene;  ///< obstacles at the current tick's time
    Vehicle vehicle;
    detail::VehicleHistory history;
    SimClock clock;
    std::vector<PendingFiring> pending;
    bool started = false;

    Impl(const Scenario& s, const Eigen::Isometry3d& T_world_body_start)
        : scenario(validated(s)),
          root(scenario.seed),
          sensors(detail::make_scenario_sensors(scenario, root)),
          world(build_world(scenario.world, scenario.base_directory)),
          caster(world.mesh, world.surface_tags),
          obstacles(scenario.moving_obstacles),
          scene{caster, world.metadata, &obstacles, 0.0},
          vehicle(scenario, world, checked_start(T_world_body_start),
                  root.split(detail::kVehicleStream).next_u64()),
          history({vehicle.state()}, scenario.dt_s),
          clock(scenario.dt_s) {
        for (const auto& sensor : sensors) {
            clock.add(RateSchedule{.rate_hz = sensor->rate_hz(), .phase_s = 0.0});
        }
    }

    static const Scenario& validated(const Scenario& s) {
        s.validate();
        return s;
    }

    static const Eigen::Isometry3d& checked_start(const Eigen::Isometry3d& T) {
        if (!T.matrix().allFinite()) throw InputError("simulator: the start pose is not finite");
        return T;
    }

    /// Queues the firings due at the current tick and casts every queued one that is ready.
    SimStep readings_now() {
        const std::int64_t k = clock.tick();
        for (const std::size_t i : clock.due_now()) {
            const double stamp_s = clock.last_fire_time_s(i);
            pending.push_back({i, k, stamp_s, stamp_s + sensors[i]->lookahead_s()});
        }
        SimStep step{
            .truth = history.last(), .wind_world_mps = vehicle.wind_world_mps(), .readings = {}};
        const double now_s = clock.now_s();
        const auto ready = [now_s](const PendingFiring& f) {
            return f.ready_s <= now_s + kStampTolerance_s;
        };
        for (const PendingFiring& firing : pending) {
            if (ready(firing)) step.readings.push_back(fire(firing));
        }
        std::erase_if(pending, ready);
        return step;
    }

    SensorReading fire(const PendingFiring& f) {
        // Obstacles frozen at the stamp for the whole firing (sensor_mount.hpp, SceneView).
        const SceneView scene_at_stamp = scene.at_time(f.stamp_s);
        const detail::FireContext context{scene_at_stamp, history, f.tick, f.stamp_s,
                                          scenario.parallel};
        return {.sensor_index = f.sensor,
                .stamp_s = f.stamp_s,
                .data = sensors[f.sensor]->fire(context)};
    }
};

Simulator::Simulator(const Scenario& scenario, const Eigen::Isometry3d& T_world_body_start)
    : impl_(std::make_unique<Impl>(scenario, T_world_body_start)) {}

Simulator::~Simulator() = default;

SimStep Simulator::start() {
    if (impl_->started) throw InputError("simulator: start() called twice");
    impl_->started = true;
    return impl_->readings_now();
}

SimStep Simulator::step(const VehicleCommand& command) {
    if (!impl_->started) throw InputError("simulator: step() before start()");
    if (!command.v_world_mps.allFinite() || !std::isfinite(command.yaw_rate_radps) ||
        !std::isfinite(command.forward_mps)) {
        throw InputError(fmt::format("simulator: command at t = {:.3f} s is not finite", now_s()));
    }
    MotionState state = impl_->vehicle.step(command);
    impl_->clock.advance();
    state.stamp_s = impl_->clock.now_s();  // from the tick count: no accumulated rounding
    impl_->history.append(state);
    impl_->scene.time_s = state.stamp_s;
    return impl_->readings_now();
}

double Simulator::now_s() const { return impl_->clock.now_s(); }
double Simulator::dt_s() const { return impl_->clock.dt_s(); }
std::int64_t Simulator::tick() const { return impl_->clock.tick(); }
const MotionState& Simulator::truth() const { return impl_->history.last(); }
const World& Simulator::world() const { return impl_->world; }
const SceneView& Simulator::scene() const { return impl_->scene; }
const Scenario& Simulator::scenario() const { return impl_->scenario; }
const MovingObstacles& Simulator::moving_obstacles() const { return impl_->obstacles; }
double Simulator::sensor_rate_hz(std::size_t i) const { return impl_->sensors.at(i)->rate_hz(); }

}  // namespace scantling::sim
