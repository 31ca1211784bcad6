#pragma once
/// @file
/// Procedural inspection worlds of SPEC §10 (and §7, §8), built from Config structs whose
/// defaults are the SPEC values. Every builder validates its config first (ConfigError names
/// the field, e.g. "ballast_tank_mockup.length_m = -1, expected > 0") and is deterministic:
/// the same config gives bit-identical vertices, triangles, tags and metadata.
/// Cost: milliseconds; worlds have a few hundred to a few tens of thousands of triangles.
///
/// Construction: tank shells are single surfaces facing into the tank; internal members (web
/// frames, bulkheads, decks, trays, stiffeners, beams) are closed plates of their thickness,
/// overlapping the walls they are welded to, so no ray passes at a joint. Shared edges carry
/// identical vertices (watertight for the ray caster's robust mode).

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/sim/world.hpp>

namespace scantling::sim {

enum class ProfileKind { FlatBar, Angle };

/// Cross-section of longitudinal stiffeners.
struct StiffenerConfig {
    ProfileKind profile = ProfileKind::FlatBar;
    double height_m = 0.1;         ///< web height, out of the plate it stiffens
    double thickness_m = 0.01;     ///< web and flange thickness
    double flange_width_m = 0.05;  ///< angle profiles: flange overhang beyond the web

    void validate(std::string_view prefix) const;
};

/// Seeded placement of corrosion and crack patches on the walls of a world.
struct DefectPlacementConfig {
    int count = 4;               ///< number of defects (0 = none)
    double min_radius_m = 0.03;  ///< patch radius (crack half-length) range
    double max_radius_m = 0.10;
    double crack_fraction = 0.3;  ///< probability that a defect is a crack, in [0, 1]
    std::uint64_t seed = 1;

    void validate(std::string_view prefix) const;
};

/// An axis-aligned rectangular through-hole of a plate (PlateConfig::holes). Two-element
/// vectors, as the YAML writes them (`centre_m: [1.0, 0.5]`).
struct PlateHoleConfig {
    std::vector<double> centre_m{0.0, 0.0};  ///< x, y of the centre on the plate, m
    std::vector<double> size_m{0.1, 0.1};    ///< sides along x and y, m
};

/// Flat metal plate, x in [-length/2, length/2], y in [-width/2, width/2], top face z = 0.
/// Its World::obstacles hold four kPlateEdge truths along the top outline ("plate_edge_1..4",
/// counter-clockwise from the edge y = -width/2; radius 0.02 m, height -thickness) and one
/// kHole truth per hole ("hole_<i+1>": the capsule inscribed in the rectangle, its axis along
/// the longer side at z = 0, radius half the shorter side, height -thickness).
struct PlateConfig {
    double length_m = 5.0;
    double width_m = 2.0;
    double thickness_m = 0.01;
    double stiffener_spacing_m = 0.0;  ///< 0 = bare plate; else flat bars along x on top
    StiffenerConfig stiffener{};
    DefectPlacementConfig defects{};
    /// Through-holes, each at least kPlateHoleMargin_m inside the outline and clear of the other
    /// holes and of the stiffeners (web and flange seen from above); at most
    /// limits::kMaxSurfaceObstacles.
    std::vector<PlateHoleConfig> holes{};
    /// A crawler on this plate drives on the world mesh (the plate's and the stiffeners' faces,
    /// with the facets' own normals) instead of the plate's bounded top plane: to drive on a
    /// stiffener's top or side. The plane, without stiffeners, is exact and cheaper.
    bool crawler_on_mesh = false;

    void validate(std::string_view prefix = "plate") const;
};

/// Least clearance of a plate hole from the plate's outline, another hole or a stiffener.
inline constexpr double kPlateHoleMargin_m = 0.02;
/// Footprint half-width of a plate edge's truth (World::obstacles).
inline constexpr double kPlateEdgeRadius_m = 0.02;

/// Isolated cylinder (SPEC §9): axis z, base at z = 0, centred on the z axis.
struct CylinderConfig {
    double radius_m = 1.0;
    double height_m = 3.0;
    int segments = 64;   ///< facets around
    bool closed = true;  ///< with end caps
    DefectPlacementConfig defects{};

    void validate(std::string_view prefix = "cylinder") const;
};

/// Vertical storage tank inspected from outside: shell with raised weld seams (ring seams
/// between courses, staggered vertical seams), flat roof and bottom, radial nozzles with
/// blind flanges. Axis z, bottom at z = 0.
struct StorageTankConfig {
    double diameter_m = 12.0;
    double height_m = 21.2;
    int segments = 128;
    double course_height_m = 2.4;  ///< ring seam every course
    int vertical_seams_per_course = 8;
    double seam_width_m = 0.03;
    double seam_height_m = 0.006;  ///< weld bead proud of the shell
    int num_nozzles = 4;
    double nozzle_radius_m = 0.3;
    double nozzle_length_m = 0.5;  ///< from the shell to the flange face
    /// Tank-farm surroundings: a ground slab and a square bund (containment) wall of this
    /// half-size around the tank, metres (0 = the tank alone, floating in empty space). The
    /// bund's corners and the pipe supports beside it break the tank's rotational symmetry.
    double bund_half_size_m = 0.0;
    double bund_height_m = 1.2;
    DefectPlacementConfig defects{};

    void validate(std::string_view prefix = "storage_tank") const;
};

/// Two-compartment topside ballast-tank mock-up (SPEC §7, art. B–E): x in [0, length],
/// y in [0, width] (y = width is the side shell), z in [0, height]. The section has a flat
/// bottom from y = hopper_width to the side shell and a sloped hopper plate rising from
/// (hopper_width, 0) to the inboard side at z = hopper_height. A web frame at x = length/2
/// with a manhole separates the compartments; an entry manhole opens the deck of the first.
/// Longitudinals run along x on every wall, evenly spread at about `longitudinal_spacing_m`.
struct BallastTankMockupConfig {
    double length_m = 5.3;
    double width_m = 2.9;
    double height_m = 1.75;
    double hopper_width_m = 1.3;
    double hopper_height_m = 0.9;
    double plate_thickness_m = 0.01;  ///< web frame
    double manhole_width_m = 0.6;     ///< along y
    double manhole_height_m = 0.8;    ///< along z
    double manhole_centre_y_m = 2.1;
    double manhole_centre_z_m = 0.85;
    double entry_width_m = 0.6;   ///< along y
    double entry_length_m = 0.8;  ///< along x
    double entry_centre_x_m = 1.0;
    double entry_centre_y_m = 2.1;
    double longitudinal_spacing_m = 0.5;
    StiffenerConfig stiffener{};
    DefectPlacementConfig defects{};

    void validate(std::string_view prefix = "ballast_tank_mockup") const;
};

/// Large two-level ballast tank of SPEC §8: x in [0, length], y in [0, width], z in
/// [0, height]; a deck at z = level_height splits it; transverse bulkheads split the lower
/// level into `lower_compartments` and the upper into `upper_compartments` equal lengths.
/// Each bulkhead has a passage near the floor; the deck has a level transition above each
/// listed lower compartment; the top has an entry manhole over the first upper compartment.
/// Side-shell longitudinals on both sides of both levels.
struct BallastTankLargeConfig {
    double length_m = 18.0;
    double width_m = 2.0;
    double height_m = 9.0;
    /// The deck's height: the upper level is 3 m tall (RESULTS-TO-REPRODUCE §4.6, thesis art. G's
    /// tank; the lower level 6 m).
    double level_height_m = 6.0;
    int lower_compartments = 5;  ///< 18 m / 5 = 3.6 m each (SPEC: "5 compartments of 3.5 m")
    int upper_compartments = 3;
    double plate_thickness_m = 0.01;
    double passage_width_m = 0.6;
    double passage_height_m = 0.8;
    double passage_sill_m = 0.3;                     ///< passage bottom edge above the floor
    double transition_length_m = 1.2;                ///< deck opening along x
    double transition_width_m = 1.0;                 ///< deck opening along y
    std::vector<int> transition_compartments{0, 4};  ///< lower compartments with an opening
    double entry_width_m = 0.6;
    double entry_length_m = 0.8;
    double longitudinal_spacing_m = 0.75;
    StiffenerConfig stiffener{};
    DefectPlacementConfig defects{.count = 8};

    void validate(std::string_view prefix = "ballast_tank_large") const;
};

/// Distillation column section (SPEC §7, art. F): vertical Ø 3 m shell, axis z, floor at
/// z = 0, trays at z = k * tray_spacing (k = 1..num_trays), roof one spacing above the last.
/// Each tray has one downcomer: the chord segment of depth `downcomer_width_m` is open and a
/// vertical plate hangs from the chord down to `downcomer_clearance_m` above the tray below;
/// the side alternates (+x for odd k, -x for even k). Support beams run under each tray,
/// parallel to the chord. A man-way opens the wall of the lowest space.
struct DistillationColumnConfig {
    double diameter_m = 3.0;
    int num_trays = 3;
    double tray_spacing_m = 2.0;
    int segments = 96;
    double tray_thickness_m = 0.01;
    double downcomer_width_m = 0.45;
    double weir_height_m = 0.05;          ///< downcomer plate above the tray deck
    double downcomer_clearance_m = 0.05;  ///< gap under the downcomer plate
    int beams_per_tray = 2;
    double beam_height_m = 0.2;
    double beam_width_m = 0.08;
    double manway_width_m = 0.6;
    double manway_height_m = 0.8;
    double manway_sill_m = 0.5;                      ///< bottom edge above the floor
    double manway_azimuth_rad = 1.5707963267948966;  ///< direction from the axis (+y)
    DefectPlacementConfig defects{};

    void validate(std::string_view prefix = "distillation_column") const;
};

/// Any triangle mesh file (OBJ, STL, PLY, ... via io::read_mesh) as a world with one surface
/// "mesh": p_world = T_world_mesh * (scale * p_file), T_world_mesh from position and
/// roll/pitch/yaw (R = Rz(yaw) Ry(pitch) Rx(roll)). E.g. the DTC hull of the shared data with
/// scale 59.407 for full size.
struct MeshWorldConfig {
    std::string path;  ///< mesh file; required
    double scale = 1.0;
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
    Eigen::Vector3d rpy_rad = Eigen::Vector3d::Zero();  ///< roll, pitch, yaw
    DefectPlacementConfig defects{.count = 0};

    void validate(std::string_view prefix = "mesh") const;
};

World build_plate(const PlateConfig& config = {});
World build_cylinder(const CylinderConfig& config = {});
World build_storage_tank(const StorageTankConfig& config = {});
World build_ballast_tank_mockup(const BallastTankMockupConfig& config = {});
World build_ballast_tank_large(const BallastTankLargeConfig& config = {});
World build_distillation_column(const DistillationColumnConfig& config = {});
/// Throws ConfigError for a bad config and FileError / ParseError (from io::read_mesh) for a
/// missing or malformed file.
World build_mesh_world(const MeshWorldConfig& config);

}  // namespace scantling::sim
