#pragma once
/// @file
/// The magnetic crawler's stop-and-map (SPEC §6): while the robot stands still its rosette
/// LiDAR's frames are accumulated in the body frame; the localisation pose is captured when the
/// accumulation begins (the SPEC's "~0.5 s after stopping": the caller decides when); at the end
/// of the stop the cloud is labelled (surface_obstacles.hpp) and registered against the previous
/// stop's cloud by constrained ICP, which corrects the map pose:
///   P_new = P_prev · P_cprev⁻¹ · P_cnew · C      (registration/constrained_icp.hpp).
///
/// The correction chain. P_cprev and P_cnew are the localisation's poses at the two stops, so
/// P_cprev⁻¹ · P_cnew is the motion the localisation saw between them and C what the clouds say
/// is left of it. The first stop's map pose is the localisation's.
///
/// What is registered: the new stop's points labelled as obstacles (positive and negative)
/// against the previous stop's whole cloud (voxelised, in range), whose normals are then
/// estimated with the surface around each obstacle. Why not the whole new cloud: the planar ICP
/// cannot move z, roll or pitch, so the free surface adds to x, y and yaw only what its
/// normals' noise puts there; on a plate at 1 cm voxels and 3 mm noise the estimated normals
/// tilt by ~0.1 rad at random, a weak but confident false constraint in x and y. The obstacles'
/// sides are the real constraints. A new stop with fewer than min_icp_points obstacle points (a
/// bare plate), a registration that did not converge, hit a cap, or is degenerate among x, y,
/// yaw (a single straight weld bead leaves the motion along it free;
/// registration::analyze_degeneracy with the free basis) gives C = identity: the chain then
/// carries the localisation's relative motion, and `icp_applied` says so. Without absolute ranges
/// the chain drifts as the localisation's relative motion does; with UWB the localisation is
/// absolute and the chain is the comparison the SPEC reports (docs/results.md).
///
/// The obstacles of a stop are its positive and negative clusters, placed in the world through
/// the stop's map pose at the fitted surface's height under their centroid.
///
/// Frames: the body frame of the robot at the stop (x forward, z the surface normal), world.
/// Thread-safety: not thread-safe, one per robot. Deterministic for a config and inputs (the
/// detection's and the ICP's seeds are in their configs).

#include <Eigen/Geometry>
#include <cstddef>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/point_cloud.hpp>
#include <scantling/perception/surface_obstacles.hpp>
#include <scantling/registration/constrained_icp.hpp>

namespace scantling::perception {

struct StopAndMapConfig {
    SurfaceObstaclesConfig obstacles{};
    registration::ConstrainedIcpConfig icp{};
    bool correct_pose = true;  ///< false: no ICP, the chain is the localisation's
    /// Most points accumulated in one stop, > 0: a guard against a stop that never ends (the
    /// Mid-70 gives 100 000 points a second, so 3 s is 300 000).
    std::size_t max_points = 2'000'000;
    /// Obstacle points each stop needs for a registration, >= 6 (see the file comment).
    std::size_t min_icp_points = 50;
    /// Cells the LiDAR should have seen and did not are holes or edges (surface_obstacles.hpp,
    /// ExpectedView), with the LiDAR's full cone angle (Livox Mid-70: 70.4°; a crawler mission
    /// takes its sensor's from the calibration), the margin off its rim and the farthest cell.
    bool missing_returns_are_negative = false;
    double lidar_fov_rad = 70.4 * std::numbers::pi / 180.0;
    double fov_margin_rad = 0.05;
    double expected_range_m = 1.5;

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "stop_and_map") const;
};

/// An obstacle cluster of one stop, in the world.
struct MappedObstacle {
    SurfaceLabel label = SurfaceLabel::kPositive;                ///< kPositive or kNegative
    Eigen::Vector3d centroid_world_m = Eigen::Vector3d::Zero();  ///< on the fitted surface
    Eigen::Vector2d min_body_xy_m = Eigen::Vector2d::Zero();     ///< extent, body frame
    Eigen::Vector2d max_body_xy_m = Eigen::Vector2d::Zero();
    std::size_t num_cells = 0;
};

/// What one stop gave.
struct StopMap {
    std::size_t index = 0;  ///< 0 for the first stop
    double begin_s = 0.0;   ///< accumulation began (the localisation pose's time)
    double end_s = 0.0;     ///< accumulation ended
    std::size_t num_frames = 0;
    Eigen::Isometry3d T_world_body_localisation = Eigen::Isometry3d::Identity();  ///< P_cnew
    Eigen::Isometry3d T_world_body_map = Eigen::Isometry3d::Identity();           ///< P_new
    bool icp_applied = false;    ///< C came from the ICP (else identity; see the file comment)
    std::string icp_status;      ///< the ICP's status, "first stop", "off" or why it was not used
    SurfaceObstacles detection;  ///< body frame
    std::vector<MappedObstacle> obstacles;  ///< world
    /// The stop's accumulated points as given (body frame, at most max_points): what a task
    /// extracts geometry from beside the obstacles (perception/face_corridor.hpp).
    PointCloud cloud_body;
};

class StopMapper {
  public:
    /// `T_body_lidar`: the LiDAR's mount. ConfigError for a bad config, InputError for a
    /// non-finite mount.
    StopMapper(const StopAndMapConfig& config, const Eigen::Isometry3d& T_body_lidar);

    /// Starts accumulating at `t_s` with the localisation's pose then. InputError when a stop
    /// is already open or the pose is not finite.
    void begin(double t_s, const Eigen::Isometry3d& T_world_body_localisation);
    /// One LiDAR frame (LiDAR frame) of the open stop; ignored when no stop is open. Non-finite
    /// points are kept for the detection to count and skip; points past max_points dropped.
    void add_frame(const PointCloud& frame_lidar);
    bool collecting() const { return open_.has_value(); }
    /// Closes the stop at `t_s`: labels, registers and places its obstacles. InputError when no
    /// stop is open.
    StopMap finish(double t_s);

    /// The map pose of the last stop, if any.
    std::optional<Eigen::Isometry3d> last_map_pose() const;

  private:
    struct Open {
        double begin_s = 0.0;
        Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
        PointCloud cloud_body;
        std::size_t num_frames = 0;
    };
    struct Previous {
        PointCloud cloud_body;  ///< voxelised, in range
        Eigen::Isometry3d T_world_body_localisation = Eigen::Isometry3d::Identity();
        Eigen::Isometry3d T_world_body_map = Eigen::Isometry3d::Identity();
    };

    void correct(StopMap& stop) const;

    StopAndMapConfig config_;
    Eigen::Isometry3d T_body_lidar_;
    std::optional<Open> open_;
    std::optional<Previous> previous_;
    std::size_t stops_ = 0;
};

/// The obstacle clusters of `detection` placed in the world through `T_world_body` (see the
/// file comment). Pure.
std::vector<MappedObstacle> map_obstacles(const SurfaceObstacles& detection,
                                          const Eigen::Isometry3d& T_world_body);

}  // namespace scantling::perception
