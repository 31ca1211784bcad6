// The camera-coverage figure of a run (coverage_spec.hpp).
#include <scantling/mission/coverage_spec.hpp>

#include <cmath>
#include <string>

#include <fmt/format.h>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/io/config_schema.hpp>
#include <scantling/planning/config_yaml.hpp>
#include <scantling/sim/scenario_schema.hpp>

#include "detail/config_nodes.hpp"
#include "detail/mission_schemas.hpp"

namespace scantling::mission {

namespace detail {

const io::ConfigSchema<perception::CameraCoverageConfig>& camera_coverage_config_schema() {
    using S = perception::CameraCoverageConfig;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("cell_size_m", &S::cell_size_m, "grid cell, m", io::kPositive)
            .field("max_range_m", &S::max_range_m, "farther cells are not seen, m", io::kPositive)
            .field("max_incidence_deg", &S::max_incidence_deg, "steeper views do not count, deg")
            .field("max_mm_per_px", &S::max_mm_per_px, "coarser views do not count (0: any)",
                   io::kNonNegative)
            .field("min_views", &S::min_views, "views a cell needs");
        return s;
    }();
    return schema;
}

}  // namespace detail

namespace {

using detail::without;

/// `coverage:` without its rectangle and grid (read separately).
const io::ConfigSchema<CoverageSpec>& coverage_schema() {
    using S = CoverageSpec;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("rate_hz", &S::rate_hz, "views per second", io::kPositive)
            .section("mount", &S::mount, sim::detail::pose_spec_schema(),
                     "body frame; the camera looks along its +x")
            .field("occlusion_margin_m", &S::occlusion_margin_m,
                   "surfaces nearer than this to a cell do not hide it, m", io::kNonNegative);
        return s;
    }();
    return schema;
}

struct CameraSpec {
    int width_px = 1280;
    int height_px = 960;
    double hfov_deg = 66.0;
    double vfov_deg = 49.5;
};

const io::ConfigSchema<CameraSpec>& camera_schema() {
    using S = CameraSpec;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.field("width_px", &S::width_px, "pixels")
            .field("height_px", &S::height_px, "pixels")
            .field("hfov_deg", &S::hfov_deg, "full horizontal field of view, degrees")
            .field("vfov_deg", &S::vfov_deg, "full vertical field of view, degrees");
        return s;
    }();
    return schema;
}

}  // namespace

CoverageSpec coverage_from_yaml(const io::ConfigNode& node,
                                const std::optional<planning::WallRectangle>& default_rectangle,
                                std::string_view missing_why) {
    if (!node.is_map()) io::detail::fail(node, "coverage", "expected a map");
    CoverageSpec spec;
    if (const io::ConfigNode* rectangle = node.find("rectangle")) {
        planning::wall_rectangle_schema().apply(*rectangle, spec.rectangle);
    } else if (default_rectangle) {
        spec.rectangle = *default_rectangle;
    } else {
        io::detail::fail(node, "coverage",
                         fmt::format("missing key 'rectangle' ({})", missing_why));
    }
    CameraSpec camera;
    if (const io::ConfigNode* c = node.find("camera")) camera_schema().apply(*c, camera);
    spec.width_px = camera.width_px;
    spec.height_px = camera.height_px;
    spec.hfov_deg = camera.hfov_deg;
    spec.vfov_deg = camera.vfov_deg;
    const io::ConfigNode rest = without(node, {"rectangle", "camera", "cell_size_m", "max_range_m",
                                               "max_incidence_deg", "max_mm_per_px", "min_views"});
    coverage_schema().apply(rest, spec);
    io::ConfigNode grid =
        without(node, {"rectangle", "camera", "mount", "rate_hz", "occlusion_margin_m"});
    detail::camera_coverage_config_schema().apply(grid, spec.config);
    return spec;
}

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
