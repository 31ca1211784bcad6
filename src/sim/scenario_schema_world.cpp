// World sections of the scenario schema (scenario_schema.hpp).
#include <scantling/sim/scenario_schema.hpp>

namespace scantling::sim::detail {
namespace {

using io::ConfigSchema;
using io::Range;

ConfigSchema<StiffenerConfig> stiffener_schema() {
    ConfigSchema<StiffenerConfig> s;
    s.enum_field("profile", &StiffenerConfig::profile,
                 {{"flat_bar", ProfileKind::FlatBar}, {"angle", ProfileKind::Angle}},
                 "profile of the longitudinals")
        .field("height_m", &StiffenerConfig::height_m, "web height", kExtent)
        .field("thickness_m", &StiffenerConfig::thickness_m, "web and flange thickness", kExtent)
        .field("flange_width_m", &StiffenerConfig::flange_width_m, "angle flange overhang",
               up_to(limits::kMaxWorldExtent_m));
    return s;
}

ConfigSchema<DefectPlacementConfig> defects_schema() {
    ConfigSchema<DefectPlacementConfig> s;
    s.field("count", &DefectPlacementConfig::count, "number of defects", up_to(limits::kMaxDefects))
        .field("min_radius_m", &DefectPlacementConfig::min_radius_m, "patch radius range", kExtent)
        .field("max_radius_m", &DefectPlacementConfig::max_radius_m, "", kExtent)
        .field("crack_fraction", &DefectPlacementConfig::crack_fraction, "share of cracks",
               io::kUnitInterval)
        .field("seed", &DefectPlacementConfig::seed, "placement seed");
    return s;
}

ConfigSchema<PlateConfig> plate_schema() {
    ConfigSchema<PlateConfig> s;
    s.field("length_m", &PlateConfig::length_m, "along x", kExtent)
        .field("width_m", &PlateConfig::width_m, "along y", kExtent)
        .field("thickness_m", &PlateConfig::thickness_m, "", kExtent)
        .field("stiffener_spacing_m", &PlateConfig::stiffener_spacing_m,
               "0 = bare plate, else at least 0.1", up_to(limits::kMaxWorldExtent_m))
        .section("stiffener", &PlateConfig::stiffener, stiffener_schema())
        .section("defects", &PlateConfig::defects, defects_schema())
        .list("holes", &PlateConfig::holes, plate_hole_schema(),
              "axis-aligned rectangular through-holes")
        .field("crawler_on_mesh", &PlateConfig::crawler_on_mesh,
               "a crawler drives on the mesh's faces (the stiffeners' too), not the top plane");
    return s;
}

ConfigSchema<CylinderConfig> cylinder_schema() {
    ConfigSchema<CylinderConfig> s;
    s.field("radius_m", &CylinderConfig::radius_m, "", kExtent)
        .field("height_m", &CylinderConfig::height_m, "", kExtent)
        .field("segments", &CylinderConfig::segments, "facets around",
               between(3, limits::kMaxSegments))
        .field("closed", &CylinderConfig::closed, "with end caps")
        .section("defects", &CylinderConfig::defects, defects_schema());
    return s;
}

ConfigSchema<StorageTankConfig> storage_tank_schema() {
    using C = StorageTankConfig;
    ConfigSchema<C> s;
    s.field("diameter_m", &C::diameter_m, "", kExtent)
        .field("height_m", &C::height_m, "", kExtent)
        .field("segments", &C::segments, "facets around", between(3, limits::kMaxSegments))
        .field("course_height_m", &C::course_height_m, "ring seam every course", kSpacing)
        .field("vertical_seams_per_course", &C::vertical_seams_per_course, "",
               up_to(limits::kMaxStructureCount))
        .field("seam_width_m", &C::seam_width_m, "", kExtent)
        .field("seam_height_m", &C::seam_height_m, "weld bead height",
               up_to(limits::kMaxWorldExtent_m))
        .field("num_nozzles", &C::num_nozzles, "", up_to(limits::kMaxStructureCount))
        .field("nozzle_radius_m", &C::nozzle_radius_m, "", kExtent)
        .field("nozzle_length_m", &C::nozzle_length_m, "", kExtent)
        .field("bund_half_size_m", &C::bund_half_size_m,
               "ground and square bund wall of this half-size, m (0 = none)",
               up_to(limits::kMaxWorldExtent_m))
        .field("bund_height_m", &C::bund_height_m, "", kExtent)
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<BallastTankMockupConfig> mockup_schema() {
    using C = BallastTankMockupConfig;
    ConfigSchema<C> s;
    s.field("length_m", &C::length_m, "", kExtent)
        .field("width_m", &C::width_m, "", kExtent)
        .field("height_m", &C::height_m, "", kExtent)
        .field("hopper_width_m", &C::hopper_width_m, "", up_to(limits::kMaxWorldExtent_m))
        .field("hopper_height_m", &C::hopper_height_m, "", up_to(limits::kMaxWorldExtent_m))
        .field("plate_thickness_m", &C::plate_thickness_m, "web frame", kExtent)
        .field("manhole_width_m", &C::manhole_width_m, "along y", kExtent)
        .field("manhole_height_m", &C::manhole_height_m, "along z", kExtent)
        .field("manhole_centre_y_m", &C::manhole_centre_y_m)
        .field("manhole_centre_z_m", &C::manhole_centre_z_m)
        .field("entry_width_m", &C::entry_width_m, "along y", kExtent)
        .field("entry_length_m", &C::entry_length_m, "along x", kExtent)
        .field("entry_centre_x_m", &C::entry_centre_x_m)
        .field("entry_centre_y_m", &C::entry_centre_y_m)
        .field("longitudinal_spacing_m", &C::longitudinal_spacing_m, "", kSpacing)
        .section("stiffener", &C::stiffener, stiffener_schema())
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<BallastTankLargeConfig> large_schema() {
    using C = BallastTankLargeConfig;
    ConfigSchema<C> s;
    s.field("length_m", &C::length_m, "", kExtent)
        .field("width_m", &C::width_m, "", kExtent)
        .field("height_m", &C::height_m, "", kExtent)
        .field("level_height_m", &C::level_height_m, "deck height", kExtent)
        .field("lower_compartments", &C::lower_compartments, "",
               between(1, limits::kMaxStructureCount))
        .field("upper_compartments", &C::upper_compartments, "",
               between(1, limits::kMaxStructureCount))
        .field("plate_thickness_m", &C::plate_thickness_m, "", kExtent)
        .field("passage_width_m", &C::passage_width_m, "", kExtent)
        .field("passage_height_m", &C::passage_height_m, "", kExtent)
        .field("passage_sill_m", &C::passage_sill_m, "", up_to(limits::kMaxWorldExtent_m))
        .field("transition_length_m", &C::transition_length_m, "", kExtent)
        .field("transition_width_m", &C::transition_width_m, "", kExtent)
        .field("entry_width_m", &C::entry_width_m, "", kExtent)
        .field("entry_length_m", &C::entry_length_m, "", kExtent)
        .field("longitudinal_spacing_m", &C::longitudinal_spacing_m, "", kSpacing)
        .section("stiffener", &C::stiffener, stiffener_schema())
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<DistillationColumnConfig> column_schema() {
    using C = DistillationColumnConfig;
    ConfigSchema<C> s;
    s.field("diameter_m", &C::diameter_m, "", kExtent)
        .field("num_trays", &C::num_trays, "", between(1, limits::kMaxStructureCount))
        .field("tray_spacing_m", &C::tray_spacing_m, "", kSpacing)
        .field("segments", &C::segments, "", between(3, limits::kMaxSegments))
        .field("tray_thickness_m", &C::tray_thickness_m, "", kExtent)
        .field("downcomer_width_m", &C::downcomer_width_m, "", kExtent)
        .field("weir_height_m", &C::weir_height_m, "", up_to(limits::kMaxWorldExtent_m))
        .field("downcomer_clearance_m", &C::downcomer_clearance_m, "", kExtent)
        .field("beams_per_tray", &C::beams_per_tray, "", up_to(limits::kMaxStructureCount))
        .field("beam_height_m", &C::beam_height_m, "", kExtent)
        .field("beam_width_m", &C::beam_width_m, "", kExtent)
        .field("manway_width_m", &C::manway_width_m, "", kExtent)
        .field("manway_height_m", &C::manway_height_m, "", kExtent)
        .field("manway_sill_m", &C::manway_sill_m, "", up_to(limits::kMaxWorldExtent_m))
        .field("manway_azimuth_rad", &C::manway_azimuth_rad, "direction from the axis")
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<MeshWorldConfig> mesh_schema() {
    using C = MeshWorldConfig;
    ConfigSchema<C> s;
    s.field("path", &C::path, "OBJ/STL/PLY file, relative to the scenario file")
        .field("scale", &C::scale, "", positive_up_to(limits::kMaxMeshScale))
        .field("position_m", &C::position_m, "T_world_mesh translation", kCoordinate)
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
        .field("end_margin_m", &C::end_margin_m, "", up_to(limits::kMaxWorldExtent_m))
        .field("wall_clearance_m", &C::wall_clearance_m, "dry dock", kExtent)
        .field("dock_wall_height_m", &C::dock_wall_height_m, "dry dock", kExtent)
        .field("keel_block_height_m", &C::keel_block_height_m, "dry dock", kExtent)
        .field("draught_m", &C::draught_m, "quay", kExtent)
        .field("fender_gap_m", &C::fender_gap_m, "quay", kExtent)
        .field("water_depth_m", &C::water_depth_m, "quay", kExtent);
    return s;
}

ConfigSchema<ShipHullConfig> ship_hull_schema() {
    using C = ShipHullConfig;
    ConfigSchema<C> s;
    s.field("length_m", &C::length_m, "", kExtent)
        .field("half_breadth_m", &C::half_breadth_m, "", kExtent)
        .field("depth_m", &C::depth_m, "keel to deck edge", kExtent)
        .field("bilge_radius_m", &C::bilge_radius_m, "", kExtent)
        .field("keel_width_m", &C::keel_width_m, "", kExtent)
        .field("keel_height_m", &C::keel_height_m, "", up_to(limits::kMaxWorldExtent_m))
        .field("flare_rad", &C::flare_rad)
        .field("side_curvature_m", &C::side_curvature_m, "", up_to(limits::kMaxWorldExtent_m))
        .field("sheer_m", &C::sheer_m, "", up_to(limits::kMaxWorldExtent_m))
        .field("frame_spacing_m", &C::frame_spacing_m, "", kSpacing)
        .field("longitudinal_spacing_m", &C::longitudinal_spacing_m, "", kSpacing)
        .section("surroundings", &C::surroundings, surroundings_schema())
        .section("defects", &C::defects, defects_schema())
        .section("appendages", &C::appendages, hull_appendages_schema(), "default: none");
    return s;
}

ConfigSchema<HullMeshDockConfig> hull_mesh_schema() {
    using C = HullMeshDockConfig;
    ConfigSchema<C> s;
    s.field("path", &C::path, "hull mesh file, relative to the scenario file")
        .field("scale", &C::scale, "file units to metres", positive_up_to(limits::kMaxMeshScale))
        .field("frame_spacing_m", &C::frame_spacing_m, "", kSpacing)
        .section("surroundings", &C::surroundings, surroundings_schema())
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<MoebiusConfig> moebius_schema() {
    using C = MoebiusConfig;
    ConfigSchema<C> s;
    s.field("radius_m", &C::radius_m, "", kExtent)
        .field("width_m", &C::width_m, "", kExtent)
        .field("thickness_m", &C::thickness_m, "0 = single sheet", up_to(limits::kMaxWorldExtent_m))
        .field("segments_around", &C::segments_around, "", between(3, limits::kMaxSegments))
        .field("segments_across", &C::segments_across, "", between(1, limits::kMaxSegments))
        .section("defects", &C::defects, defects_schema());
    return s;
}

ConfigSchema<UrbanRouteNode> route_node_schema() {
    ConfigSchema<UrbanRouteNode> s;
    s.field("i", &UrbanRouteNode::i, "street along y, x = i pitch_x",
            up_to(limits::kMaxUrbanBlocks))
        .field("j", &UrbanRouteNode::j, "street along x, y = j pitch_y",
               up_to(limits::kMaxUrbanBlocks));
    return s;
}

ConfigSchema<UrbanConfig> urban_schema() {
    using C = UrbanConfig;
    ConfigSchema<C> s;
    s.field("blocks_x", &C::blocks_x, "blocks between streets 0 and blocks_x",
            between(1, limits::kMaxUrbanBlocks))
        .field("blocks_y", &C::blocks_y, "blocks between streets 0 and blocks_y",
               between(1, limits::kMaxUrbanBlocks))
        .field("block_length_m", &C::block_length_m, "along x, kerb to kerb", kExtent)
        .field("block_width_m", &C::block_width_m, "along y, kerb to kerb", kExtent)
        .field("street_width_m", &C::street_width_m, "kerb to kerb", kExtent)
        .field("sidewalk_width_m", &C::sidewalk_width_m, "kerb to building line", kExtent)
        .field("kerb_height_m", &C::kerb_height_m, "", up_to(limits::kMaxWorldExtent_m))
        .field("ground_margin_m", &C::ground_margin_m, "road around the city", kExtent)
        .field("min_height_m", &C::min_height_m, "building height range", kExtent)
        .field("max_height_m", &C::max_height_m, "", kExtent)
        .field("min_frontage_m", &C::min_frontage_m, "building length range", kSpacing)
        .field("max_frontage_m", &C::max_frontage_m, "", kExtent)
        .field("min_depth_m", &C::min_depth_m, "building depth range", kExtent)
        .field("max_depth_m", &C::max_depth_m, "", kExtent)
        .field("gap_probability", &C::gap_probability, "gap after a building", io::kUnitInterval)
        .field("min_gap_m", &C::min_gap_m, "gap width range", kExtent)
        .field("max_gap_m", &C::max_gap_m, "", kExtent)
        .field("storey_height_m", &C::storey_height_m, "", kSpacing)
        .field("bay_width_m", &C::bay_width_m, "window spacing", kSpacing)
        .field("facade_recess_m", &C::facade_recess_m, "glazing behind the piers", kExtent)
        .field("balcony_probability", &C::balcony_probability, "per building", io::kUnitInterval)
        .field("pole_spacing_m", &C::pole_spacing_m, "lamp posts along the kerbs", kSpacing)
        .field("tree_probability", &C::tree_probability, "between two posts", io::kUnitInterval)
        .field("parked_car_probability", &C::parked_car_probability, "per 6 m kerb slot",
               io::kUnitInterval)
        .list("route", &C::route, route_node_schema(), "closed loop of crossings {i, j}")
        .field("lane_offset_m", &C::lane_offset_m, "route: right of the centre line",
               up_to(limits::kMaxWorldExtent_m))
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
            .section("urban", &WorldSpec::urban, urban_schema())
            .list("obstacles", &WorldSpec::obstacles, surface_obstacle_schema(),
                  "bolts, brackets and weld beads on the crawler's surface, any type");
        return s;
    }();
    return schema;
}

}  // namespace scantling::sim::detail
