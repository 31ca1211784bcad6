#pragma once
/// @file
/// The ROV's guidance during a hull survey (SPEC §5; D4.2 §III; issue 14 item 3): constant-
/// bearing guidance in the horizontal plane, depth by its own controller (the vertical
/// thruster), heading towards the hull, and the pause of the inspection motion while heading
/// or depth is off.
///
/// Constant bearing (Fossen, Handbook of Marine Craft Hydrodynamics and Motion Control, §10.1,
/// "manoeuvring-based" target tracking), horizontal components only:
///   p̃   = p − p_t                      position error to the target point
///   v_a = −κ p̃ / √(p̃ᵀp̃ + Δ²)          approach velocity: |v_a| < κ, smooth near the target
///   v_d = v_t + v_a                      then clamped to max_speed_mps
/// with v_t the target's own velocity (the survey speed along the path, zero while paused),
/// κ = max_approach_speed_mps and Δ = transient_m (larger: softer approach).
/// Depth: v_z = v_t,z + PID(z_t − z), the sum clamped to the PID's output range (the heave limit).
/// Heading: ψ̇ = clamp(k_ψ wrap(ψ_t − ψ)). Pause (SPEC: "if heading or depth error is too large,
/// pause the inspection motion until corrected"): entered when |ψ_t − ψ| > max_heading_error_rad or
/// |z_t − z| > max_depth_error_m; left when both are below resume_fraction × their bounds
/// (hysteresis, so an error at the bound does not toggle it every tick). While paused v_t is not
/// applied (the vehicle holds at the target point, which the caller stops advancing), and the
/// heading and depth loops keep correcting.
///
/// Frames: world, z up; yaw about z. Thread-safety: mutable state (PID, pause), one per vehicle.
/// Deterministic. Cost: O(1).

#include <Eigen/Core>
#include <numbers>
#include <string_view>

#include <scantling/control/pid.hpp>

namespace scantling::control {

struct RovGuidanceConfig {
    double max_approach_speed_mps = 0.4;  ///< κ, > 0
    double transient_m = 0.5;             ///< Δ, > 0
    double max_speed_mps = 0.5;           ///< clamp of the horizontal command, > 0
    double yaw_gain_per_s = 1.0;          ///< k_ψ, > 0
    double max_yaw_rate_radps = 0.5;      ///< > 0
    /// Depth loop: a PI on the depth error (m → m/s), clamped to ±0.3 m/s of heave.
    PidConfig depth{.kp = 0.8, .ki = 0.05, .output_min = -0.3, .output_max = 0.3};
    double max_heading_error_rad = 15.0 * std::numbers::pi / 180.0;  ///< pause above, > 0
    double max_depth_error_m = 0.3;                                  ///< pause above, > 0
    double resume_fraction = 0.5;  ///< resume below this share of both bounds, (0, 1]
    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "rov_guidance") const;
};

/// Where the vehicle should be now: a point moving along the survey path.
struct GuidanceTarget {
    Eigen::Vector3d p_world_m = Eigen::Vector3d::Zero();
    Eigen::Vector2d v_horizontal_mps = Eigen::Vector2d::Zero();  ///< the target's own velocity
    /// The target's vertical velocity, fed forward to the heave command (a vertical slice's
    /// descent: without it the PI lags a target moving at 0.25 m/s by 0.3 m, the pause bound).
    double v_vertical_mps = 0.0;
    double yaw_rad = 0.0;  ///< facing the hull
};

struct GuidanceCommand {
    Eigen::Vector3d v_world_mps = Eigen::Vector3d::Zero();
    double yaw_rate_radps = 0.0;
    bool paused = false;  ///< the inspection motion is paused (the caller holds the target)
    double heading_error_rad = 0.0;
    double depth_error_m = 0.0;  ///< z_t − z
};

class RovGuidance {
  public:
    /// Validates the config (ConfigError).
    explicit RovGuidance(const RovGuidanceConfig& config = {});

    /// One step, `dt_s` after the previous one. InputError for non-finite input or dt ≤ 0.
    GuidanceCommand update(const Eigen::Vector3d& p_world_m, double yaw_rad,
                           const GuidanceTarget& target, double dt_s);

    bool paused() const { return paused_; }
    void reset();
    const RovGuidanceConfig& config() const { return config_; }

  private:
    void update_pause(double heading_error_rad, double depth_error_m);
    Eigen::Vector2d horizontal(const Eigen::Vector3d& p_world_m,
                               const GuidanceTarget& target) const;

    RovGuidanceConfig config_;
    Pid depth_;
    bool paused_ = false;
};

}  // namespace scantling::control
