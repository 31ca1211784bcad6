// YAML bindings of the safety configs: overrides, defaults kept, and errors naming the file,
// the line and the key (ranges, unknown keys) or the cross-field rule validate() enforces.
#include <gtest/gtest.h>

#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/safety/config_yaml.hpp>

#include "../planning/expect_error.hpp"

namespace scantling::safety {
namespace {

template <class T>
T parse(const io::ConfigSchema<T>& schema, const std::string& yaml, const std::string& prefix) {
    T config{};
    schema.apply(io::parse_yaml_string(yaml, "safety.yaml"), config, prefix);
    return config;
}

TEST(SafetyConfigYaml, CollisionPreventionKeysOverrideOnlyWhatTheyName) {
    const CollisionPreventionConfig config =
        parse(collision_prevention_schema(), "d_att_m: 3\nd_min_m: 1.0\n", "collision_prevention");
    const CollisionPreventionConfig defaults;
    EXPECT_EQ(config.d_att_m, 3.0);
    EXPECT_EQ(config.d_min_m, 1.0);
    EXPECT_EQ(config.robot_radius_m, defaults.robot_radius_m);
    EXPECT_EQ(config.half_fov_vertical_deg, defaults.half_fov_vertical_deg);
    EXPECT_EQ(collision_prevention_schema().keys().size(), 7u);  // every field
}

TEST(SafetyConfigYaml, CollisionPreventionErrorsNameFileLineAndKey) {
    SCANTLING_EXPECT_ERROR(
        parse(collision_prevention_schema(), "d_min_m: 0.8\nhalf_fov_horizontal_deg: 90\n",
              "collision_prevention"),
        ParseError,
        "safety.yaml: line 2: key 'collision_prevention.half_fov_horizontal_deg' = 90, expected "
        "in (0, 90)");
    SCANTLING_EXPECT_ERROR(
        parse(collision_prevention_schema(), "d_att_m: 0.5\n", "collision_prevention"), ConfigError,
        "safety.yaml: collision_prevention.d_att_m = 0.5");
    SCANTLING_EXPECT_ERROR(parse(collision_prevention_schema(), "d_max_m: 3\n", "cp"), ParseError,
                           "line 1: key 'cp.d_max_m': unknown key");
}

TEST(SafetyConfigYaml, HeightKeeping) {
    const HeightKeepingConfig config =
        parse(height_keeping_schema(), "floor_min_m: 0.8\nfloor_att_m: 1.5\n", "height_keeping");
    EXPECT_EQ(config.floor_min_m, 0.8);
    EXPECT_EQ(config.floor_att_m, 1.5);
    EXPECT_EQ(config.ceiling_min_m, HeightKeepingConfig{}.ceiling_min_m);
    EXPECT_EQ(height_keeping_schema().keys().size(), 7u);
    SCANTLING_EXPECT_ERROR(parse(height_keeping_schema(), "floor_att_m: 0.5\n", "height_keeping"),
                           ConfigError, "safety.yaml: height_keeping.floor_att_m = 0.5");
    SCANTLING_EXPECT_ERROR(parse(height_keeping_schema(), "gain_per_s: fast\n", "hk"), ParseError,
                           "key 'hk.gain_per_s': expected a number, got 'fast'");
}

}  // namespace
}  // namespace scantling::safety
