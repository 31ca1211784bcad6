#pragma once
/// @file
/// The magnetic crawler's path follower on a triangle mesh (SPEC §6, D5.2 §III.3): a path is a
/// list of segments S_i = (B_i, E_i), each lying in one facet, followed one after the other.
///
/// Frames. Segment i has a frame R_i = T_world_segment (world ← segment), origin B_i, with
///   x = (E_i − B_i) / |E_i − B_i|, z = the facet normal with its x component removed and
///   normalised, y = z × x.
/// The robot pose T_world_body (body x forward, z out of the surface) is expressed in that
/// frame, T_segment_body = R_i⁻¹ · T_world_body (SPEC writes "T_3 · R_i⁻¹"; the pose *in* the
/// segment frame is this product order), and only x, y and yaw are kept: the surface is taken as
/// locally flat, so z, roll and pitch are dropped. yaw is the heading of the body x axis
/// projected onto the segment's x-y plane (atan2 of its y and x components).
///
/// Law. SPEC writes ω = k_y · y + k_yaw · yaw with unspecified gains. Here the gains are positive
/// and the law is written with its stabilising sign, i.e. SPEC's k's are the negatives of ours:
///   ω = −(k_y · y + k_yaw · yaw), clamped to ±max_omega,
///   v = v_ref · exp(−(ω / ω_0)²)              (ω the clamped, commanded rate),
/// so the robot slows down, nearly to a turn on the spot, while it turns hard. Linearised about
/// the segment (ẏ = v sin yaw ≈ v yaw, yaẇ = ω) the loop is s² + k_yaw s + k_y v = 0.
///
/// Switching. Segment i is done once x > |E_i − B_i| (strictly); the next one is then used in
/// the same update (several, if the robot is already past them). The path is done after the last
/// one: the command is then v = ω = 0 with `done` set. An empty path is done at once.
///
/// Thread-safety: update() mutates the follower (one follower per robot); the const accessors may
/// be called concurrently with each other. Deterministic. Cost: O(n) construction for n segments;
/// update() is O(1) plus O(k) for k segments passed in that call.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <string_view>
#include <vector>

#include <scantling/planning/mesh_path.hpp>

namespace scantling::control {

/// One path segment, lying in one facet of the mesh. World frame, metres: B_i = begin_world_m,
/// E_i = end_world_m (≥ 1e-6 m from B_i), normal_world the facet normal (not ∥ E − B); `face`
/// is not used by the follower. The planner's type, so that shortest_path_on_mesh()'s segments
/// are followed as they are.
using PathSegment = planning::MeshPathSegment;

/// Defaults for a magnetic crawler at 0.1 m/s (SPEC §6 gives v_ref's order but no gains). The
/// gains place both poles of the linearised loop (see @file) at −ω_n (critically damped, ζ = 1)
/// with ω_n = 0.7 rad/s: k_yaw = 2 ζ ω_n = 1.4 /s, k_y = ω_n² / v_ref = 4.9 /(m s). That settles
/// a 0.1 m offset in about 6/ω_n ≈ 9 s over ≈ v_ref/ω_n ≈ 0.14 m of travel, tight enough for the
/// stiffener tasks without asking for more than max_omega on centimetre errors. ω_0 = 0.5 rad/s:
/// at the full max_omega = 1 rad/s the speed is v_ref e^−4 ≈ 2 % (a turn on the spot, which
/// keeps a crawler on its facet through a corner).
struct SegmentFollowerConfig {
    double k_y_per_m_s = 4.9;      ///< k_y > 0, rad/s of turn rate per metre of cross-track y
    double k_yaw_per_s = 1.4;      ///< k_yaw > 0, rad/s of turn rate per radian of yaw
    double v_ref_mps = 0.1;        ///< v_ref > 0, forward speed when not turning
    double omega0_radps = 0.5;     ///< ω_0 > 0, turn rate at which v falls to v_ref / e
    double max_omega_radps = 1.0;  ///< > 0, |ω| is clamped to this

    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "segment_follower") const;
};

/// The robot in the current segment's frame (x along from B, y to the left, yaw from x).
struct SegmentFrameError {
    double x_m = 0.0;
    double y_m = 0.0;
    double yaw_rad = 0.0;  ///< in [−π, π]
};

/// A unicycle command in the body frame: forward speed along body x, turn rate about body z.
struct FollowerCommand {
    double v_mps = 0.0;
    double omega_radps = 0.0;
    std::size_t segment = 0;  ///< the segment followed (path size once done)
    bool done = false;        ///< the last segment is finished; v = ω = 0
    SegmentFrameError error;  ///< in segment `segment`'s frame (zeros once done)
};

/// R_i of the @file for `segment` (world ← segment). Throws ConfigError naming
/// "<prefix>.path[<index>]" for non-finite values, a segment shorter than 1e-6 m, or a normal
/// with less than 1e-6 left after removing its component along the segment.
Eigen::Isometry3d segment_frame(const PathSegment& segment, std::size_t index,
                                std::string_view prefix = "segment_follower");

/// x, y, yaw of `T_world_body` in the frame `T_world_segment` (no checks).
SegmentFrameError segment_frame_error(const Eigen::Isometry3d& T_world_segment,
                                      const Eigen::Isometry3d& T_world_body);

/// The control law of the @file for `error` (v, ω only; no checks).
FollowerCommand segment_follower_law(const SegmentFrameError& error,
                                     const SegmentFollowerConfig& config);

class SegmentFollower {
  public:
    /// Validates `config` and every segment (ConfigError, see segment_frame()).
    explicit SegmentFollower(std::vector<PathSegment> path,
                             const SegmentFollowerConfig& config = {});

    /// Advances past finished segments and returns the command for `T_world_body`.
    /// Throws InputError ("segment_follower.T_world_body ...") for a non-finite pose.
    FollowerCommand update(const Eigen::Isometry3d& T_world_body);

    std::size_t segment_index() const { return segment_; }
    bool done() const { return segment_ >= path_.size(); }
    const std::vector<PathSegment>& path() const { return path_; }
    const Eigen::Isometry3d& T_world_segment(std::size_t index) const { return frames_[index]; }

  private:
    std::vector<PathSegment> path_;
    std::vector<Eigen::Isometry3d> frames_;  ///< R_i, world ← segment
    std::vector<double> lengths_m_;          ///< |E_i − B_i|
    SegmentFollowerConfig config_;
    std::size_t segment_ = 0;
};

}  // namespace scantling::control
