#pragma once
/// @file
/// The UAV 3D reconstruction experiment of SPEC §9 (source 004 §3; RESULTS-TO-REPRODUCE 4.7):
/// the helix baseline (Table 1) and the point-density planner (Tables 2–3) around the isolated
/// cylinder, with a sparse stereo feature camera feeding an ORB-SLAM2-like feature map.
///
/// Simulation: world `cylinder` (r 1 m, h 3 m, textured); sim::StereoPoints with the UAV3D
/// camera's 640 × 480, 66° × 49.5° view, looking along body x; the vehicle follows its
/// trajectory exactly and the feature map is fed GROUND-TRUTH camera poses (the source's
/// ORB-SLAM2 tracking error is not simulated). Frames are taken every 1 / frame_rate_hz s.
///
/// Sunlight (004 l.87: "directed at segment 0's centre, segment 2 fully in the shadow"): the
/// sensor has no light model, so the runner keeps each detected feature with probability
///   p = ambient + (1 − ambient) · max(0, n · s),
/// n the cylinder's outward normal at the point, s the unit direction to the sun (horizontal,
/// azimuth sun_azimuth_rad). A convex cylinder casts no shadow on itself other than this
/// attached shadow (n · s ≤ 0), so the geometry is exact; the detection probability is a model.
///
/// Helix (Eq. 1, sim::HelixTrajectory): centred on the cylinder axis, z from 0 to the cylinder
/// height h over the whole flight, so v_z = h ω / (2π rotations) (the source does not say).
/// Planner: take-off at (r_flight, 0) from z 0 to flight height, one counter-clockwise turn
/// (step 0), then PointDensityPlanner steps flown along the circle at ω, facing the centre.
///
/// Determinism: a pure function of the config (seeded). Thread-safety: free functions.

#include <cstddef>
#include <cstdint>
#include <numbers>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/perception/feature_map.hpp>
#include <scantling/planning/point_density_planner.hpp>
#include <scantling/sim/stereo_points.hpp>
#include <scantling/sim/world_builders.hpp>

namespace scantling::mission {

/// The UAV3D stereo camera: sim::uav3d_camera()'s intrinsics (640 × 480, 66° × 49.5°),
/// mounted looking along body x (optical z = body x, optical y = −body z); 30 Hz; baseline
/// 0.12 m (ZED class, an assumption: 004 gives only the FOV); one feature per 20 px cell
/// (768 per frame, ORB-SLAM2's default is ~1000 features).
sim::StereoPointsConfig uav3d_stereo_points();

struct ReconstructionExperimentConfig {
    sim::CylinderConfig cylinder{};                          ///< r 1 m, h 3 m (004 l.71)
    sim::StereoPointsConfig stereo = uav3d_stereo_points();  ///< the camera
    perception::FeatureMapConfig feature_map{};  ///< intrinsics/depths are taken from `stereo`
    double omega_radps = 0.25;                   ///< angular rate on the circle (004: 0.25 rad/s)
    double frame_rate_hz = 30.0;                 ///< frames fed to the map per second (camera rate)
    bool sunlight = true;  ///< apply the sunlight detection model (file comment)
    double sun_azimuth_rad = std::numbers::pi / 4.0;  ///< segment 0's centre
    double shadow_ambient = 0.2;     ///< detection probability in full shadow (= the pinhole
                                     ///< camera's ambient share)
    double takeoff_climb_mps = 0.5;  ///< planner run: vertical take-off speed (not in 004)
    std::uint64_t seed = 1;
    ParallelConfig parallel{};  ///< ray casting threads

    /// Throws ConfigError naming the field ("reconstruction.omega_radps = 0, expected ...").
    void validate(std::string_view prefix = "reconstruction") const;
};

/// One helix flight (one row of Table 1).
struct HelixRun {
    double radius_m = 0.0;
    double rotations = 0.0;
    double v_z_mps = 0.0;
    double duration_s = 0.0;
    double path_length_m = 0.0;
    std::size_t frames = 0;
    std::size_t raw_points = 0;        ///< stereo points summed over frames (overcount)
    std::size_t confirmed_points = 0;  ///< the feature map's count
    planning::SectorCounts sectors{};  ///< confirmed points per sector (sector 0 from +x)
};

/// Helix of `rotations` turns at `radius_m` (file comment). Throws ConfigError.
HelixRun run_helix(const ReconstructionExperimentConfig& config, double radius_m, double rotations);

/// One row of Tables 2–3: the map after flying to the step's target.
struct PlannerStepRow {
    std::size_t step = 0;              ///< 0: after take-off and the initial turn
    std::size_t total = 0;             ///< confirmed points
    planning::SectorCounts sectors{};  ///< confirmed points per sector
    int target_sector = -1;            ///< sector flown to (-1 for step 0)
    double arc_rad = 0.0;              ///< signed rotation flown in this step
    double turns = 0.0;                ///< cumulative |rotation| / 2π
    double path_length_m = 0.0;        ///< cumulative, take-off included
    double time_s = 0.0;               ///< cumulative flight time
};

struct PlannerRun {
    double flight_radius_m = 0.0;
    double flight_height_m = 0.0;
    std::vector<PlannerStepRow> steps;
    planning::PlannerStatus stop = planning::PlannerStatus::kMaxSteps;  ///< why it stopped
    planning::ObjectEstimate voxel_estimate{};  ///< locate_object on the step-0 map, unfixed
    std::size_t frames = 0;
};

/// The point-density planner run. `planner` should fix the centre (0, 0), r_flight and the
/// height (004 l.98, l.120); the start is (r_flight, 0) rotated by planner.start_angle_rad.
/// Throws ConfigError.
PlannerRun run_planner(const ReconstructionExperimentConfig& config,
                       const planning::PointDensityPlannerConfig& planner);

}  // namespace scantling::mission
