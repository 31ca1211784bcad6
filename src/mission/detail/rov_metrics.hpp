#pragma once
// The figures of an ROV run (rov_mission.hpp, RovMissionResult), accumulated tick by tick on
// the truth: stand-off and heading to the hull by a ray from the true camera centre, the
// estimate's error, the laser pointers' distance against the true optical-axis range.
#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <scantling/localization/local_ekf.hpp>
#include <scantling/mission/rov_mission.hpp>
#include <scantling/sim/motion_state.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::mission::detail {

/// A stand-off sample farther than this is not looking at the hull (a slice's end).
inline constexpr double kMaxStandOffRayM = 3.0;

struct StandOffSample {
    double stand_off_m = 0.0;  ///< perpendicular distance to the surface hit
    double heading_error_rad = 0.0;
};

/// The true stand-off of a camera at `p_camera_world` heading along `yaw_rad` (see
/// rov_mission.hpp); nothing when the horizontal ray meets no surface within
/// kMaxStandOffRayM, or meets one of `skipped_tags` (the appendages: the stand-off is the
/// plating's, and a ray grazing an anode's end would read a 90° heading error).
std::optional<StandOffSample> true_stand_off(const sim::SceneView& scene,
                                             const Eigen::Vector3d& p_camera_world, double yaw_rad,
                                             std::span<const int> skipped_tags = {});

/// The surface tags of the hull appendages present in `scene` (sim/world_hull_appendages.hpp).
std::vector<int> appendage_tags(const sim::SceneView& scene);

class RovMetrics {
  public:
    /// `skipped_tags`: surfaces whose hits are not stand-off samples (appendage_tags).
    RovMetrics(double wanted_stand_off_m, const Eigen::Isometry3d& T_body_camera,
               std::vector<int> skipped_tags = {});

    /// One tick: `scene` at the tick, the stack's command and state.
    void add_tick(const sim::SceneView& scene, const sim::MotionState& truth,
                  const localization::DroneState& estimate, const RovStackCommand& command,
                  double t_s);
    /// A laser-pointer distance against the true range along the optical axis of the camera
    /// at `T_world_camera`.
    void add_laser(const sim::SceneView& scene, const Eigen::Isometry3d& T_world_camera,
                   double distance_m);
    /// The figures; the caller adds the stack's counters and the coverage.
    RovMissionResult result(control::MissionState final_state) const;

  private:
    double wanted_m_;
    Eigen::Isometry3d T_body_camera_;
    std::vector<int> skipped_tags_;
    double stand_off_sum_m_ = 0.0, stand_off_max_m_ = 0.0;
    double heading_sum_rad_ = 0.0, heading_max_rad_ = 0.0;
    std::size_t stand_off_samples_ = 0;
    double error_sq_sum_ = 0.0, error_max_m_ = 0.0, yaw_sq_sum_ = 0.0;
    std::size_t ticks_ = 0;
    double path_length_m_ = 0.0;
    std::optional<Eigen::Vector3d> previous_p_;
    std::size_t paused_ = 0, backing_off_ = 0;
    double laser_error_sum_m_ = 0.0;
    std::size_t laser_samples_ = 0;
    std::optional<double> started_s_, completed_s_;
    double last_t_s_ = 0.0;
};

/// mission/summary.json of an ROV run.
std::string rov_summary_json(const RovMissionScenario& scenario, const RovMissionResult& result);

}  // namespace scantling::mission::detail
