// The camera-coverage figure of a run (detail/coverage_monitor.hpp).
#include "detail/coverage_monitor.hpp"

#include <cmath>

namespace scantling::mission::detail {

CoverageMonitor::CoverageMonitor(const CoverageSpec& spec, const sim::SceneView& scene)
    : spec_((spec.validate("coverage"), spec)),
      scene_(scene),
      coverage_(spec_.inspection_rectangle(), spec_.intrinsics(), spec_.config),
      T_body_camera_(spec_.T_body_camera()) {}

void CoverageMonitor::add(double t_s, const Eigen::Isometry3d& T_world_body) {
    if (next_view_s_ && t_s < *next_view_s_ - 1e-9) return;
    next_view_s_ = next_view_s_.value_or(t_s) + 1.0 / spec_.rate_hz;
    coverage_.add_view(T_world_body * T_body_camera_,
                       [this](const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
                           return occluded(from, to);
                       });
}

bool CoverageMonitor::occluded(const Eigen::Vector3d& camera_world,
                               const Eigen::Vector3d& cell_world) const {
    const Eigen::Vector3d ray = cell_world - camera_world;
    const double distance_m = ray.norm();
    const double reach_m = distance_m - spec_.occlusion_margin_m;
    if (reach_m <= 1e-6) return false;
    return scene_.cast(camera_world, ray / distance_m, reach_m).hit;
}

}  // namespace scantling::mission::detail
