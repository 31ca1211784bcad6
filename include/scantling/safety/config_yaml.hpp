#pragma once
/// @file
/// YAML bindings of the safety module (io::ConfigSchema): collision prevention (SPEC §3) and
/// height keeping. Each key is registered once; its default stays in the struct's in-class
/// initialiser. `schema.apply(node, config, "collision_prevention")` overwrites the keys the
/// document names and validates, with errors naming the file, the line and the key path
/// ("x.yaml: line 4: key 'collision_prevention.d_min_m' = -1, expected > 0"); unknown keys
/// are errors.
///
/// Thread-safety: the schemas are built once (function-local statics) and immutable.

#include <scantling/io/config_schema.hpp>
#include <scantling/safety/collision_prevention.hpp>
#include <scantling/safety/height_keeping.hpp>

namespace scantling::safety {

const io::ConfigSchema<CollisionPreventionConfig>& collision_prevention_schema();
const io::ConfigSchema<HeightKeepingConfig>& height_keeping_schema();

}  // namespace scantling::safety
