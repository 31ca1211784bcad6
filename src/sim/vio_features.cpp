// Feature quality of a VIO camera from a grid of rays (vio_features.hpp).
#include <scantling/sim/vio_features.hpp>

#include <cmath>
#include <string>

#include <scantling/core/error.hpp>

namespace scantling::sim {
namespace {

std::string key(std::string_view prefix, const char* field) {
    return std::string(prefix) + "." + field;
}

void require_count(std::string_view prefix, const char* field, int value) {
    if (value < 1) {
        throw ConfigError(key(prefix, field) + " = " + std::to_string(value) + ", expected >= 1");
    }
}

/// Pixel at the centre of cell (i, j) of a columns × rows grid over the image.
Eigen::Vector2d cell_centre(const PinholeIntrinsics& k, int i, int j, int columns, int rows) {
    return {(i + 0.5) * k.width / columns - 0.5, (j + 0.5) * k.height / rows - 0.5};
}

}  // namespace

void VioFeatureConfig::validate(std::string_view prefix) const {
    intrinsics.validate(key(prefix, "intrinsics"));
    require_count(prefix, "columns", columns);
    require_count(prefix, "rows", rows);
    if (!(min_range_m >= 0.0) || !(max_range_m > min_range_m) || !std::isfinite(max_range_m)) {
        throw ConfigError(key(prefix, "max_range_m") + " = " + std::to_string(max_range_m) +
                          ", expected finite and > min_range_m = " + std::to_string(min_range_m) +
                          " >= 0");
    }
    if (!(ambient_light >= 0.0 && ambient_light <= 1.0)) {
        throw ConfigError(key(prefix, "ambient_light") + " = " + std::to_string(ambient_light) +
                          ", expected in [0, 1]");
    }
    validate_mount(T_body_sensor, prefix);
}

double vio_feature_quality(const SceneView& scene, const Eigen::Isometry3d& T_world_body,
                           const VioFeatureConfig& config) {
    // Darkness needs no rays (and keeps a dark scenario cheap).
    if (config.ambient_light == 0.0) return 0.0;
    const Eigen::Isometry3d T_world_camera = T_world_body * config.T_body_sensor;
    int textured_hits = 0;
    for (int j = 0; j < config.rows; ++j) {
        for (int i = 0; i < config.columns; ++i) {
            const Eigen::Vector2d pixel =
                cell_centre(config.intrinsics, i, j, config.columns, config.rows);
            const Ray ray{
                .origin = T_world_camera.translation(),
                .direction = T_world_camera.linear() * config.intrinsics.ray_direction(pixel),
                .max_range_m = config.max_range_m,
                .min_range_m = 0.0};
            // Near surfaces still occlude: they count as featureless, not as see-through.
            const RayHit hit = scene.cast(ray);
            if (hit.hit && hit.range_m >= config.min_range_m &&
                surface_of(scene.metadata, hit.surface_tag).textured) {
                ++textured_hits;
            }
        }
    }
    return config.ambient_light * textured_hits / (config.columns * config.rows);
}

}  // namespace scantling::sim
