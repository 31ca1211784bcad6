#pragma once
// Dry dock and quay around a hull, shared by the parametric and the mesh hull worlds (private
// to the simulator). Config checks come from sensor_checks.hpp.

#include "mesh_builder.hpp"
#include "sensor_checks.hpp"

#include <scantling/sim/world_hull.hpp>

#include <string_view>
#include <vector>

namespace scantling::sim::detail {

/// What the surroundings need to know about the hull (world frame, metres).
struct HullExtent {
    double x_min_m = 0.0;
    double x_max_m = 0.0;
    double half_breadth_m = 0.0;    ///< widest |y|
    double keel_z_m = 0.0;          ///< lowest hull point
    std::vector<double> block_x_m;  ///< keel-block centres (dry dock)
};

/// Adds the surfaces of `config.environment` around `hull`.
void add_surroundings(MeshBuilder& builder, const HullExtent& hull,
                      const HullSurroundingsConfig& config);

/// Positions every spacing_m along [x_min, x_max] (as many as fit), centred in that range: keel
/// blocks, bollards.
std::vector<double> centred_positions(double x_min_m, double x_max_m, double spacing_m);

}  // namespace scantling::sim::detail
