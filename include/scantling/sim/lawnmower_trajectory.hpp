#pragma once
/// @file
/// Lawnmower (zig-zag) sweeps over a rectangle on a wall at a constant stand-off: the MAV
/// sweeping mission of SPEC §4 and the ROV hull survey plan of SPEC §5.
///
/// Wall frame (`T_world_wall`): x along the rectangle's width, y along its height, z the wall
/// normal pointing into free space (towards the vehicle). The rectangle is [0, width] × [0,
/// height] at z = 0; the vehicle flies at z = standoff_m.
/// Slices: `kHorizontal` slices run along x and step along y (SPEC §4: side to side, top to
/// bottom); `kVertical` slices run along y and step along x (SPEC §5: surface to keel). The
/// first and last slices lie on the rectangle's edges and the step is shrunk so that
/// consecutive slices are at most `slice_spacing_m` apart: n = ⌈extent / spacing⌉ + 1 slices.
/// The vehicle stops at each corner (a WaypointTrajectory underneath) and keeps one heading.
///
/// Thread-safety and determinism: see trajectory.hpp.

#include <Eigen/Geometry>
#include <string_view>
#include <vector>

#include <scantling/sim/waypoint_trajectory.hpp>

namespace scantling::sim {

enum class SliceDirection { kHorizontal, kVertical };

struct LawnmowerTrajectoryConfig {
    Eigen::Isometry3d T_world_wall = Eigen::Isometry3d::Identity();  ///< see the file comment
    double width_m = 8.0;          ///< along wall x (SPEC §4: 8 × 5 m sweep)
    double height_m = 5.0;         ///< along wall y
    double standoff_m = 1.0;       ///< distance from the wall plane (SPEC §5: 1.0 m)
    double slice_spacing_m = 1.0;  ///< largest allowed distance between slices
    SliceDirection slices = SliceDirection::kHorizontal;
    bool start_at_top = true;  ///< first slice / first descent at the top (wall y max)
    bool face_wall = true;     ///< heading: towards the wall (horizontal part of −z_wall)
    double yaw_rad = 0.0;      ///< heading when !face_wall or the wall is horizontal
    double max_speed_mps = 0.5;
    double max_accel_mps2 = 0.5;
    ProfileShape shape = ProfileShape::kSmooth;

    /// Throws ConfigError naming the field ("lawnmower_trajectory.width_m = 0, ...").
    void validate(std::string_view prefix = "lawnmower_trajectory") const;
};

/// Slice spacing that gives `overlap` (in [0, 1)) between neighbouring camera footprints at
/// `standoff_m`, for a camera field of view `fov_rad` across the slices (SPEC §5):
/// 2 standoff tan(fov / 2) (1 − overlap). Throws InputError on out-of-range arguments.
double footprint_slice_spacing_m(double fov_rad, double standoff_m, double overlap);

class LawnmowerTrajectory : public Trajectory {
  public:
    explicit LawnmowerTrajectory(const LawnmowerTrajectoryConfig& config);

    MotionState at(double t_s) const override { return path_.at(t_s); }
    double duration_s() const override { return path_.duration_s(); }

    int num_slices() const { return num_slices_; }
    /// The spacing actually used (<= slice_spacing_m).
    double slice_step_m() const { return step_m_; }
    /// The corner waypoints in the world frame, two per slice, in flying order.
    const std::vector<Waypoint>& waypoints() const { return path_.config().waypoints; }
    const WaypointTrajectory& path() const { return path_; }
    const LawnmowerTrajectoryConfig& config() const { return config_; }

  private:
    LawnmowerTrajectoryConfig config_;
    int num_slices_ = 0;
    double step_m_ = 0.0;
    WaypointTrajectory path_;
};

}  // namespace scantling::sim
