#pragma once
/// @file
/// Art. F's 3-DoF registration in a distillation column (SPEC §7): x, y and yaw of the body
/// from one depth frame, attempted only when the frame shows the column's structure
/// (perception/column_structure.hpp: a wall of the known diameter and the unique downcomer).
///
/// Steps:
/// 1. the frame is turned into the levelled frame G: origin at the sensor, z up (roll and pitch
///    from the IMU), the body's yaw left out, so T_world_body = T_world_G · T_G_body with
///    T_world_G = (R_z(ψ), p_sensor) and ψ the body's yaw;
/// 2. the structure is detected in G (up = z, viewpoint = origin); a frame without a wall of
///    the known diameter or without a downcomer is refused ("not_registrable");
/// 3. the seed: ψ turns the seen downcomer direction (from the axis) onto the map's downcomer
///    line (downcomers alternate sides per tray, so both of its directions are candidates and
///    the one nearer the prediction's yaw is taken), and the sensor sits where the seen axis
///    point puts it, p_sensor_xy = axis_xy − R_z(ψ) · axis_point_G; z from the floor when it
///    is seen (the map's floor point under the sensor plus the height above the seen floor,
///    art. F's z from the legs), else from the prediction;
/// 4. Stein-ICP restricted to (x, y, yaw) of T_world_G (registration/stein_icp.hpp,
///    reduced_3dof), its particles started in a small box around the seed; the pose is the
///    particles' KDE mode, refused ("registration") when its RMS error or fitness is poor;
/// 5. the measurement's covariance: the particles' spread in x, y, yaw (with floors), and
///    floor_z_sigma_m on z when the floor gave it, free_sigma on the rest (roll, pitch; z
///    without a floor) so that a filter takes only what was measured.
///
/// Frames: T_<to>_<from>; the map (world) frame has z up, the column axis vertical through
/// axis_xy_m. Units: metres, radians (degrees where the field name says so).
/// Thread-safety: the functions only read their inputs (reentrant).
/// Cost: the structure detection (~12 ms for a binned Azure NFOV frame at the 2 cm detection
/// voxel) plus K · (T + R) · B nearest-neighbour queries of the Stein-ICP (defaults:
/// 64 · 50 · 64 ≈ 0.2 M): ~140 ms per registered frame in all (docs/results.md, art. F).
/// @note Deterministic: the detection and the particles are seeded (stein.seed + seed_offset).

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/localization/pose_filter.hpp>
#include <scantling/perception/column_structure.hpp>
#include <scantling/registration/stein_icp.hpp>

namespace scantling::localization {

struct ColumnRegistrationConfig {
    /// The detector (diameter check, downcomer tests); its diameter is the column's.
    perception::ColumnStructureConfig structure;
    /// The frame is downsampled to this voxel before the detection, metres, >= 0 (0: every
    /// point). 2 cm keeps the detector's 2 cm plane bands and 5-point height bins populated
    /// (a plate at 3 m still gives ~25 points per 5 cm) at a third of a binned frame's points.
    double detection_voxel_m = 0.02;
    /// The frame is downsampled to this voxel for the registration, metres, > 0: the map's
    /// (LocalizationMapConfig::voxel_size_m), so that frame and map points weigh alike.
    double registration_voxel_m = 0.05;
    /// Where the column axis is in the map, metres (the simulator's column: the origin).
    Eigen::Vector2d axis_xy_m = Eigen::Vector2d::Zero();
    /// Azimuth of the line through the axis that the downcomers lie on, from the map's x axis,
    /// degrees. Downcomers alternate sides from one tray to the next (the simulator's: +x and
    /// −x), so the seen one fixes the yaw up to 180°, which the prediction resolves.
    double downcomer_azimuth_deg = 0.0;
    /// Refinement: 3-DoF Stein-ICP from a box around the seed. The seed is good to ~2 cm and
    /// ~2° (the detector's axis and plate normal), so a box of ±5 cm / ±3° holds the optimum
    /// and the thesis' 200 particles and 100 iterations (2.3 s per frame) are not needed:
    /// 64 particles, 30 + 20 iterations of 64 points run in ~0.13 s. Point-to-plane (the map
    /// has normals); 0.3 m of correspondence distance covers the box and the VIO's drift.
    registration::SteinIcpConfig stein = [] {
        registration::SteinIcpConfig c;
        c.num_particles = 64;
        c.iterations = 30;
        c.batch_size = 64;
        c.refine_iterations = 20;
        c.max_correspondence_distance_m = 0.3;
        c.reduced_3dof = true;
        c.init = registration::SteinInit::kBounds;
        c.init_half_widths = (Vector6d() << 0.05, 0.05, 0.0, 0.0, 0.0, 0.05).finished();
        return c;
    }();
    /// z from the floor: the map point nearest to where the prediction puts the seen floor
    /// under the sensor is taken as the floor when it is within this distance (metres, > 0:
    /// more than the VIO's vertical drift, less than the 2 m between trays) and its normal
    /// within structure.vertical_tolerance_deg of vertical. Otherwise z is the prediction's, and
    /// a z drifted by the VIO would show in the RMS error below.
    double max_floor_snap_m = 0.3;
    /// σ of that z, metres, > 0: the floor plane's fit (~mm) plus the map's voxel (0.05 m
    /// centroids of a flat floor lie on it) and the trunk's bounce between the two.
    double floor_z_sigma_m = 0.01;
    /// Quality (art. F judges the registration by its RMS error): the RMS distance of the
    /// inlier pairs at the mode, metres, > 0. A right pose gives the map's voxel noise, ~1–2 cm.
    double max_rmse_m = 0.04;
    /// Share of the frame's points within the correspondence distance at the mode, in (0, 1).
    double min_fitness = 0.6;
    /// Floors of the reported σ (the particles sample the stated likelihood, which knows
    /// nothing of the map's discretisation): metres and degrees, >= 0.
    double min_position_sigma_m = 0.01;
    double min_yaw_sigma_deg = 0.5;
    /// σ given to z, roll and pitch, which the registration does not measure (metres and
    /// radians), > 0: large enough that the filter keeps its own.
    double free_sigma = 10.0;

    /// Throws ConfigError naming "<prefix>.<field>" (nested: "<prefix>.stein.<field>").
    void validate(std::string_view prefix = "column") const;
};

/// (x, y) of the sensor and yaw of the body: the 3 DoFs the column leaves to be found.
struct ColumnSeed {
    Eigen::Vector2d p_world_sensor_xy = Eigen::Vector2d::Zero();
    double yaw_rad = 0.0;
};

struct ColumnRegistration {
    /// The measurement, when the frame was registered and passed the quality tests.
    std::optional<AbsolutePose> pose;
    /// The registration's body pose, also when it failed the quality tests.
    std::optional<Eigen::Isometry3d> T_world_body;
    std::optional<ColumnSeed> seed;
    bool z_from_floor = false;  ///< z measured from the seen floor (else the prediction's)
    /// The structure, in the levelled frame G (z up, origin at the sensor).
    perception::ColumnStructure structure;
    double rmse_m = 0.0;
    double fitness = 0.0;
    int num_modes = 0;
    /// "" when registered, "not_registrable" (structure.status says why) or "registration".
    std::string failure;
    std::string reason;

    bool ok() const { return pose.has_value(); }
};

/// The seed of a registrable structure (in G) given the predicted body yaw (pure).
/// nullopt when the structure is not registrable.
std::optional<ColumnSeed> column_seed(const perception::ColumnStructure& structure_G,
                                      double predicted_yaw_rad,
                                      const ColumnRegistrationConfig& config);

/// Registers one frame (sensor frame, no-return points removed) against the map (`map` with
/// normals, `map_tree` built over its points). `R_world_body_imu`: the IMU's attitude (only
/// its roll and pitch are used); `predicted`: the filter's body pose at the frame's stamp
/// (its yaw picks the downcomer's side, its z is kept). The pose's stamp is predicted.stamp_s.
/// Throws ConfigError for a bad config, InputError for an empty map or non-finite inputs.
ColumnRegistration register_column(const PointCloud& frame_sensor,
                                   const Eigen::Isometry3d& T_body_sensor,
                                   const Eigen::Matrix3d& R_world_body_imu,
                                   const AbsolutePose& predicted, const PointCloud& map,
                                   const KdTree& map_tree, const ColumnRegistrationConfig& config,
                                   std::uint64_t seed_offset = 0);

}  // namespace scantling::localization
