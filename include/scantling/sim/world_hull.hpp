#pragma once
/// @file
/// Ship-hull worlds of SPEC §5, §10 (issue 3, item 1: `ship_hull`, `moebius`): a parametric hull
/// section, the real DTC hull mesh standing in a dry dock or at a quay, and the Möbius strip of
/// the crawler runs (SPEC §6). Same contract as world_builders.hpp: configs validate first
/// (ConfigError names the field), builders are deterministic (bit-identical for one config) and
/// cost milliseconds (the mesh-file world: the time to read the file).
///
/// Hull frame (the world frame): x forward along the hull, z up, the keel bottom at z = 0, the
/// hull symmetric about (or, for a mesh, centred on) the centreline plane y = 0.
/// Surroundings are built around the hull's extent, so a long-range LiDAR sees what it would
/// see where ships are inspected: a dock floor, dock walls and keel blocks, or water, a quay
/// wall with bollards and the seabed.

#include <Eigen/Core>
#include <string>
#include <string_view>

#include <scantling/sim/world.hpp>
#include <scantling/sim/world_builders.hpp>
#include <scantling/sim/world_hull_appendages.hpp>

namespace scantling::sim {

enum class HullEnvironment {
    kNone,     ///< the hull alone
    kDryDock,  ///< dock floor (surface "dock_floor"), two side walls ("dock_wall"), "keel_blocks"
    kQuay,     ///< "water" surface, "quay_wall", "quay_deck", "bollards", "seabed"
};

/// Where the hull stands. Surfaces are added only for the chosen environment. The "water"
/// surface is a plain tagged plane: sensors may treat it as non-returning (LiDAR) or as a
/// surface (sonar from below); it also spans the hull's inside, hidden by a closed hull.
struct HullSurroundingsConfig {
    HullEnvironment environment = HullEnvironment::kDryDock;
    double end_margin_m = 15.0;  ///< floor / water / quay beyond each end of the hull, along x
    // Dry dock: the hull rests on keel blocks; the dock floor is their foot.
    double wall_clearance_m = 8.0;      ///< widest hull point to each dock wall, along y
    double dock_wall_height_m = 14.0;   ///< dock floor to the top of the walls
    double keel_block_height_m = 1.5;   ///< dock floor to the keel
    double keel_block_length_m = 1.2;   ///< along x
    double keel_block_width_m = 1.8;    ///< along y
    double keel_block_spacing_m = 5.0;  ///< centre to centre, along x
    // Quay: the hull floats at its draught, starboard side (+y) alongside the quay.
    double draught_m = 5.0;           ///< keel to the water surface
    double fender_gap_m = 2.0;        ///< widest hull point to the quay wall, along y
    double quay_height_m = 3.0;       ///< quay deck above the water
    double quay_apron_m = 15.0;       ///< quay deck depth from the wall, along y
    double water_depth_m = 12.0;      ///< water surface to the seabed (> draught_m)
    double water_extent_m = 40.0;     ///< water beyond the hull's port side, along y
    double bollard_spacing_m = 12.0;  ///< along x on the quay deck
    double bollard_radius_m = 0.3;
    double bollard_height_m = 0.7;

    void validate(std::string_view prefix) const;
};

/// Parametric hull section (SPEC §5: a ~30 × 5 m section surveyed by an ROV), x in
/// [0, length_m], symmetric about y = 0, keel bottom z = 0, deck at z = depth_m. Cross-section
/// (each side): a keel of keel_width_m × keel_height_m under the centreline (a narrow one is a
/// bar keel, a wide one a box keel), a flat bottom at z = keel_height_m, a bilge arc of
/// bilge_radius_m turning into the side shell, which leans outward by flare_rad. The section
/// is swept along x: the bottom, bilge and sides move inward by side_curvature_m · s² and the
/// deck edge rises by sheer_m · s², s = 2x/L − 1 (the keel stays straight). A flat deck and
/// two end bulkheads close the section (normals outward).
/// Surfaces: "side_shell", "bilge", "bottom", "keel", "deck", "section_end", plus the
/// surroundings'. Metadata: frames every frame_spacing_m along x (plane x = const, numbered
/// from 0 at x = 0), longitudinals (strake lines on the +y side shell at heights every
/// longitudinal_spacing_m above the bilge, point and axis at midship), landmarks at their
/// crossings (exactly on the shell), defects on side shell, bilge and bottom (possibly under an
/// appendage). Appendages (world_hull_appendages.hpp) add the surfaces "bilge_keel", "anode"
/// and "sea_chest_grating" after the surroundings' (default: none).
struct ShipHullConfig {
    double length_m = 30.0;
    double half_breadth_m = 8.0;  ///< centreline to the side shell at the bilge top
    double depth_m = 8.0;         ///< keel bottom to deck edge at midship
    double bilge_radius_m = 1.5;
    double keel_width_m = 1.0;       ///< full width
    double keel_height_m = 0.4;      ///< below the flat bottom
    double flare_rad = 0.05;         ///< side-shell lean outward from vertical
    double side_curvature_m = 0.3;   ///< inward offset of the sides at both ends
    double sheer_m = 0.0;            ///< deck-edge rise at both ends
    double station_spacing_m = 0.5;  ///< triangulation along x
    double panel_size_m = 0.5;       ///< max edge along the flat parts of the profile
    int bilge_segments = 16;         ///< facets around each bilge quarter circle
    double frame_spacing_m = 0.8;
    double longitudinal_spacing_m = 0.7;
    HullSurroundingsConfig surroundings{};
    DefectPlacementConfig defects{.count = 8};
    HullAppendagesConfig appendages{};

    void validate(std::string_view prefix = "ship_hull") const;
};

/// The real hull of a mesh file (default: none; the shared DTC container-ship model at
/// scale 59.407 gives the full-size 355 m hull). Read with io::read_mesh, scaled, moved so its
/// lowest point is at z = 0 and its bounding box is centred on y = 0 with x starting at 0, and
/// placed on keel blocks (dry dock: blocks under the centreline wherever the bottom is within
/// 5 cm of the keel) or at a quay. Surface "hull" plus the surroundings'. Frames every
/// frame_spacing_m along x.
struct HullMeshDockConfig {
    std::string path;       ///< mesh file; required
    double scale = 59.407;  ///< file units to metres
    double frame_spacing_m = 10.0;
    HullSurroundingsConfig surroundings{.draught_m = 10.8};
    DefectPlacementConfig defects{.count = 0};

    void validate(std::string_view prefix = "ship_hull_mesh") const;
};

/// Möbius strip for the crawler (SPEC §6): centre circle of radius_m in the plane z = 0 around
/// the z axis; p(u, v) = ((R + v cos(u/2)) cos u, (R + v cos(u/2)) sin u, v sin(u/2)),
/// u in [0, 2π), |v| ≤ width_m / 2, so every mid-surface point is within width_m / 2 of the
/// centre circle. The seam is at u = 0 (the +x axis), where v meets −v.
/// Normals: the strip is non-orientable, so with thickness_m = 0 (a single sheet, surface
/// "strip") triangles face n = ∂p/∂u × ∂p/∂v, which flips across the seam; ray casting is
/// double-sided anyway. With thickness_m > 0 the two faces at ±thickness/2 along n join at the
/// seam into one closed, orientable surface ("strip", facing outward) closed by the "rim" along
/// both edges: a robot driving once round comes back on the other face.
/// Vertices: segments_around · (segments_across + 1), twice that with a thickness.
struct MoebiusConfig {
    double radius_m = 2.0;
    double width_m = 1.0;
    double thickness_m = 0.01;  ///< 0 = a single sheet
    int segments_around = 256;
    int segments_across = 16;
    DefectPlacementConfig defects{.count = 0};

    void validate(std::string_view prefix = "moebius") const;
};

World build_ship_hull(const ShipHullConfig& config = {});
/// Throws ConfigError for a bad config (an empty path names "ship_hull_mesh.path") and
/// FileError / ParseError (from io::read_mesh) for a missing or malformed file.
World build_hull_mesh_in_dock(const HullMeshDockConfig& config);
World build_moebius(const MoebiusConfig& config = {});

std::string_view to_string(HullEnvironment environment);

}  // namespace scantling::sim
