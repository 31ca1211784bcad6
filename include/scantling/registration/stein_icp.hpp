#pragma once
/// @file
/// Stein ICP (Maken et al.; SPEC §7): registration with a particle posterior over the pose.
///
/// Parametrisation: a particle is x = (x, y, z, roll, pitch, yaw) of `T_target_source`,
/// metres and radians, rotation `R = R_z(yaw) R_y(pitch) R_x(roll)` (core/se3.hpp). Euler
/// angles (not a rotation vector) so that the per-DoF KDE, the 3-DoF variant (x, y, yaw) and the
/// reported spreads read directly as the quantities a surveyor and the filters use. Angles are
/// kept wrapped to [−π, π]; means, differences and kernels treat them as circular. Pitch is
/// assumed to stay away from ±π/2 (gimbal lock), true for every robot in the SPEC.
///
/// Posterior: log p(x) = −Σᵢ rᵢ(x)² / (2σ²) over the N source points, σ = `noise_sigma_m`,
/// rᵢ the distance (point-to-point) or the normal distance (point-to-plane, used when the
/// target has normals) to the nearest target point, pairs beyond the correspondence distance
/// dropped. Each iteration estimates ∇log p per particle from a random batch of B points
/// (scaled by N/B), then moves every particle along the Stein variational gradient
///   φ(xᵢ) = (1/K) Σⱼ [k(xⱼ, xᵢ) ∇log p(xⱼ) + ∇ₓⱼ k(xⱼ, xᵢ)],
/// with k = exp(−|xⱼ − xᵢ|² / h) and h = median(|xⱼ − xᵢ|²) / log K, computed separately for
/// the translation block and for the rotation block (two kernels, two bandwidths), each block
/// stepped by Adam with its own learning rate, decayed geometrically over the iterations.
///
/// Adam normalises the step, so after those T iterations the particles' spread and their
/// distance from the optimum are set by the learning rates, not by the posterior (measured on
/// the ballast-tank mock-up: spread and error both ~cm where the posterior is ~mm, mean NEES
/// 13.7; docs/results.md). R = `refine_iterations` steps of preconditioned Langevin dynamics
/// follow, each particle on its own:
///   xᵢ += ε F⁻¹ ĝᵢ + ξᵢ,   ξᵢ ~ N(0, ε (2 − ε) F⁻¹ − ε² F⁻¹ Cᵢ F⁻¹),
/// ĝᵢ the batch gradient, Cᵢ its covariance (from the batch's per-point gradients), F the
/// particles' mean Gauss-Newton information Σ Jᵀ J / σ² (stochastic gradient Fisher scoring,
/// Ahn, Korattikara & Welling 2012). On a Gaussian posterior N(μ, F⁻¹) the step contracts
/// xᵢ − μ by (1 − ε) and the injected plus batch noise make the stationary covariance exactly
/// F⁻¹ for any ε; in the second half of the R steps ε is lowered per particle where the batch
/// noise alone would exceed that budget. The particles converge to the optimum of their mode
/// and then sample the posterior there, so `covariance` is the posterior of the stated
/// likelihood: its width scales with `noise_sigma_m`. The modes found by the SVGD steps are
/// kept (no particle leaves its basin).
///
/// Cost: K · (T + R) · B nearest-neighbour queries plus O(K² T) kernel terms; the particles are
/// processed in parallel (TBB arena of `parallel.num_threads`).
/// Thread-safety: the functions only read their inputs.
/// @note Deterministic: particle i draws its batch at iteration t from the stream
/// `Rng(seed).split(t · K + i)` and its Langevin noise at refinement step r from
/// `split((T + R + r) · K + i)`, and every sum over particles runs in index order, so the same
/// seed gives bit-identical particles for any thread count.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/registration/icp.hpp>

namespace scantling::registration {

/// How the particles start.
enum class SteinInit {
    /// Uniform within `init_half_widths` around the guess.
    kBounds,
    /// `num_yaw_seeds` short ICP runs from the guess's position with yaws spread uniformly over
    /// [−π, π] (SPEC §7, for a structure whose centre is known but not its heading); the
    /// particles are shared round-robin among the results and jittered by `seed_jitter`.
    kIcpSeeded,
};

struct SteinIcpConfig {
    int num_particles = 200;  ///< K, >= 2 (the bandwidth divides by log K). SPEC §7: 200
    int iterations = 100;     ///< T, >= 1. 50 left stray particles on a 0.3 m / 0.2 rad box
    int batch_size = 100;     ///< B source points per particle and iteration, >= 1
    /// Pairs farther apart than this are dropped, metres, > 0. Must exceed the initial spread.
    double max_correspondence_distance_m = 0.5;
    /// Pairing with the hidden face of a thin plate (IcpConfig::back_faces; the sensor is the
    /// source frame's origin, the target's normals must point to the free side; kReject needs
    /// target normals, the others without normals keep the nearest point). Its bias
    /// along the view, shared by every particle, is not an uncertainty (docs/results.md, NEES
    /// section), so the default is ICP's.
    BackFaces back_faces = BackFaces::kPreferFront;
    /// σ of the point residuals, metres, > 0: the likelihood's temperature. Sensor noise plus
    /// map error; smaller means a tighter posterior. With `refine_iterations` > 0 it sets the
    /// reported covariance (∝ σ²). 5 cm (SPEC §7) is conservative in the ballast-tank mock-up
    /// (docs/results.md: spread 2–4× the error there).
    double noise_sigma_m = 0.05;
    /// Adam learning rates: the largest step per iteration, metres and radians, > 0.
    double translation_lr_m = 0.03;
    double rotation_lr_rad = 0.015;
    /// Learning rate at the last iteration as a fraction of the first, in (0, 1]: the decay
    /// lets the particles settle into their modes before the refinement steps.
    double final_lr_fraction = 0.05;
    /// R, >= 0: preconditioned Langevin steps after the SVGD ones (file comment), which let the
    /// particles converge and then sample the posterior, so the spread is the posterior's and
    /// not the learning rates'. 0 = SVGD only (spread and error ~cm in the mock-up). 30: at
    /// ε = 0.5 an offset of 100 posterior σ decays to < 1 σ in 7 steps; the rest mix.
    int refine_iterations = 30;
    /// ε of those steps, in (0, 1]: the share of the offset from a Gaussian posterior's mean
    /// removed per step. 0.5: fast, and leaves room for batch noise up to λ = 3 times the
    /// posterior's (λ ≈ (N / B) (s / σ)², s the residual RMS) before the step must shrink.
    double refine_step = 0.5;
    /// x, y, yaw only; z, roll and pitch stay exactly those of the guess (known from the robot).
    bool reduced_3dof = false;
    SteinInit init = SteinInit::kBounds;
    /// kBounds: half-widths (x, y, z, roll, pitch, yaw) of the uniform box around the guess,
    /// metres and radians, each >= 0.
    Vector6d init_half_widths = (Vector6d() << 0.3, 0.3, 0.1, 0.05, 0.05, 0.2).finished();
    int num_yaw_seeds = 8;         ///< kIcpSeeded: ICP runs, >= 1
    int seed_icp_iterations = 10;  ///< kIcpSeeded: iterations of each ICP run, >= 1
    /// kIcpSeeded: half-widths of the uniform jitter around each ICP result, each >= 0.
    Vector6d seed_jitter = (Vector6d() << 0.05, 0.05, 0.0, 0.0, 0.0, 0.05).finished();
    /// A KDE mode counts in `num_modes` when it attracts at least this share of the particles,
    /// in (0, 1). 0.1: stray particles do not count as modes.
    double min_mode_fraction = 0.1;
    std::uint64_t seed = 1;   ///< same seed ⇒ same particles
    ParallelConfig parallel;  ///< threads over particles

    /// Throws ConfigError("<prefix>.num_particles = 1, expected >= 2").
    void validate(std::string_view prefix = "stein_icp") const;
};

struct SteinIcpResult {
    /// Final particles (x, y, z, roll, pitch, yaw), metres and radians, angles in [−π, π].
    std::vector<Vector6d> particles;
    Vector6d mean = Vector6d::Zero();  ///< translation averaged, angles circular means
    /// Sample covariance of the particles about `mean` (angle differences wrapped), in the
    /// (x, y, z, roll, pitch, yaw) parametrisation, m² / rad². Fixed DoFs (3-DoF) are zero.
    Matrix6d covariance = Matrix6d::Zero();
    /// Per-DoF mode of a Gaussian KDE of the particles (the pose to use: the mean can lie
    /// between two modes of a symmetric structure).
    Vector6d mode = Vector6d::Zero();
    Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();  ///< pose of `mode`
    /// Largest number of distinct KDE modes over the DoFs (see min_mode_fraction): > 1 means
    /// an ambiguous registration.
    int num_modes = 1;
    double fitness = 0.0;  ///< share of source points within the correspondence distance at `mode`
    double rmse_m = 0.0;   ///< RMS distance of those points, metres
};

/// Registers `source` to `target` starting from `T_target_source_guess`.
/// Throws InputError for an empty, inconsistent or non-finite cloud, a non-finite guess or
/// back_faces = kReject without target normals, ConfigError for a bad config.
SteinIcpResult stein_icp(const PointCloud& source, const PointCloud& target,
                         const Eigen::Isometry3d& T_target_source_guess,
                         const SteinIcpConfig& config);

/// Same, reusing `target_tree` built over exactly `target.points` (InputError otherwise).
SteinIcpResult stein_icp(const PointCloud& source, const PointCloud& target,
                         const KdTree& target_tree, const Eigen::Isometry3d& T_target_source_guess,
                         const SteinIcpConfig& config);

/// (x, y, z, roll, pitch, yaw) of `T`. Pure.
Vector6d pose_params_from_isometry(const Eigen::Isometry3d& T);

/// Inverse of pose_params_from_isometry. Pure.
Eigen::Isometry3d isometry_from_pose_params(const Vector6d& params);

/// Modes of a 1-D Gaussian KDE (Silverman bandwidth, robust form) found by mean shift from
/// every sample. `circular`: values are angles, wrapped to [−π, π] in the differences.
struct KdeModes {
    double mode = 0.0;       ///< location of the densest mode
    int num_modes = 0;       ///< modes attracting >= min_fraction of the samples
    double bandwidth = 0.0;  ///< kernel σ used
};

/// KDE modes of `values` (non-empty, finite; InputError otherwise). O(n² · iterations).
KdeModes kde_modes(std::span<const double> values, bool circular, double min_fraction);

}  // namespace scantling::registration
