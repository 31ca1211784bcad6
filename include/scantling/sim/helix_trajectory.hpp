#pragma once
/// @file
/// Circular motions around a vertical axis: the orbit of SPEC §4 (circular inspection around
/// an isolated structure) and the helix baseline of SPEC §9 (UAV 3D reconstruction).
///
/// Orbit: θ(t) = θ0 + ω t,  p(t) = c + r (cos θ, sin θ, 0) + (0, 0, v_z t),
/// yaw facing the centre (ψ = θ + π + offset) or the direction of travel (ψ = θ ± π/2 +
/// offset). The motion starts and ends at full speed (no ramps): velocity, acceleration and
/// yaw rate are constant in magnitude and exact derivatives of the pose.
///
/// Helix (SPEC §9, verbatim): x = −r cos(ωt) + x0, y = r sin(ωt) + y0, z = v_z t + z0,
/// ψ = −ωt + ψ0. It is the orbit with θ0 = π, angular rate −ω, facing the centre (ψ0 = 0 faces
/// the centre).
///
/// Thread-safety and determinism: see trajectory.hpp. `at` is O(1).

#include <Eigen/Core>
#include <string_view>

#include <scantling/sim/trajectory.hpp>

namespace scantling::sim {

enum class OrbitHeading { kFaceCentre, kFaceTravel };

struct OrbitTrajectoryConfig {
    Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();  ///< axis point at the start height
    double radius_m = 2.0;
    double angular_rate_radps = 0.25;  ///< ω; > 0 counter-clockwise seen from above
    double start_angle_rad = 0.0;      ///< θ0: start position = c + r (cos θ0, sin θ0, 0)
    double climb_rate_mps = 0.0;       ///< v_z (0: a flat circle)
    double turns = 1.0;                ///< duration = 2π turns / |ω|
    OrbitHeading heading = OrbitHeading::kFaceCentre;
    double yaw_offset_rad = 0.0;  ///< added to the heading (e.g. a camera looking sideways)

    /// Throws ConfigError naming the field ("orbit_trajectory.radius_m = 0, expected > 0").
    void validate(std::string_view prefix = "orbit_trajectory") const;
};

class OrbitTrajectory : public Trajectory {
  public:
    explicit OrbitTrajectory(const OrbitTrajectoryConfig& config);

    MotionState at(double t_s) const override;
    double duration_s() const override { return duration_s_; }
    const OrbitTrajectoryConfig& config() const { return config_; }

  private:
    OrbitTrajectoryConfig config_;
    double duration_s_ = 0.0;
};

/// SPEC §9 helix parameters (defaults: the reported ω = 0.25 rad/s, r = 2 m, 5 rotations).
struct HelixTrajectoryConfig {
    double x0_m = 0.0;  ///< helix axis x
    double y0_m = 0.0;  ///< helix axis y
    double z0_m = 0.0;  ///< start height
    double radius_m = 2.0;
    double omega_radps = 0.25;  ///< ω (> 0 turns clockwise seen from above, as in SPEC §9)
    double v_z_mps = 0.025;     ///< climb rate (3 m in 5 rotations at ω = 0.25 rad/s)
    double yaw0_rad = 0.0;      ///< ψ0
    double rotations = 5.0;     ///< duration = 2π rotations / ω

    /// Throws ConfigError naming the field ("helix_trajectory.omega_radps = 0, ...").
    void validate(std::string_view prefix = "helix_trajectory") const;
};

class HelixTrajectory : public Trajectory {
  public:
    explicit HelixTrajectory(const HelixTrajectoryConfig& config);

    MotionState at(double t_s) const override { return orbit_.at(t_s); }
    double duration_s() const override { return orbit_.duration_s(); }
    const HelixTrajectoryConfig& config() const { return config_; }

  private:
    HelixTrajectoryConfig config_;
    OrbitTrajectory orbit_;
};

}  // namespace scantling::sim
