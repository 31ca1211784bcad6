#pragma once
/// @file
/// Hierarchical landmark localisation (SPEC §7, art. B): the frame × longitudinal landmarks
/// seen in a depth frame (perception/frame_landmarks.hpp) matched with the map's and turned
/// into an absolute pose for the filter, like any registration.
///
/// The frame is placed in the map through the predicted pose; each detected landmark is
/// matched with the nearest map landmark (minimum Euclidean distance, within
/// association_distance_m, one-to-one) among those of the compartment the robot is in and of
/// the compartments its manholes open onto (the map tree: the next bay's frame is seen through
/// a manhole, bays further away are not), on a frame face that looks towards the camera (the
/// two faces of a web frame are one plate thickness apart). The correction is the rotation
/// that turns the seen frame normals onto the map's (art. B's landmark orientation; the
/// rotation about that normal is left to the IMU and the VIO) and the translation that then
/// brings the largest set of agreeing landmarks onto the map's on average (the others are
/// spurious detections).
///
/// Covariance: position_sigma_m per landmark (shrinking as 1/√n), normal_sigma_rad about the
/// two axes the frame normal fixes, free_rotation_sigma_rad about the normal itself.

#include <Eigen/Geometry>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/point_cloud.hpp>
#include <scantling/io/structural_map.hpp>
#include <scantling/localization/pose_filter.hpp>
#include <scantling/perception/frame_landmarks.hpp>

namespace scantling::localization {

struct LandmarkCorrectionConfig {
    perception::FrameLandmarkConfig detector;
    /// The frame is downsampled to this voxel before detection, metres, > 0: fine enough to
    /// keep a 0.1 m stiffener's top edge (a 0.05 m voxel averages it 2.5 cm low).
    double voxel_size_m = 0.02;
    /// Match gate, metres, > 0: under half the stiffener spacing (0.53 m in the mock-up).
    double association_distance_m = 0.2;
    /// Matches whose offsets agree within this form the consensus the correction rests on, the
    /// others are dropped as wrong detections, metres, > 0.
    double max_residual_m = 0.05;
    /// Fewest agreeing matches for a correction, >= 1: one alone can be a spurious line (a
    /// bracket, a plate edge) that happens to lie near a landmark; two that agree rarely are.
    std::size_t min_landmarks = 2;
    /// Per landmark, metres, > 0: the detections on the mock-up flight are 5 mm off with ~5
    /// landmarks a frame, i.e. ~1 cm each (docs/results.md).
    double position_sigma_m = 0.01;
    double normal_sigma_rad = 0.01;  ///< of the frame plane's normal, > 0
    /// About the frame normal, which the landmarks do not fix, > 0.
    double free_rotation_sigma_rad = 0.5;

    void validate(std::string_view prefix = "landmarks") const;
};

struct LandmarkMatch {
    int map_landmark = -1;  ///< io::Landmark::id
    int detection = -1;     ///< index into LandmarkCorrection::detected.landmarks
    Eigen::Vector3d seen_world = Eigen::Vector3d::Zero();  ///< through the prediction
    double distance_m = 0.0;  ///< to the map landmark, before the correction
};

struct LandmarkCorrection {
    /// Empty when a pose was computed; otherwise why not ("no_landmarks", "no_match",
    /// "residual": too few matches agree).
    std::string failure;
    std::string reason;                  ///< with the numbers
    AbsolutePose pose;                   ///< stamp, corrected T_world_body, covariance (left twist)
    std::vector<LandmarkMatch> matches;  ///< the consensus the correction rests on
    std::size_t outliers = 0;            ///< matches left out of it
    perception::FrameLandmarks detected;  ///< in the predicted world frame
    bool ok() const { return failure.empty(); }
};

/// Corrects `predicted` (T_world_body at the frame's capture time) with the landmarks seen in
/// `frame_sensor` (finite points) mounted at T_body_sensor, among the landmarks of
/// `compartment` (-1: all). Throws ConfigError for a bad config.
LandmarkCorrection correct_with_landmarks(const PointCloud& frame_sensor,
                                          const AbsolutePose& predicted,
                                          const Eigen::Isometry3d& T_body_sensor,
                                          const io::StructuralMap& map, int compartment,
                                          const LandmarkCorrectionConfig& config);

}  // namespace scantling::localization
