#pragma once
/// @file
/// Magnetic crawler: a unicycle (forward speed v, turn rate ω about the surface normal)
/// constrained to a surface, with wheel slip (SPEC §6, §10).
///
/// Body frame: x forward (heading, tangent to the surface), z the surface normal (into free
/// space), y = z × x (left). Per step of dt:
/// 1. the wheel speed and turn rate follow the (clipped) command with a first-order lag;
/// 2. slip: the body moves at v_b = (v̄ (1 − s_long), |v̄| s_lat, 0) and turns at
///    ω̄ (1 + s_yaw), where v̄, ω̄ are the wheels' mean over the step and (s_long, s_lat, s_yaw)
///    a seeded GustProcess (mean slip + Ornstein–Uhlenbeck variation);
/// 3. the position moves along the midpoint heading, then is projected onto the surface;
///    body z becomes the surface normal there and body x the turned heading with its normal
///    component removed (parallel transport), so the crawler never leaves the surface.
/// The wheel (encoder) motion is exposed separately for wheel odometry: it excludes slip.
///
/// State semantics: pose at `stamp_s` on the surface; velocity = body-frame slip velocity
/// rotated to the world (tangent to the surface); acceleration and angular rate = means over
/// the step that ended at `stamp_s` (mav_dynamics.hpp). Integrating them reproduces the pose
/// to O(dt² · curvature) (the surface projection is not an integral of the velocity).
/// Determinism: same config, surface, seed, start and commands give bit-identical states.
/// Thread-safety: mutable; one per vehicle. Cost: one `SurfaceProjector::project` per step.

#include <Eigen/Geometry>
#include <cstdint>
#include <string_view>

#include <scantling/core/surface_projector.hpp>
#include <scantling/sim/disturbance.hpp>
#include <scantling/sim/motion_state.hpp>

namespace scantling::sim {

struct CrawlerDynamicsConfig {
    double dt_s = 0.01;                     ///< fixed step (100 Hz)
    double velocity_time_constant_s = 0.1;  ///< lag of the wheels (0: none)
    double max_speed_mps = 0.3;             ///< command clip, |v|
    double max_yaw_rate_radps = 0.5;        ///< command clip, |ω|
    double slip_mean = 0.02;                ///< mean longitudinal slip fraction
    double slip_sigma = 0.02;               ///< 1σ of the longitudinal slip fraction
    double lateral_slip_sigma = 0.01;       ///< 1σ of lateral speed / |forward speed|
    double yaw_slip_sigma = 0.03;           ///< 1σ of the relative turn-rate error
    double slip_correlation_time_s = 1.0;   ///< of the slip process

    /// Throws ConfigError naming the field ("crawler.slip_mean = 1.5, expected in [0, 1)").
    void validate(std::string_view prefix = "crawler") const;
};

struct CrawlerCommand {
    double v_mps = 0.0;           ///< forward, along body x
    double yaw_rate_radps = 0.0;  ///< about body z (the surface normal)
};

class CrawlerDynamics {
  public:
    /// Starts at rest at `T_world_body_start` projected onto `surface` (body z aligned with
    /// the normal, heading kept as far as possible). `surface` is not owned and must outlive
    /// this object. Throws ConfigError / InputError (non-finite start).
    CrawlerDynamics(const CrawlerDynamicsConfig& config, const SurfaceProjector& surface,
                    const Eigen::Isometry3d& T_world_body_start, std::uint64_t seed,
                    double start_s = 0.0);

    /// Advances one step of config().dt_s (InputError for a non-finite command).
    const MotionState& step(const CrawlerCommand& command);

    const MotionState& state() const { return state_; }
    /// Wheel (encoder) forward speed at `state().stamp_s`, without slip, m/s.
    double wheel_speed_mps() const { return wheel_v_mps_; }
    /// Turn rate the wheels command at `state().stamp_s`, without slip, rad/s.
    double wheel_yaw_rate_radps() const { return wheel_w_radps_; }
    /// Distance the wheels rolled since the start (signed), m.
    double wheel_distance_m() const { return wheel_distance_m_; }
    const CrawlerDynamicsConfig& config() const { return config_; }

  private:
    Eigen::Isometry3d settle(const Eigen::Vector3d& p, const Eigen::Vector3d& heading) const;
    Eigen::Vector3d slip_velocity_body(double wheel_v) const;

    CrawlerDynamicsConfig config_;
    const SurfaceProjector* surface_;
    GustProcess slip_;
    MotionState state_;
    double start_s_ = 0.0;
    double wheel_v_mps_ = 0.0;
    double wheel_w_radps_ = 0.0;
    double wheel_distance_m_ = 0.0;
    std::int64_t steps_ = 0;
};

}  // namespace scantling::sim
