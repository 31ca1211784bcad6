#pragma once
// The figures of a closed-loop run (closed_loop.hpp, MissionResult), accumulated tick by tick.
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include <scantling/core/point_cloud.hpp>
#include <scantling/localization/local_ekf.hpp>
#include <scantling/mission/closed_loop.hpp>
#include <scantling/odometry/liodom.hpp>
#include <scantling/planning/waypoints.hpp>
#include <scantling/sim/motion_state.hpp>

namespace scantling::mission::detail {

/// Distance from `p` to the polyline `vertices` (one vertex: the distance to it).
double distance_to_polyline(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& vertices);

class LoopMetrics {
  public:
    /// The intended path: from `p_start_world_m` through the waypoints.
    LoopMetrics(const planning::WaypointPath& path, const Eigen::Vector3d& p_start_world_m);

    void add_sweep(const PointCloud& sweep_sensor);
    void add_odometry(const std::optional<odometry::FrameReport>& report);
    void add_tick(const sim::MotionState& truth, const localization::DroneState& estimate,
                  const StackCommand& command, double t_s);
    MissionResult result(control::MissionState final_state) const;

  private:
    std::vector<Eigen::Vector3d> polyline_;
    std::size_t num_waypoints_ = 0;
    double deviation_sum_m_ = 0.0;
    double deviation_max_m_ = 0.0;
    std::size_t deviation_count_ = 0;
    double error_sq_sum_ = 0.0;
    double error_max_m_ = 0.0;
    double final_error_m_ = 0.0;
    double yaw_sq_sum_ = 0.0;
    double nees_sum_ = 0.0;
    std::size_t ticks_ = 0;
    std::size_t nees_count_ = 0;
    double path_length_m_ = 0.0;
    std::optional<Eigen::Vector3d> previous_p_;
    std::size_t reached_ = 0;
    std::size_t interventions_ = 0;
    double min_obstacle_m_ = std::numeric_limits<double>::infinity();
    std::size_t sweeps_ = 0;
    std::size_t odometry_registered_ = 0;
    std::size_t odometry_degenerate_ = 0;
    std::size_t odometry_iterations_ = 0;
    std::size_t odometry_unregistered_ = 0;
    std::optional<double> started_s_;
    std::optional<double> completed_s_;
    double last_t_s_ = 0.0;
    bool completed_ = false;
};

/// mission/summary.json: the scenario's name and the result's figures.
std::string summary_json(const MissionScenario& scenario, const MissionResult& result);

}  // namespace scantling::mission::detail
