// Validation of the world-builder configs (the builders live in world_<kind>.cpp).
#include <scantling/core/error.hpp>
#include <scantling/sim/world_builders.hpp>

#include <fmt/format.h>

#include "detail/plate_holes.hpp"

#include <cmath>

namespace scantling::sim {
namespace {

void require(bool ok, std::string_view prefix, std::string_view field, double value,
             std::string_view expected) {
    if (!ok)
        throw ConfigError(fmt::format("{}.{} = {}, expected {}", prefix, field, value, expected));
}

void positive(std::string_view prefix, std::string_view field, double value) {
    require(std::isfinite(value) && value > 0.0, prefix, field, value, "> 0");
}

void at_least(std::string_view prefix, std::string_view field, double value, double min) {
    require(std::isfinite(value) && value >= min, prefix, field, value, fmt::format(">= {}", min));
}

void below(std::string_view prefix, std::string_view field, double value, double max,
           std::string_view what) {
    require(std::isfinite(value) && value > 0.0 && value < max, prefix, field, value,
            fmt::format("in (0, {}) ({})", max, what));
}

std::string sub(std::string_view prefix, std::string_view field) {
    return fmt::format("{}.{}", prefix, field);
}

}  // namespace

void StiffenerConfig::validate(std::string_view prefix) const {
    require(profile == ProfileKind::FlatBar || profile == ProfileKind::Angle, prefix, "profile",
            static_cast<int>(profile), "flat_bar or angle");
    positive(prefix, "height_m", height_m);
    below(prefix, "thickness_m", thickness_m, height_m, "thinner than height_m");
    if (profile == ProfileKind::Angle) positive(prefix, "flange_width_m", flange_width_m);
}

void DefectPlacementConfig::validate(std::string_view prefix) const {
    at_least(prefix, "count", count, 0);
    positive(prefix, "min_radius_m", min_radius_m);
    require(std::isfinite(max_radius_m) && max_radius_m >= min_radius_m, prefix, "max_radius_m",
            max_radius_m, fmt::format(">= min_radius_m = {}", min_radius_m));
    require(crack_fraction >= 0.0 && crack_fraction <= 1.0, prefix, "crack_fraction",
            crack_fraction, "in [0, 1]");
}

void PlateConfig::validate(std::string_view prefix) const {
    positive(prefix, "length_m", length_m);
    positive(prefix, "width_m", width_m);
    below(prefix, "thickness_m", thickness_m, std::min(length_m, width_m), "thinner than wide");
    require(std::isfinite(stiffener_spacing_m) && stiffener_spacing_m >= 0.0, prefix,
            "stiffener_spacing_m", stiffener_spacing_m, ">= 0 (0 = no stiffeners)");
    if (stiffener_spacing_m > 0.0) {
        require(stiffener_spacing_m > 2.0 * stiffener.thickness_m + stiffener.flange_width_m,
                prefix, "stiffener_spacing_m", stiffener_spacing_m, "wider than a stiffener");
    }
    stiffener.validate(sub(prefix, "stiffener"));
    defects.validate(sub(prefix, "defects"));
    detail::check_plate_holes(*this, prefix);
}

void CylinderConfig::validate(std::string_view prefix) const {
    positive(prefix, "radius_m", radius_m);
    positive(prefix, "height_m", height_m);
    at_least(prefix, "segments", segments, 3);
    defects.validate(sub(prefix, "defects"));
}

void StorageTankConfig::validate(std::string_view prefix) const {
    positive(prefix, "diameter_m", diameter_m);
    positive(prefix, "height_m", height_m);
    at_least(prefix, "segments", segments, 8);
    positive(prefix, "course_height_m", course_height_m);
    at_least(prefix, "vertical_seams_per_course", vertical_seams_per_course, 0);
    below(prefix, "seam_width_m", seam_width_m, course_height_m, "narrower than a course");
    below(prefix, "seam_height_m", seam_height_m, 0.05 * diameter_m, "a thin bead");
    at_least(prefix, "num_nozzles", num_nozzles, 0);
    below(prefix, "nozzle_radius_m", nozzle_radius_m, std::min(0.25 * diameter_m, 0.25 * height_m),
          "small against the tank");
    positive(prefix, "nozzle_length_m", nozzle_length_m);
    require(segments >= 2 * vertical_seams_per_course, prefix, "segments", segments,
            ">= 2 * vertical_seams_per_course");
    require(bund_half_size_m == 0.0 || bund_half_size_m >= 0.5 * diameter_m + 1.0, prefix,
            "bund_half_size_m", bund_half_size_m, "0 (none) or >= diameter_m / 2 + 1");
    positive(prefix, "bund_height_m", bund_height_m);
    defects.validate(sub(prefix, "defects"));
}

void BallastTankMockupConfig::validate(std::string_view prefix) const {
    positive(prefix, "length_m", length_m);
    positive(prefix, "width_m", width_m);
    positive(prefix, "height_m", height_m);
    below(prefix, "hopper_width_m", hopper_width_m, width_m, "less than width_m");
    below(prefix, "hopper_height_m", hopper_height_m, height_m, "less than height_m");
    below(prefix, "plate_thickness_m", plate_thickness_m, 0.25 * length_m, "a thin plate");
    positive(prefix, "manhole_width_m", manhole_width_m);
    positive(prefix, "manhole_height_m", manhole_height_m);
    positive(prefix, "entry_width_m", entry_width_m);
    positive(prefix, "entry_length_m", entry_length_m);
    below(prefix, "longitudinal_spacing_m", longitudinal_spacing_m, std::max(width_m, height_m),
          "smaller than the tank");
    stiffener.validate(sub(prefix, "stiffener"));
    defects.validate(sub(prefix, "defects"));
    // Placement of the openings is checked by the builder, which knows the section.
}

void BallastTankLargeConfig::validate(std::string_view prefix) const {
    positive(prefix, "length_m", length_m);
    positive(prefix, "width_m", width_m);
    positive(prefix, "height_m", height_m);
    below(prefix, "level_height_m", level_height_m, height_m, "the deck lies inside the tank");
    at_least(prefix, "lower_compartments", lower_compartments, 1);
    at_least(prefix, "upper_compartments", upper_compartments, 1);
    below(prefix, "plate_thickness_m", plate_thickness_m, 0.1, "a thin plate");
    below(prefix, "passage_width_m", passage_width_m, width_m - 2.0 * stiffener.height_m,
          "fits between the side longitudinals");
    const double level_clear = std::min(level_height_m, height_m - level_height_m);
    positive(prefix, "passage_sill_m", passage_sill_m);
    below(prefix, "passage_height_m", passage_height_m, level_clear - passage_sill_m - 0.05,
          "fits in a level above the sill");
    below(prefix, "transition_width_m", transition_width_m, width_m - 2.0 * stiffener.height_m,
          "fits between the side longitudinals");
    below(prefix, "transition_length_m", transition_length_m,
          length_m / std::max(lower_compartments, upper_compartments) - 0.2,
          "fits in one compartment of each level");
    for (std::size_t i = 0; i < transition_compartments.size(); ++i) {
        const int c = transition_compartments[i];
        require(c >= 0 && c < lower_compartments, prefix,
                fmt::format("transition_compartments[{}]", i), c,
                fmt::format("a lower compartment index in [0, {})", lower_compartments));
    }
    below(prefix, "entry_width_m", entry_width_m, width_m - 2.0 * stiffener.height_m,
          "fits between the side longitudinals");
    below(prefix, "entry_length_m", entry_length_m, length_m / upper_compartments - 0.2,
          "fits in one compartment");
    below(prefix, "longitudinal_spacing_m", longitudinal_spacing_m, level_clear,
          "smaller than a level");
    stiffener.validate(sub(prefix, "stiffener"));
    defects.validate(sub(prefix, "defects"));
}

void DistillationColumnConfig::validate(std::string_view prefix) const {
    positive(prefix, "diameter_m", diameter_m);
    at_least(prefix, "num_trays", num_trays, 0);
    positive(prefix, "tray_spacing_m", tray_spacing_m);
    at_least(prefix, "segments", segments, 12);
    below(prefix, "tray_thickness_m", tray_thickness_m, 0.1 * tray_spacing_m, "a thin plate");
    below(prefix, "downcomer_width_m", downcomer_width_m, 0.5 * diameter_m, "less than the radius");
    at_least(prefix, "weir_height_m", weir_height_m, 0.0);
    below(prefix, "downcomer_clearance_m", downcomer_clearance_m, 0.5 * tray_spacing_m,
          "a gap under the downcomer");
    at_least(prefix, "beams_per_tray", beams_per_tray, 0);
    below(prefix, "beam_height_m", beam_height_m, 0.5 * tray_spacing_m, "below the tray");
    below(prefix, "beam_width_m", beam_width_m, 0.25 * diameter_m, "a narrow beam");
    below(prefix, "manway_width_m", manway_width_m, 0.5 * diameter_m, "narrower than the radius");
    positive(prefix, "manway_height_m", manway_height_m);
    const double room =
        num_trays > 0 ? tray_spacing_m - beam_height_m - tray_thickness_m : tray_spacing_m;
    below(prefix, "manway_sill_m", manway_sill_m, room - manway_height_m,
          "the man-way fits under the beams of the first tray");
    require(std::isfinite(manway_azimuth_rad), prefix, "manway_azimuth_rad", manway_azimuth_rad,
            "finite");
    defects.validate(sub(prefix, "defects"));
}

void MeshWorldConfig::validate(std::string_view prefix) const {
    if (path.empty())
        throw ConfigError(fmt::format("{}.path is empty, expected a mesh file", prefix));
    positive(prefix, "scale", scale);
    if (!position_m.allFinite() || !rpy_rad.allFinite()) {
        throw ConfigError(fmt::format("{}.position_m / rpy_rad, expected finite values", prefix));
    }
    defects.validate(sub(prefix, "defects"));
}

}  // namespace scantling::sim
