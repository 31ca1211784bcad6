#pragma once
/// @file
/// What a closed-loop run measures of the inspection itself (issue 13, item 6): the share of
/// the inspected wall rectangle that a camera on the vehicle saw, judged on the true poses (it
/// is a figure of the run, not something the robot estimates). A mission scenario asks for it
/// with `coverage:`:
///
///   coverage:
///     rectangle: {corner_world_m, normal_world, width_m, height_m}  # default: the mission's
///     camera: {width_px: 1280, height_px: 960, hfov_deg: 66.0, vfov_deg: 49.5}
///     mount: {xyz: [0.15, 0, 0], rpy_deg: [0, 0, 0]}  # body frame; looks along its +x
///     rate_hz: 5
///     cell_size_m: 0.05, max_range_m: 6.0, max_incidence_deg: 60, max_mm_per_px: 0
///     occlusion_margin_m: 0.5
///
/// The camera defaults are the UAV3D paper's (66° × 49.5°). A cell counts as hidden when a
/// surface of the world (or a moving obstacle) lies more than `occlusion_margin_m` in front of
/// it along the line of sight: the rectangle is a plane laid on the structure, which may stand
/// a few centimetres proud of it (a hull's flare), and must not hide its own cells.

#include <Eigen/Geometry>
#include <optional>
#include <string_view>

#include <scantling/io/config_node.hpp>

#include <scantling/core/pinhole_intrinsics.hpp>
#include <scantling/perception/camera_coverage.hpp>
#include <scantling/planning/wall_rectangle.hpp>
#include <scantling/sim/scenario.hpp>

namespace scantling::mission {

struct CoverageSpec {
    planning::WallRectangle rectangle{};
    int width_px = 1280;
    int height_px = 960;
    double hfov_deg = 66.0;
    double vfov_deg = 49.5;
    sim::PoseSpec mount{};  ///< body frame; the optical axis is the mount's +x
    double rate_hz = 5.0;   ///< views per second, > 0
    perception::CameraCoverageConfig config{};
    double occlusion_margin_m = 0.5;  ///< >= 0

    PinholeIntrinsics intrinsics() const;
    /// The optical frame (z forward, x right, y down) in the body frame.
    Eigen::Isometry3d T_body_camera() const;
    /// The rectangle with u = its right, v = its up (u × v = its normal, facing the vehicle).
    perception::InspectionRectangle inspection_rectangle() const;
    /// Throws ConfigError naming "<prefix>.<field>".
    void validate(std::string_view prefix = "coverage") const;
};

/// `coverage:` of a mission document (see the file comment). Without a `rectangle` key the
/// spec takes `default_rectangle` (the mission's), and without one either it is a ParseError
/// naming the file and line and `missing_why`. Unknown keys are errors.
CoverageSpec coverage_from_yaml(const io::ConfigNode& node,
                                const std::optional<planning::WallRectangle>& default_rectangle,
                                std::string_view missing_why);

}  // namespace scantling::mission
