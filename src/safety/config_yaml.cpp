#include <scantling/safety/config_yaml.hpp>

namespace scantling::safety {
namespace {

using io::ConfigSchema;
using io::kNonNegative;
using io::kPositive;

/// A half field of view: (0, 90) degrees.
const io::Range kHalfAngleDeg{
    .min = 0.0, .min_exclusive = true, .max = 90.0, .max_exclusive = true};

}  // namespace

const ConfigSchema<CollisionPreventionConfig>& collision_prevention_schema() {
    static const ConfigSchema<CollisionPreventionConfig> schema = [] {
        using C = CollisionPreventionConfig;
        ConfigSchema<C> s;
        s.field("d_att_m", &C::d_att_m, "attenuation starts here (> d_min_m), m", kPositive)
            .field("d_min_m", &C::d_min_m, "no closer, centre distance (> robot_radius_m), m",
                   kPositive)
            .field("robot_radius_m", &C::robot_radius_m, "d_r: the frustum's near plane, m",
                   kNonNegative)
            .field("repulsion_gain_per_s", &C::repulsion_gain_per_s, "K, 1/s", kPositive)
            .field("max_speed_mps", &C::max_speed_mps, "v_max: the repulsion's clamp, m/s",
                   kPositive)
            .field("half_fov_horizontal_deg", &C::half_fov_horizontal_deg,
                   "half the frustum's horizontal field of view, deg", kHalfAngleDeg)
            .field("half_fov_vertical_deg", &C::half_fov_vertical_deg,
                   "half the frustum's vertical field of view, deg", kHalfAngleDeg);
        return s;
    }();
    return schema;
}

const ConfigSchema<HeightKeepingConfig>& height_keeping_schema() {
    static const ConfigSchema<HeightKeepingConfig> schema = [] {
        using C = HeightKeepingConfig;
        ConfigSchema<C> s;
        s.field("floor_min_m", &C::floor_min_m, "minimum centre height above the floor, m",
                kPositive)
            .field("floor_att_m", &C::floor_att_m, "descent attenuation starts here, m", kPositive)
            .field("ceiling_min_m", &C::ceiling_min_m, "minimum clearance below the ceiling, m",
                   kPositive)
            .field("ceiling_att_m", &C::ceiling_att_m, "climb attenuation starts here, m",
                   kPositive)
            .field("gain_per_s", &C::gain_per_s, "K: push-back per metre inside a minimum, 1/s",
                   kPositive)
            .field("max_vertical_speed_mps", &C::max_vertical_speed_mps, "clamp of the push, m/s",
                   kPositive)
            .field("footprint_radius_m", &C::footprint_radius_m,
                   "radius of the cylinder whose LiDAR points are floor or ceiling, m", kPositive);
        return s;
    }();
    return schema;
}

}  // namespace scantling::safety
