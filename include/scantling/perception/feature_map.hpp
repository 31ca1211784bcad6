#pragma once
/// @file
/// A sparse feature-point map that accumulates stereo feature frames the way ORB-SLAM2 keeps
/// its map points (SPEC §9 step 1; RESULTS-TO-REPRODUCE 4.7: summing raw frames overcounts).
///
/// Each frame (points in the camera frame + T_world_camera) is merged point by point, in order:
/// - a frame point within `merge_radius_m` of a live map point (the nearest; ties to the older
///   point) is an OBSERVATION of it: the position becomes the running mean, the observation
///   count grows by one. A map point takes at most one observation per frame; a second frame
///   point near it in the same frame is dropped (a map point is one feature);
/// - otherwise the frame point becomes a new CANDIDATE.
/// Candidates are then judged like ORB-SLAM2's recent map point culling (LocalMapping::
/// MapPointCulling): every frame in which a candidate should have been visible (in front, in
/// the image, in the depth range, seen within `max_view_angle_rad` of its mean viewing
/// direction: ORB-SLAM2's isInFrustum) counts as "visible", every frame that observed it as
/// "found"; it is culled when found / visible < `min_found_ratio`, and `culling_window_frames`
/// frames after its creation it is confirmed when it has at least `min_observations`
/// observations (its creation included), culled otherwise. Confirmed points are kept for good
/// (no bundle-adjustment outlier removal is modelled). Only confirmed points count.
///
/// Frames: points in the camera's optical frame (x right, y down, z forward), the map in the
/// world frame, metres. Cost per frame: O(frame points) hash look-ups (27 cells of edge
/// merge_radius_m) + O(candidates) projections. Determinism: a pure function of the frames in
/// order. Thread-safety: none (a stateful object; const members may be read concurrently).

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <scantling/core/pinhole_intrinsics.hpp>
#include <scantling/core/point_cloud.hpp>

namespace scantling::perception {

struct FeatureMapConfig {
    /// A frame point this close to a map point observes it, metres. It also fixes the map's
    /// saturated density: at most ≈ 0.7 / merge_radius_m² points per m² of surface (random
    /// sequential packing of disks of diameter merge_radius_m).
    double merge_radius_m = 0.04;
    std::size_t min_observations = 3;       ///< to confirm a candidate (ORB-SLAM2 stereo: 3)
    std::size_t culling_window_frames = 3;  ///< a candidate is judged this many frames after
                                            ///< its creation (ORB-SLAM2: 2–3 keyframes)
    double min_found_ratio = 0.25;          ///< found / visible below this culls (ORB-SLAM2)
    PinholeIntrinsics intrinsics{};         ///< the camera, for "should have been visible"
    double min_depth_m = 0.2;               ///< visible only within [min, max] depth
    double max_depth_m = 10.0;
    /// Visible only when the viewing direction is within this of the point's mean viewing
    /// direction (ORB-SLAM2's isInFrustum: cos > 0.5, i.e. 60°), radians.
    double max_view_angle_rad = std::numbers::pi / 3.0;

    /// Throws ConfigError naming the field ("feature_map.merge_radius_m = 0, expected ...").
    void validate(std::string_view prefix = "feature_map") const;
};

/// One map point.
struct MapPoint {
    Eigen::Vector3d p_world = Eigen::Vector3d::Zero();   ///< mean of its observations
    Eigen::Vector3d view_sum = Eigen::Vector3d::Zero();  ///< sum of unit camera→point rays
    std::size_t observations = 0;                        ///< frames that observed it
    std::size_t visible = 0;                             ///< frames it should have been seen in
    std::size_t first_frame = 0;                         ///< frame index of its creation
    std::size_t last_observed_frame = 0;
    bool confirmed = false;
    bool alive = true;  ///< false once culled
};

/// What one frame did to the map.
struct FeatureFrameStats {
    std::size_t frame_points = 0;  ///< points in the frame
    std::size_t observed = 0;      ///< observations of existing map points
    std::size_t created = 0;       ///< new candidates
    std::size_t dropped = 0;       ///< second hits on a point already observed this frame
    std::size_t confirmed = 0;     ///< candidates confirmed after this frame
    std::size_t culled = 0;        ///< candidates culled after this frame
};

class FeatureMap {
  public:
    /// Validates the config (ConfigError).
    explicit FeatureMap(FeatureMapConfig config = {});

    /// Merges one frame (see the file comment). Throws InputError for a non-finite point or
    /// pose.
    FeatureFrameStats insert(std::span<const Eigen::Vector3d> points_camera,
                             const Eigen::Isometry3d& T_world_camera);

    std::size_t num_confirmed() const { return num_confirmed_; }
    std::size_t num_candidates() const { return candidates_.size(); }
    std::size_t num_frames() const { return num_frames_; }

    /// Confirmed points, world frame, in creation order.
    PointCloud confirmed_cloud() const;
    /// Every point ever created (culled ones with alive = false), in creation order.
    const std::vector<MapPoint>& points() const { return points_; }
    const FeatureMapConfig& config() const { return config_; }

  private:
    using CellKey = std::uint64_t;
    CellKey key_of(const Eigen::Vector3d& p) const;
    std::size_t nearest(const Eigen::Vector3d& p_world) const;  // points_.size() when none
    void observe(std::size_t index, const Eigen::Vector3d& p_world, const Eigen::Vector3d& ray);
    void create(const Eigen::Vector3d& p_world, const Eigen::Vector3d& ray);
    bool should_see(const MapPoint& point, const Eigen::Isometry3d& T_camera_world,
                    const Eigen::Vector3d& camera_world) const;
    void judge_candidates(const Eigen::Isometry3d& T_world_camera, FeatureFrameStats& stats);
    void unhash(std::size_t index);

    FeatureMapConfig config_;
    std::vector<MapPoint> points_;
    std::vector<std::size_t> candidates_;  // indices of live unconfirmed points, creation order
    std::unordered_map<CellKey, std::vector<std::size_t>> cells_;
    std::size_t num_confirmed_ = 0;
    std::size_t num_frames_ = 0;
};

}  // namespace scantling::perception
