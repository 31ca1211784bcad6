// World sections of the scenario schema (scenario_schema.hpp).
#include <scantling/sim/scenario_schema.hpp>

namespace scantling::sim::detail {
namespace {

using io::ConfigSchema;
using io::kNonNegative;
using io::kPositive;
using io::Range;

ConfigSchema<StiffenerConfig> stiffener_schema() {
    ConfigSchema<StiffenerConfig> s;
    s.enum_field("profile", &StiffenerConfig::profile,
                 {{"flat_bar", ProfileKind::FlatBar}, {"angle", ProfileKind::Angle}},
                 "profile of the longitudinals")
        .field("height_m", &StiffenerConfig::height_m, "web height", kPositive)
        .field("thickness_m", &StiffenerConfig::thickness_m, "web and flange thickness", kPositive)
        .field("flange_width_m", &StiffenerConfig::flange_width_m, "angle flange overhang",
               kNonNegative);
    return s;
}

ConfigSchema<DefectPlacementConfig> defects_schema() {
    ConfigSchema<DefectPlacementConfig> s;
    s.field("count", &DefectPlacementConfig::count, "number of defects", kNonNegative)
        .field("min_radius_m", &DefectPlacementConfig::min_radius_m, "patch radius range",
               kPositive)
        .field("max_radius_m", &DefectPlacementConfig::max_radius_m, "", kPositive)
        .field("crack_fraction", &DefectPlacementConfig::crack_fraction, "share of cracks",
               io::kUnitInterval)
        .field("seed", &DefectPlacementConfig::seed, "placement seed");
    return s;
}

ConfigSchema<PlateConfig> plate_schema() {
    ConfigSchema<PlateConfig> s;
    s.field("length_m", &PlateConfig::length_m, "along x", kPositive)
        .field("width_m", &PlateConfig::width_m, "along y", kPositive)
        .field("thickness_m", &PlateConfig::thickness_m, "", kPositive)
        .field("stiffener_spacing_m", &PlateConfig::stiffener_spacing_m, "0 = bare plate",
               kNonNegative)
        .section("stiffener", &PlateConfig::stiffener, stiffener_schema())
        .section("defects", &PlateConfig::defects, defects_schema());
    return s;
}

ConfigSchema<CylinderConfig> cylinder_schema() {
    ConfigSchema<CylinderConfig> s;
    s.field("radius_m", &CylinderConfig::radius_m, "", kPositive)
        .field("height_m", &CylinderConfig::height_m, "", kPositive)
        .field("segments", &CylinderConfig::segments, "facets around", Range{.min = 3})
        .field("closed", &CylinderConfig::closed, "with end caps")
        .section("defects", &CylinderConfig::defects, defects_schema());
    return s;
}

ConfigSchema<StorageTankConfig> storage_tank_schema() {
    using C = StorageTankConfig;
    ConfigSchema<C> s;
    s.field("diameter_m", &C::diameter_m, "", kPositive)
        .field("height_m", &C::height_m, "", kPositive)
        .field("segments", &C::segments, "facets around", Range{.min = 3})
        .field("course_height_m", &C::course_height_m, "ring seam every course", kPositive)
        .field("vertical_seams_per_course", &C::vertical_seams_per_course, "", kNonNegative)
        .field("seam_width_m", &C::seam_width_m, "", kPositive)
        .field("seam_height_m", &C::seam_height_m, "weld bead height", kNonNegative)
        .field("num_nozzles", &C::num_nozzles, "", kNonNegative)
        .field("nozzle_radius_m", &C::nozzle_radius_m, "", kPositive)
        .field("nozzle_length_m", &C::nozzle_length_m, "", kPositive)
        .field("bund_half_size_m", &C::bund_half_size_m,
               "ground and square bund wall of this half-size, m (0 = none)", kNonNegative)
        .field("bund_height_m", &C::bund_height_m, "", kPositive)
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<BallastTankMockupConfig> mockup_schema() {
    using C = BallastTankMockupConfig;
    ConfigSchema<C> s;
    s.field("length_m", &C::length_m, "", kPositive)
        .field("width_m", &C::width_m, "", kPositive)
        .field("height_m", &C::height_m, "", kPositive)
        .field("hopper_width_m", &C::hopper_width_m, "", kNonNegative)
        .field("hopper_height_m", &C::hopper_height_m, "", kNonNegative)
        .field("plate_thickness_m", &C::plate_thickness_m, "web frame", kPositive)
        .field("manhole_width_m", &C::manhole_width_m, "along y", kPositive)
        .field("manhole_height_m", &C::manhole_height_m, "along z", kPositive)
        .field("manhole_centre_y_m", &C::manhole_centre_y_m)
        .field("manhole_centre_z_m", &C::manhole_centre_z_m)
        .field("entry_width_m", &C::entry_width_m, "along y", kPositive)
        .field("entry_length_m", &C::entry_length_m, "along x", kPositive)
        .field("entry_centre_x_m", &C::entry_centre_x_m)
        .field("entry_centre_y_m", &C::entry_centre_y_m)
        .field("longitudinal_spacing_m", &C::longitudinal_spacing_m, "", kPositive)
        .section("stiffener", &C::stiffener, stiffener_schema())
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<BallastTankLargeConfig> large_schema() {
    using C = BallastTankLargeConfig;
    ConfigSchema<C> s;
    s.field("length_m", &C::length_m, "", kPositive)
        .field("width_m", &C::width_m, "", kPositive)
        .field("height_m", &C::height_m, "", kPositive)
        .field("level_height_m", &C::level_height_m, "deck height", kPositive)
        .field("lower_compartments", &C::lower_compartments, "", Range{.min = 1})
        .field("upper_compartments", &C::upper_compartments, "", Range{.min = 1})
        .field("plate_thickness_m", &C::plate_thickness_m, "", kPositive)
        .field("passage_width_m", &C::passage_width_m, "", kPositive)
        .field("passage_height_m", &C::passage_height_m, "", kPositive)
        .field("passage_sill_m", &C::passage_sill_m, "", kNonNegative)
        .field("transition_length_m", &C::transition_length_m, "", kPositive)
        .field("transition_width_m", &C::transition_width_m, "", kPositive)
        .field("entry_width_m", &C::entry_width_m, "", kPositive)
        .field("entry_length_m", &C::entry_length_m, "", kPositive)
        .field("longitudinal_spacing_m", &C::longitudinal_spacing_m, "", kPositive)
        .section("stiffener", &C::stiffener, stiffener_schema())
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<DistillationColumnConfig> column_schema() {
    using C = DistillationColumnConfig;
    ConfigSchema<C> s;
    s.field("diameter_m", &C::diameter_m, "", kPositive)
        .field("num_trays", &C::num_trays, "", Range{.min = 1})
        .field("tray_spacing_m", &C::tray_spacing_m, "", kPositive)
        .field("segments", &C::segments, "", Range{.min = 3})
        .field("tray_thickness_m", &C::tray_thickness_m, "", kPositive)
        .field("downcomer_width_m", &C::downcomer_width_m, "", kPositive)
        .field("weir_height_m", &C::weir_height_m, "", kNonNegative)
        .field("downcomer_clearance_m", &C::downcomer_clearance_m, "", kPositive)
        .field("beams_per_tray", &C::beams_per_tray, "", kNonNegative)
        .field("beam_height_m", &C::beam_height_m, "", kPositive)
        .field("beam_width_m", &C::beam_width_m, "", kPositive)
        .field("manway_width_m", &C::manway_width_m, "", kPositive)
        .field("manway_height_m", &C::manway_height_m, "", kPositive)
        .field("manway_sill_m", &C::manway_sill_m, "", kNonNegative)
        .field("manway_azimuth_rad", &C::manway_azimuth_rad, "direction from the axis")
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<MeshWorldConfig> mesh_schema() {
    using C = MeshWorldConfig;
    ConfigSchema<C> s;
    s.field("path", &C::path, "OBJ/STL/PLY file, relative to the scenario file")
        .field("scale", &C::scale, "", kPositive)
        .field("position_m", &C::position_m, "T_world_mesh translation")
        .field("rpy_rad", &C::rpy_rad, "T_world_mesh roll, pitch, yaw")
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<HullSurroundingsConfig> surroundings_schema() {
    using C = HullSurroundingsConfig;
    ConfigSchema<C> s;
    s.enum_field("environment", &C::environment,
                 {{"none", HullEnvironment::kNone},
                  {"dry_dock", HullEnvironment::kDryDock},
                  {"quay", HullEnvironment::kQuay}})
        .field("end_margin_m", &C::end_margin_m, "", kNonNegative)
        .field("wall_clearance_m", &C::wall_clearance_m, "dry dock", kPositive)
        .field("dock_wall_height_m", &C::dock_wall_height_m, "dry dock", kPositive)
        .field("keel_block_height_m", &C::keel_block_height_m, "dry dock", kPositive)
        .field("draught_m", &C::draught_m, "quay", kPositive)
        .field("fender_gap_m", &C::fender_gap_m, "quay", kPositive)
        .field("water_depth_m", &C::water_depth_m, "quay", kPositive);
    return s;
}

ConfigSchema<ShipHullConfig> ship_hull_schema() {
    using C = ShipHullConfig;
    ConfigSchema<C> s;
    s.field("length_m", &C::length_m, "", kPositive)
        .field("half_breadth_m", &C::half_breadth_m, "", kPositive)
        .field("depth_m", &C::depth_m, "keel to deck edge", kPositive)
        .field("bilge_radius_m", &C::bilge_radius_m, "", kPositive)
        .field("keel_width_m", &C::keel_width_m, "", kPositive)
        .field("keel_height_m", &C::keel_height_m, "", kNonNegative)
        .field("flare_rad", &C::flare_rad)
        .field("side_curvature_m", &C::side_curvature_m, "", kNonNegative)
        .field("sheer_m", &C::sheer_m, "", kNonNegative)
        .field("frame_spacing_m", &C::frame_spacing_m, "", kPositive)
        .field("longitudinal_spacing_m", &C::longitudinal_spacing_m, "", kPositive)
        .section("surroundings", &C::surroundings, surroundings_schema())
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<HullMeshDockConfig> hull_mesh_schema() {
    using C = HullMeshDockConfig;
    ConfigSchema<C> s;
    s.field("path", &C::path, "hull mesh file, relative to the scenario file")
        .field("scale", &C::scale, "file units to metres", kPositive)
        .field("frame_spacing_m", &C::frame_spacing_m, "", kPositive)
        .section("surroundings", &C::surroundings, surroundings_schema())
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<MoebiusConfig> moebius_schema() {
    using C = MoebiusConfig;
    ConfigSchema<C> s;
    s.field("radius_m", &C::radius_m, "", kPositive)
        .field("width_m", &C::width_m, "", kPositive)
        .field("thickness_m", &C::thickness_m, "0 = single sheet", kNonNegative)
        .field("segments_around", &C::segments_around, "", Range{.min = 3})
        .field("segments_across", &C::segments_across, "", Range{.min = 1})
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<UrbanRouteNode> route_node_schema() {
    ConfigSchema<UrbanRouteNode> s;
    s.field("i", &UrbanRouteNode::i, "street along y, x = i pitch_x", kNonNegative)
        .field("j", &UrbanRouteNode::j, "street along x, y = j pitch_y", kNonNegative);
    return s;
}

ConfigSchema<UrbanConfig> urban_schema() {
    using C = UrbanConfig;
    ConfigSchema<C> s;
    s.field("blocks_x", &C::blocks_x, "blocks between streets 0 and blocks_x", Range{.min = 1})
        .field("blocks_y", &C::blocks_y, "blocks between streets 0 and blocks_y", Range{.min = 1})
        .field("block_length_m", &C::block_length_m, "along x, kerb to kerb", kPositive)
        .field("block_width_m", &C::block_width_m, "along y, kerb to kerb", kPositive)
        .field("street_width_m", &C::street_width_m, "kerb to kerb", kPositive)
        .field("sidewalk_width_m", &C::sidewalk_width_m, "kerb to building line", kPositive)
        .field("kerb_height_m", &C::kerb_height_m, "", kNonNegative)
        .field("ground_margin_m", &C::ground_margin_m, "road around the city", kPositive)
        .field("min_height_m", &C::min_height_m, "building height range", kPositive)
        .field("max_height_m", &C::max_height_m, "", kPositive)
        .field("min_frontage_m", &C::min_frontage_m, "building length range", kPositive)
        .field("max_frontage_m", &C::max_frontage_m, "", kPositive)
        .field("min_depth_m", &C::min_depth_m, "building depth range", kPositive)
        .field("max_depth_m", &C::max_depth_m, "", kPositive)
        .field("gap_probability", &C::gap_probability, "gap after a building", io::kUnitInterval)
        .field("min_gap_m", &C::min_gap_m, "gap width range", kPositive)
        .field("max_gap_m", &C::max_gap_m, "", kPositive)
        .field("storey_height_m", &C::storey_height_m, "", kPositive)
        .field("bay_width_m", &C::bay_width_m, "window spacing", kPositive)
        .field("facade_recess_m", &C::facade_recess_m, "glazing behind the piers", kPositive)
        .field("balcony_probability", &C::balcony_probability, "per building", io::kUnitInterval)
        .field("pole_spacing_m", &C::pole_spacing_m, "lamp posts along the kerbs", kPositive)
        .field("tree_probability", &C::tree_probability, "between two posts", io::kUnitInterval)
        .field("parked_car_probability", &C::parked_car_probability, "per 6 m kerb slot",
               io::kUnitInterval)
        .list("route", &C::route, route_node_schema(), "closed loop of crossings {i, j}")
        .field("lane_offset_m", &C::lane_offset_m, "route: right of the centre line", kNonNegative)
        .field("seed", &C::seed, "buildings, gaps, trees, cars")
        .section("defects", &C::defects, defects_schema());
    return s;
}

}  // namespace

const ConfigSchema<WorldSpec>& world_spec_schema() {
    static const ConfigSchema<WorldSpec> schema = [] {
        ConfigSchema<WorldSpec> s;
        s.enum_field("type", &WorldSpec::type,
                     {{"ballast_tank_mockup", WorldType::kBallastTankMockup},
                      {"ballast_tank_large", WorldType::kBallastTankLarge},
                      {"storage_tank", WorldType::kStorageTank},
                      {"distillation_column", WorldType::kDistillationColumn},
                      {"cylinder", WorldType::kCylinder},
                      {"plate", WorldType::kPlate},
                      {"mesh", WorldType::kMesh},
                      {"ship_hull", WorldType::kShipHull},
                      {"moebius", WorldType::kMoebius},
                      {"ship_hull_mesh", WorldType::kShipHullMesh},
                      {"urban", WorldType::kUrban}},
                     "world builder; its parameters go in the section of the same name")
            .section("ballast_tank_mockup", &WorldSpec::ballast_tank_mockup, mockup_schema())
            .section("ballast_tank_large", &WorldSpec::ballast_tank_large, large_schema())
            .section("storage_tank", &WorldSpec::storage_tank, storage_tank_schema())
            .section("distillation_column", &WorldSpec::distillation_column, column_schema())
            .section("cylinder", &WorldSpec::cylinder, cylinder_schema())
            .section("plate", &WorldSpec::plate, plate_schema())
            .section("mesh", &WorldSpec::mesh, mesh_schema())
            .section("ship_hull", &WorldSpec::ship_hull, ship_hull_schema())
            .section("moebius", &WorldSpec::moebius, moebius_schema())
            .section("ship_hull_mesh", &WorldSpec::ship_hull_mesh, hull_mesh_schema())
            .section("urban", &WorldSpec::urban, urban_schema());
        return s;
    }();
    return schema;
}

}  // namespace scantling::sim::detail
