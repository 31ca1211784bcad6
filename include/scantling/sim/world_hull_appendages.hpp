#pragma once
/// @file
/// Hull appendages of the parametric ship hull (SPEC §5 obstacles; issue 14, item 6): bilge
/// keels, sacrificial anodes and sea-chest gratings, the things an ROV surveying a hull meets.
/// Opt-in: the default (empty lists) adds nothing, so a hull without them is bit-identical to
/// one built before they existed.
///
/// Frame: the hull frame of world_hull.hpp (x forward, z up, keel bottom z = 0, starboard +y).
/// Each kind is one tagged surface of the world ("bilge_keel", "anode", "sea_chest_grating"),
/// registered only when used. Each piece is a closed solid welded onto the shell: its inner face
/// sits 1 cm inside the shell, so no gap shows between it and the faceted shell.
/// Placement is checked by ShipHullConfig::validate (ConfigError naming
/// "<prefix>.appendages.anodes[i].z_m" and so on).

#include <vector>

namespace scantling::sim {

enum class HullSide {
    kPort,       ///< −y
    kStarboard,  ///< +y (alongside the quay in a quay environment)
};

/// A plate standing out of the bilge normal to it, at 45° between the bottom and the side,
/// on both sides, along x in [x_start_m, x_end_m]; it follows the hull's side curvature.
struct BilgeKeel {
    double x_start_m = 7.5;     ///< must lie in [0, length_m)
    double x_end_m = 22.5;      ///< in (x_start_m, length_m]
    double depth_m = 0.4;       ///< stand-out from the bilge surface, along its normal
    double thickness_m = 0.03;  ///< plate thickness, along the bilge's girth
};

/// A box welded flat onto the side shell (the part above the bilge), centred on the shell point
/// at (x_m, z_m) with its edges along the shell's x and up-the-shell directions.
struct HullAnode {
    HullSide side = HullSide::kPort;
    double x_m = 15.0;          ///< centre, along the hull
    double z_m = 3.0;           ///< centre height; below the draught at a quay
    double length_m = 0.6;      ///< along x
    double height_m = 0.15;     ///< up the shell
    double thickness_m = 0.10;  ///< stand-out from the shell
};

/// Bars over a sea-chest opening: bar_count bars running up the shell, bar_spacing_m apart
/// (centre to centre) along x, centred on the shell point at (x_m, z_m), each standing
/// stand_off_m out of the shell. With an odd count a bar crosses the centre.
struct SeaChestGrating {
    HullSide side = HullSide::kPort;
    double x_m = 10.0;           ///< centre, along the hull
    double z_m = 3.0;            ///< centre height; below the draught at a quay
    int bar_count = 9;           ///< ≥ 1
    double bar_spacing_m = 0.1;  ///< centre to centre, along x; > bar_width_m
    double bar_width_m = 0.02;   ///< along x
    double height_m = 0.6;       ///< bar length, up the shell
    double stand_off_m = 0.05;   ///< bar depth out of the shell
};

/// Appendages of a ShipHullConfig (default: none).
struct HullAppendagesConfig {
    std::vector<BilgeKeel> bilge_keels;  ///< each on both sides
    std::vector<HullAnode> anodes;
    std::vector<SeaChestGrating> gratings;

    bool empty() const { return bilge_keels.empty() && anodes.empty() && gratings.empty(); }
};

}  // namespace scantling::sim
