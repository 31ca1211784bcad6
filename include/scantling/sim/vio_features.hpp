#pragma once
/// @file
/// How many visual features a VIO camera sees (issue 3, item 2: VIO "worse in dark and
/// featureless areas"). The scenario runner feeds this into VioSimulator::step.
///
/// Model: a fixed grid of `columns` × `rows` rays through the pixel-cell centres of a pinhole
/// view (the T265-like 90° × 86.7° view of stereo_points.hpp by default), cast from
/// T_world_camera = T_world_body · T_body_sensor (optical frame: x right, y down, z forward).
///   quality = ambient_light · (rays hitting a TEXTURED surface within [min_range_m,
///             max_range_m]) / (columns · rows),
/// so open space, untextured walls and darkness all lower it. Deterministic: no random draws;
/// the result depends only on the scene, the pose and the config. Cost: columns · rows rays.
/// Thread-safety: pure function, safe to call concurrently.

#include <Eigen/Geometry>
#include <string_view>

#include <scantling/sim/camera_model.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim {

struct VioFeatureConfig {
    /// The view the rays go through; only its field of view matters.
    PinholeIntrinsics intrinsics{
        .width = 848, .height = 800, .fx = 424.0, .fy = 424.0, .cx = 423.5, .cy = 399.5};
    int columns = 8;  ///< rays across the image, >= 1
    int rows = 6;     ///< rays down the image, >= 1
    /// Nearer hits count as featureless (out of focus, no stereo overlap); they still occlude.
    double min_range_m = 0.2;
    double max_range_m = 10.0;   ///< farther surfaces give no usable stereo disparity
    double ambient_light = 1.0;  ///< lighting factor in [0, 1] (0 = dark, 1 = well lit)
    /// body ← VIO camera optical frame. Identity looks along body z; `rpy_deg [-90, 0, -90]`
    /// (the scenario's default for VIO) looks along body x.
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();

    /// Throws ConfigError naming the field ("vio_features.rows = 0, expected >= 1").
    void validate(std::string_view prefix = "vio_features") const;
};

/// Feature quality in [0, 1] seen from the vehicle pose `T_world_body` (see the file comment).
/// The config must be valid (validate()).
double vio_feature_quality(const SceneView& scene, const Eigen::Isometry3d& T_world_body,
                           const VioFeatureConfig& config);

}  // namespace scantling::sim
