#pragma once
// Seeded placement of defect patches on chosen surfaces of a world (private to the simulator).

#include <scantling/sim/world.hpp>
#include <scantling/sim/world_builders.hpp>

#include <span>
#include <string_view>

namespace scantling::sim::detail {

/// Appends `config.count` defects to `world.metadata.defects`, each on a triangle whose tag is
/// in `eligible_tags` (chosen with probability proportional to area), placed so that the whole
/// patch lies on one plane of that surface and is seen unobstructed from 5 cm in front of it
/// (not under a stiffener, not across an opening or an edge), without overlapping another
/// defect. Deterministic for a given seed. Throws ConfigError("<prefix>.count = N, ...") when
/// the surfaces cannot hold that many.
void place_defects(World& world, const DefectPlacementConfig& config,
                   std::span<const int> eligible_tags, std::string_view prefix);

}  // namespace scantling::sim::detail
