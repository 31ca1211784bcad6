#pragma once
// Appendages of the parametric hull (world_hull_appendages.hpp), private to the simulator.

#include <scantling/sim/world_hull.hpp>

#include <string>

#include "mesh_builder.hpp"

namespace scantling::sim::detail {

/// Adds config.appendages to `builder`, registering a surface only for a kind that is used:
/// nothing at all for the default (empty) appendages. The config must be valid.
void add_hull_appendages(MeshBuilder& builder, const ShipHullConfig& config);

/// ConfigError "<prefix>.anodes[1].z_m = 6, expected in [...] (...)" for a piece off the hull,
/// a non-positive size or, at a quay, an anode or grating above the water line. Call it after
/// the hull's own checks: it relies on a valid hull.
void validate_hull_appendages(const ShipHullConfig& config, const std::string& prefix);

}  // namespace scantling::sim::detail
