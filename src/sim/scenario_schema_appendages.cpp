// `world.ship_hull.appendages` of the scenario schema (world_hull_appendages.hpp): the sizes are
// bounded here, the placement on the hull by ShipHullConfig::validate.
#include <scantling/sim/scenario_schema.hpp>

namespace scantling::sim::detail {
namespace {

using io::ConfigSchema;

const std::vector<std::pair<std::string, HullSide>> kSides{{"port", HullSide::kPort},
                                                           {"starboard", HullSide::kStarboard}};
// Hull coordinates: on a hull of at most kMaxWorldExtent_m.
constexpr io::Range kOnHull = up_to(limits::kMaxWorldExtent_m);

ConfigSchema<BilgeKeel> bilge_keel_schema() {
    ConfigSchema<BilgeKeel> s;
    s.field("x_start_m", &BilgeKeel::x_start_m, "along the hull, from its aft end", kOnHull)
        .field("x_end_m", &BilgeKeel::x_end_m, "", kOnHull)
        .field("depth_m", &BilgeKeel::depth_m, "stand-out from the bilge, normal to it", kExtent)
        .field("thickness_m", &BilgeKeel::thickness_m, "plate thickness", kExtent);
    return s;
}

ConfigSchema<HullAnode> anode_schema() {
    ConfigSchema<HullAnode> s;
    s.enum_field("side", &HullAnode::side, kSides)
        .field("x_m", &HullAnode::x_m, "centre along the hull", kOnHull)
        .field("z_m", &HullAnode::z_m, "centre height on the side shell", kOnHull)
        .field("length_m", &HullAnode::length_m, "along x", kExtent)
        .field("height_m", &HullAnode::height_m, "up the shell", kExtent)
        .field("thickness_m", &HullAnode::thickness_m, "stand-out from the shell", kExtent);
    return s;
}

ConfigSchema<SeaChestGrating> grating_schema() {
    using C = SeaChestGrating;
    ConfigSchema<C> s;
    s.enum_field("side", &C::side, kSides)
        .field("x_m", &C::x_m, "centre along the hull", kOnHull)
        .field("z_m", &C::z_m, "centre height on the side shell", kOnHull)
        .field("bar_count", &C::bar_count, "bars up the shell", between(1, limits::kMaxSegments))
        .field("bar_spacing_m", &C::bar_spacing_m, "centre to centre, along x", kExtent)
        .field("bar_width_m", &C::bar_width_m, "along x", kExtent)
        .field("height_m", &C::height_m, "bar length, up the shell", kExtent)
        .field("stand_off_m", &C::stand_off_m, "bar depth out of the shell", kExtent);
    return s;
}

}  // namespace

ConfigSchema<HullAppendagesConfig> hull_appendages_schema() {
    using C = HullAppendagesConfig;
    ConfigSchema<C> s;
    s.list("bilge_keels", &C::bilge_keels, bilge_keel_schema(), "each on both sides")
        .list("anodes", &C::anodes, anode_schema(), "boxes on the side shell")
        .list("gratings", &C::gratings, grating_schema(), "sea-chest bars on the side shell");
    return s;
}

}  // namespace scantling::sim::detail
