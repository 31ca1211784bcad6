// Vehicle histories for the scenario runner (detail/scenario_parts.hpp).
#include <algorithm>
#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/sim/legged_base.hpp>
#include <scantling/sim/mav_dynamics.hpp>
#include <scantling/sim/rov_dynamics.hpp>

#include "detail/scenario_parts.hpp"

namespace scantling::sim::detail {
namespace {

double yaw_of(const Eigen::Isometry3d& T_world_body) {
    const Eigen::Matrix3d R = T_world_body.rotation();
    return std::atan2(R(1, 0), R(0, 0));
}

std::vector<MotionState> scripted_states(const Trajectory& trajectory, double dt_s,
                                         std::int64_t num_ticks) {
    std::vector<MotionState> states;
    states.reserve(static_cast<std::size_t>(num_ticks));
    for (std::int64_t k = 0; k < num_ticks; ++k) {
        states.push_back(trajectory.at(static_cast<double>(k) * dt_s));
    }
    return states;
}

/// Feed-forward plus proportional tracking of the reference (scenario_runner.hpp).
MavCommand tracking_command(const VehicleSpec& spec, const MotionState& reference,
                            const MotionState& state, double yaw_rad) {
    MavCommand command;
    command.v_world_mps =
        reference.v_world_mps + spec.position_gain_per_s * (reference.T_world_body.translation() -
                                                            state.T_world_body.translation());
    command.yaw_rate_radps =
        reference.omega_body_radps.z() +
        spec.yaw_gain_per_s * wrap_angle(yaw_of(reference.T_world_body) - yaw_rad);
    return command;
}

std::vector<MotionState> mav_states(const VehicleSpec& spec, const Trajectory& trajectory,
                                    double dt_s, std::int64_t num_ticks, Rng& rng) {
    MavDynamicsConfig config = spec.mav;
    config.dt_s = dt_s;
    MavDynamics mav(config, trajectory.at(0.0).T_world_body, rng.next_u64());
    std::vector<MotionState> states{mav.state()};
    states.reserve(static_cast<std::size_t>(num_ticks));
    for (std::int64_t k = 1; k < num_ticks; ++k) {
        // The command acts over the step ending at tick k, aiming at the reference there.
        const MotionState reference = trajectory.at(static_cast<double>(k) * dt_s);
        states.push_back(mav.step(tracking_command(spec, reference, mav.state(), mav.yaw_rad())));
        states.back().stamp_s = static_cast<double>(k) * dt_s;  // no accumulated rounding
    }
    return states;
}

/// World-frame velocity command of the tracking loop, rotated into the yawed body frame.
Eigen::Vector3d body_velocity_command(const VehicleSpec& spec, const MotionState& reference,
                                      const MotionState& state, double yaw_rad) {
    const Eigen::Vector3d v_world = tracking_command(spec, reference, state, yaw_rad).v_world_mps;
    return Eigen::AngleAxisd(-yaw_rad, Eigen::Vector3d::UnitZ()) * v_world;
}

std::vector<MotionState> rov_states(const VehicleSpec& spec, const Trajectory& trajectory,
                                    double dt_s, std::int64_t num_ticks, Rng& rng) {
    RovDynamicsConfig config = spec.rov;
    config.dt_s = dt_s;
    RovDynamics rov(config, trajectory.at(0.0).T_world_body, rng.next_u64());
    std::vector<MotionState> states{rov.state()};
    states.reserve(static_cast<std::size_t>(num_ticks));
    for (std::int64_t k = 1; k < num_ticks; ++k) {
        const MotionState reference = trajectory.at(static_cast<double>(k) * dt_s);
        const Eigen::Vector3d v =
            body_velocity_command(spec, reference, rov.state(), rov.yaw_rad());
        const double yaw_rate =
            tracking_command(spec, reference, rov.state(), rov.yaw_rad()).yaw_rate_radps;
        states.push_back(rov.step(RovCommand{v.x(), v.y(), v.z(), yaw_rate}));
        states.back().stamp_s = static_cast<double>(k) * dt_s;
    }
    return states;
}

std::vector<MotionState> legged_states(const VehicleSpec& spec, const Trajectory& trajectory,
                                       double dt_s, std::int64_t num_ticks) {
    LeggedBaseConfig config = spec.legged;
    config.dt_s = dt_s;
    LeggedBase legged(config, trajectory.at(0.0).T_world_body);
    std::vector<MotionState> states{legged.state()};
    states.reserve(static_cast<std::size_t>(num_ticks));
    for (std::int64_t k = 1; k < num_ticks; ++k) {
        const MotionState reference = trajectory.at(static_cast<double>(k) * dt_s);
        const double yaw = legged.yaw_rad();
        const Eigen::Vector3d v = body_velocity_command(spec, reference, legged.state(), yaw);
        const double yaw_rate =
            tracking_command(spec, reference, legged.state(), yaw).yaw_rate_radps;
        states.push_back(legged.step(LeggedCommand{v.x(), v.y(), yaw_rate}));
        states.back().stamp_s = static_cast<double>(k) * dt_s;
    }
    return states;
}

}  // namespace

Eigen::Isometry3d VehicleHistory::pose_at(double t_s) const {
    const double position = std::clamp(t_s / dt_s_, 0.0, static_cast<double>(states_.size() - 1));
    const auto k = static_cast<std::size_t>(std::floor(position));
    if (k + 1 >= states_.size()) return states_.back().T_world_body;
    return interpolate(states_[k].T_world_body, states_[k + 1].T_world_body,
                       position - static_cast<double>(k));
}

VehicleHistory simulate_vehicle(const VehicleSpec& spec, const WorldSpec& world_spec,
                                const World& world, double dt_s, std::int64_t num_ticks, Rng& rng) {
    const std::unique_ptr<Trajectory> trajectory = make_trajectory(spec.trajectory);
    switch (spec.type) {
        case VehicleType::kScripted:
            return VehicleHistory(scripted_states(*trajectory, dt_s, num_ticks), dt_s);
        case VehicleType::kMav:
            return VehicleHistory(mav_states(spec, *trajectory, dt_s, num_ticks, rng), dt_s);
        case VehicleType::kRov:
            return VehicleHistory(rov_states(spec, *trajectory, dt_s, num_ticks, rng), dt_s);
        case VehicleType::kLegged:
            return VehicleHistory(legged_states(spec, *trajectory, dt_s, num_ticks), dt_s);
        case VehicleType::kCrawler: {
            const std::unique_ptr<SurfaceProjector> surface = crawler_surface(world_spec, world);
            return VehicleHistory(crawler_states(spec, *trajectory, *surface, dt_s, num_ticks, rng),
                                  dt_s);
        }
    }
    throw ConfigError("vehicle.type: unknown value");
}

}  // namespace scantling::sim::detail
