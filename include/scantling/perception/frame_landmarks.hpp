#pragma once
/// @file
/// Structural landmarks in a depth frame of a stiffened tank (SPEC §7, art. B): the points
/// where a web frame (or bulkhead) meets a longitudinal stiffener, each with its orientation
/// (the frame's normal and the plating's normal), the landmarks a surveyor names as
/// "frame 12, longitudinal 7".
///
/// The frame must be given in a frame roughly aligned with the ship's axes (the map frame
/// through a predicted pose: a few degrees and decimetres off are fine), so that the
/// frame axis (along the ship, the normal of web frames and the direction of longitudinals)
/// is known. Steps:
/// 1. planes by sequential RANSAC (plane_ransac.hpp); a plane whose normal is within
///    axis_tolerance_deg of the frame axis is a frame, one whose normal is perpendicular to it
///    (within the same tolerance) and that spreads across the ship wider than a stiffener is
///    high is plating (a stiffener's own side is not);
/// 2. for each plating plane, the points on its free side between min_ and max_stiffener_height_m
///    above it, leaving out the frames and every plane that rises higher than a stiffener
///    (other walls), are split into stiffeners by gaps across the ship; a stiffener seen along at
///    least min_line_length_m is a line along the axis at its top edge (the height_quantile of its
///    points' heights: the top edge is what the map's landmark marks);
/// 3. each line meets each frame plane it reaches (within max_gap_to_frame_m of its last
///    point, inside the frame's seen extent): a landmark.
///
/// Deterministic (the plane search is seeded). Not thread-safe to share a config being edited;
/// the function itself is reentrant.

#include <Eigen/Core>
#include <cstddef>
#include <string_view>
#include <vector>

#include <scantling/core/point_cloud.hpp>
#include <scantling/perception/plane_ransac.hpp>

namespace scantling::perception {

struct FrameLandmarkConfig {
    /// Plane search: 2 cm bands (the L515's noise at 2 m is ~5 mm; plates meet at welds),
    /// planes of at least 150 points (a stiffener's side at 2 cm spacing has ~500).
    PlaneRansacConfig planes = [] {
        PlaneRansacConfig c;
        c.min_inliers = 150;
        c.max_planes = 10;
        return c;
    }();
    Eigen::Vector3d frame_axis = Eigen::Vector3d::UnitX();  ///< along the ship, non-zero
    double axis_tolerance_deg = 15.0;                       ///< plane classification, in (0, 45)
    /// Points this far above a plate can belong to a stiffener on it, metres (0 < min < max).
    double min_stiffener_height_m = 0.03;
    double max_stiffener_height_m = 0.3;
    /// Fewest points of a plating plane, >= 3: a small plane across stiffeners (their tops,
    /// a bracket) is not the plate they stand on (500 at 2 cm spacing: 0.2 m²).
    std::size_t min_plate_inliers = 500;
    double stiffener_gap_m = 0.06;       ///< a gap this wide across the ship separates two, > 0
    double min_line_length_m = 0.2;      ///< seen length along the axis, > 0
    std::size_t min_line_points = 20;    ///< >= 3
    double height_quantile = 0.9;        ///< the top edge among the heights, in (0, 1]
    double max_gap_to_frame_m = 0.3;     ///< line end to the frame plane, >= 0
    double frame_extent_margin_m = 0.1;  ///< the landmark within the frame's seen extent + this

    void validate(std::string_view prefix = "landmarks") const;
};

/// A longitudinal stiffener seen in the frame: the line along its top edge.
struct StiffenerLine {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< on the top edge, mid-way of the seen part
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();     ///< unit, along the frame axis' sense
    Eigen::Vector3d plate_normal = Eigen::Vector3d::UnitZ();  ///< unit, towards the viewpoint
    double height_m = 0.0;                                    ///< top edge above the plate
    double axial_min_m = 0.0, axial_max_m = 0.0;              ///< seen extent along `direction`
    std::size_t num_points = 0;
    int plate = -1;  ///< index into FrameLandmarks::planes
};

/// A frame × longitudinal intersection.
struct DetectedLandmark {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    /// Unit normal of the frame plane, towards the viewpoint (the compartment the camera is in).
    Eigen::Vector3d frame_normal = Eigen::Vector3d::UnitX();
    Eigen::Vector3d plate_normal = Eigen::Vector3d::UnitZ();  ///< unit, towards the stiffener
    int frame_plane = -1;                                     ///< index into FrameLandmarks::planes
    int line = -1;                                            ///< index into FrameLandmarks::lines
};

struct FrameLandmarks {
    std::vector<Plane> planes;
    std::vector<int> frame_planes;  ///< indices of planes classified as frames
    std::vector<int> plate_planes;  ///< indices of planes classified as plating
    std::vector<StiffenerLine> lines;
    std::vector<DetectedLandmark> landmarks;
};

/// Detects frames, stiffeners and their intersections in `cloud` (see the file comment; any
/// frame roughly aligned with the ship) seen from `viewpoint` (the sensor's position in that
/// frame: every surface seen faces it). Empty cloud: nothing found. Throws InputError for a
/// non-finite cloud or viewpoint, ConfigError for a bad config.
FrameLandmarks detect_frame_landmarks(const PointCloud& cloud, const Eigen::Vector3d& viewpoint,
                                      const FrameLandmarkConfig& config = {});

}  // namespace scantling::perception
