#pragma once
// The camera-coverage figure of a run (coverage_spec.hpp), fed with the true pose every tick.
#include <Eigen/Geometry>
#include <optional>

#include <scantling/mission/coverage_spec.hpp>
#include <scantling/perception/camera_coverage.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::mission::detail {

class CoverageMonitor {
  public:
    /// `scene` must outlive the monitor (the simulator's).
    CoverageMonitor(const CoverageSpec& spec, const sim::SceneView& scene);

    /// Adds a view when one is due at `t_s` (every 1 / rate_hz).
    void add(double t_s, const Eigen::Isometry3d& T_world_body);
    perception::CoverageResult result() const { return coverage_.result(); }

  private:
    bool occluded(const Eigen::Vector3d& camera_world, const Eigen::Vector3d& cell_world) const;

    CoverageSpec spec_;
    const sim::SceneView& scene_;
    perception::CameraCoverage coverage_;
    Eigen::Isometry3d T_body_camera_;
    std::optional<double> next_view_s_;
};

}  // namespace scantling::mission::detail
