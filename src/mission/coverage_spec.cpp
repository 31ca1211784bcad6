// The camera-coverage figure of a run (coverage_spec.hpp).
#include <scantling/mission/coverage_spec.hpp>

#include <cmath>
#include <string>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::mission {

PinholeIntrinsics CoverageSpec::intrinsics() const {
    return PinholeIntrinsics::from_fov(width_px, height_px, hfov_deg * M_PI / 180.0,
                                       vfov_deg * M_PI / 180.0);
}

Eigen::Isometry3d CoverageSpec::T_body_camera() const {
    // Mount frame x forward, y left, z up -> optical z forward, x right, y down.
    Eigen::Matrix3d R_mount_optical;
    R_mount_optical << 0.0, 0.0, 1.0,  //
        -1.0, 0.0, 0.0,                //
        0.0, -1.0, 0.0;
    Eigen::Isometry3d T = mount.to_isometry();
    T.linear() = T.linear() * R_mount_optical;
    return T;
}

perception::InspectionRectangle CoverageSpec::inspection_rectangle() const {
    const planning::WallAxes axes = planning::wall_axes(rectangle);
    return {.corner_world = rectangle.corner_world_m,
            .u_world = axes.right_world,
            .v_world = axes.up_world,
            .width_m = rectangle.width_m,
            .height_m = rectangle.height_m};
}

void CoverageSpec::validate(std::string_view prefix) const {
    const std::string p(prefix);
    rectangle.validate(p + ".rectangle");
    config_checks::require(rate_hz > 0.0 && std::isfinite(rate_hz), p, "rate_hz", rate_hz,
                           "finite > 0 (views per second)");
    config_checks::require(occlusion_margin_m >= 0.0 && std::isfinite(occlusion_margin_m), p,
                           "occlusion_margin_m", occlusion_margin_m, "finite >= 0");
    if (!mount.xyz.allFinite() || !mount.rpy_deg.allFinite()) {
        throw ConfigError(p + ".mount: expected a finite pose (xyz, rpy_deg)");
    }
    config_checks::require(width_px >= 1 && width_px <= 100000, p + ".camera", "width_px", width_px,
                           "in [1, 100000] pixels");
    config_checks::require(height_px >= 1 && height_px <= 100000, p + ".camera", "height_px",
                           height_px, "in [1, 100000] pixels");
    config_checks::require(hfov_deg > 0.0 && hfov_deg < 180.0, p + ".camera", "hfov_deg", hfov_deg,
                           "in (0, 180) degrees");
    config_checks::require(vfov_deg > 0.0 && vfov_deg < 180.0, p + ".camera", "vfov_deg", vfov_deg,
                           "in (0, 180) degrees");
    config.validate(p);
    inspection_rectangle().validate(p + ".rectangle");
}

}  // namespace scantling::mission
