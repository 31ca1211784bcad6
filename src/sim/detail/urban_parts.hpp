#pragma once
// Buildings, kerbs and street furniture of the urban world (private to the simulator).
//
// Every part is placed in a street-side frame: `along` runs along the kerb, `inward` points
// from the street into the block, z is up and the road is at z = 0.

#include "mesh_builder.hpp"

#include <scantling/sim/world_urban.hpp>

#include <Eigen/Core>

namespace scantling::sim::detail {

/// Surface tags of the urban world, registered in a fixed order.
struct UrbanTags {
    int road, sidewalk, kerb, building_wall, window, facade, roof, balcony, pole, tree_trunk,
        tree_crown, parked_car;
};

UrbanTags add_urban_surfaces(MeshBuilder& builder);

/// One side of a block that faces a street.
struct StreetSide {
    Eigen::Vector3d kerb_start = Eigen::Vector3d::Zero();  ///< block corner on the kerb, z = 0
    Eigen::Vector3d along = Eigen::Vector3d::UnitX();      ///< unit, along the kerb
    Eigen::Vector3d inward = Eigen::Vector3d::UnitY();     ///< unit, into the block
    double length_m = 0.0;                                 ///< kerb length
};

/// A building on a street side: frontage [start_m, start_m + frontage_m] along the kerb.
struct BuildingSpec {
    double start_m = 0.0;
    double frontage_m = 0.0;
    double depth_m = 0.0;
    double height_m = 0.0;  ///< above the sidewalk
    int door_bay = 0;       ///< ground-floor bay without a sill band (-1: none)
    bool balconies = false;
    /// Corner building: the side wall at the start (end) of the frontage faces a cross street,
    /// so it gets a facade too, flush with that street's building line.
    bool corner_start = false;
    bool corner_end = false;
};

/// Number of window bays of a frontage (at least one).
int bay_count(const UrbanConfig& config, double frontage_m);

/// The body (glazing in front, walls, roof), the pier-and-band facade and the balconies.
void add_building(MeshBuilder& builder, const UrbanConfig& config, const UrbanTags& tags,
                  const StreetSide& side, const BuildingSpec& building);

/// The raised sidewalk of the block [x0, x1] × [y0, y1]: top and kerbs, no bottom.
void add_block_platform(MeshBuilder& builder, const UrbanConfig& config, const UrbanTags& tags,
                        const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy);

/// Lamp post at `at_m` along the side, its arm reaching over the street.
void add_lamp_post(MeshBuilder& builder, const UrbanConfig& config, const UrbanTags& tags,
                   const StreetSide& side, double at_m);

/// Tree on the sidewalk: trunk and a low-poly crown.
void add_tree(MeshBuilder& builder, const UrbanConfig& config, const UrbanTags& tags,
              const StreetSide& side, double at_m, double trunk_height_m, double crown_radius_m);

/// Parked car on the road along the kerb, centred at `at_m`; the cabin is shifted by
/// `cabin_shift_m` along the car.
void add_parked_car(MeshBuilder& builder, const UrbanTags& tags, const StreetSide& side,
                    double at_m, double cabin_shift_m);

}  // namespace scantling::sim::detail
