#pragma once
// Through-holes and the outline of a plate world: their checks, loops and ground truth
// (private to the simulator; PlateConfig in world_builders.hpp).

#include <string_view>
#include <vector>

#include <scantling/sim/surface_obstacles_truth.hpp>
#include <scantling/sim/world_builders.hpp>

#include "mesh_builder.hpp"

namespace scantling::sim::detail {

/// Throws ConfigError naming "<prefix>.holes[i].<field>" for too many holes (checked before
/// the pairwise overlap test), a centre or size that is not two finite values (sizes > 0), a
/// hole closer than kPlateHoleMargin_m to the outline, another hole or a stiffener.
void check_plate_holes(const PlateConfig& config, std::string_view prefix);

/// The holes as loops at height z (counter-clockwise seen from +z).
std::vector<Loop3> plate_hole_loops(const PlateConfig& config, double z);

/// The plate's edges and holes (see PlateConfig).
std::vector<ObstacleTruth> plate_obstacle_truths(const PlateConfig& config);

}  // namespace scantling::sim::detail
