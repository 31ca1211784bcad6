// The crawler of a scenario: its surface and a pursuit of the projected trajectory
// (detail/scenario_parts.hpp).
#include <algorithm>
#include <cmath>

#include <scantling/sim/crawler_dynamics.hpp>

#include "detail/scenario_parts.hpp"

namespace scantling::sim::detail {
namespace {

/// The pursuit aims this far ahead along the trajectory: long enough to smooth the corners of a
/// lawnmower, short enough to keep the path (0.5 s at 0.3 m/s is 15 cm).
constexpr double kLookahead_s = 0.5;

Eigen::Vector3d initial_heading(const Trajectory& trajectory) {
    const Eigen::Vector3d ahead = trajectory.at(kLookahead_s).T_world_body.translation() -
                                  trajectory.at(0.0).T_world_body.translation();
    if (ahead.norm() > 1e-6) return ahead;
    return trajectory.at(0.0).T_world_body.linear().col(0);
}

/// Steers towards the projected reference ahead; drives at the reference speed plus a
/// correction of the along-track error, slowed down while the aim is off the heading.
CrawlerCommand pursuit(const VehicleSpec& spec, const SurfaceProjector& surface,
                       const Trajectory& trajectory, const MotionState& state, double t_s) {
    const MotionState reference = trajectory.at(t_s);
    const Eigen::Vector3d aim =
        surface.project(trajectory.at(t_s + kLookahead_s).T_world_body.translation()).point;
    const Eigen::Vector3d p_ref = surface.project(reference.T_world_body.translation()).point;
    const Eigen::Isometry3d& T = state.T_world_body;
    const Eigen::Vector3d to_aim = T.linear().transpose() * (aim - T.translation());
    const Eigen::Vector3d to_ref = T.linear().transpose() * (p_ref - T.translation());
    const double bearing =
        to_aim.head<2>().norm() > 1e-4 ? std::atan2(to_aim.y(), to_aim.x()) : 0.0;
    const double speed =
        reference.v_world_mps.norm() + spec.position_gain_per_s * std::max(to_ref.x(), 0.0);
    return CrawlerCommand{.v_mps = speed * std::max(std::cos(bearing), 0.0),
                          .yaw_rate_radps = spec.yaw_gain_per_s * bearing};
}

}  // namespace

std::unique_ptr<SurfaceProjector> crawler_surface(const WorldSpec& spec, const World& world) {
    switch (spec.type) {
        case WorldType::kPlate:
            // The facets' own normals: a box's smoothed vertex normals would tilt a stiffener's
            // narrow faces by tens of degrees.
            if (spec.plate.crawler_on_mesh) return std::make_unique<MeshSurface>(world.mesh, false);
            // Bounded: a crawler stops at the plate's edge instead of driving on into the air
            // (the plate's through-holes are not part of it).
            return std::make_unique<PlateSurface>(
                Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                0.5 * spec.plate.length_m, 0.5 * spec.plate.width_m);
        case WorldType::kCylinder:
            return std::make_unique<CylinderSurface>(
                Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), spec.cylinder.radius_m);
        case WorldType::kStorageTank:
            return std::make_unique<CylinderSurface>(Eigen::Vector3d::Zero(),
                                                     Eigen::Vector3d::UnitZ(),
                                                     0.5 * spec.storage_tank.diameter_m);
        default:
            return std::make_unique<MeshSurface>(world.mesh);
    }
}

std::vector<MotionState> crawler_states(const VehicleSpec& spec, const Trajectory& trajectory,
                                        const SurfaceProjector& surface, double dt_s,
                                        std::int64_t num_ticks, Rng& rng) {
    CrawlerDynamicsConfig config = spec.crawler;
    config.dt_s = dt_s;
    Eigen::Isometry3d T_start = Eigen::Isometry3d::Identity();
    T_start.translation() = trajectory.at(0.0).T_world_body.translation();
    // The crawler settles on the surface keeping only column 0 (its heading).
    T_start.linear().col(0) = initial_heading(trajectory).normalized();
    CrawlerDynamics crawler(config, surface, T_start, rng.next_u64());
    std::vector<MotionState> states{crawler.state()};
    states.reserve(static_cast<std::size_t>(num_ticks));
    for (std::int64_t k = 1; k < num_ticks; ++k) {
        // The command acts over the step ending at tick k, aiming at the reference there.
        const double t_s = static_cast<double>(k) * dt_s;
        states.push_back(crawler.step(pursuit(spec, surface, trajectory, crawler.state(), t_s)));
        states.back().stamp_s = static_cast<double>(k) * dt_s;
    }
    return states;
}

}  // namespace scantling::sim::detail
