// Bounds on the repeated structure of a scenario's world (detail/scenario_checks.hpp).
//
// Each key's range (scenario_schema_world.cpp) bounds one value; these checks bound the
// products that multiply in the builders: a storage tank is courses x (segments + seams) shell
// plates and seam beads, a Moebius strip segments_around x segments_across quads, an urban
// block's facades (perimeter x height) / (storey x bay) windows. Measured (Release, one core)
// near kMaxWorldElements: a tank of 97 courses x 1032 builds in 39 s and 140 MB, a strip of
// 4096 x 61 (2.5e5) in 2.4 s and 210 MB, 16 x 16 default urban blocks (2e5) in 3.1 s and
// 340 MB; without these checks a 4096 x 4096 strip exhausted a 3 GB address space.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/sim/scenario_limits.hpp>

#include "detail/scenario_checks.hpp"

namespace scantling::sim::detail {
namespace {

void check_elements(std::string_view prefix, std::string_view formula, double elements) {
    if (elements <= static_cast<double>(limits::kMaxWorldElements)) return;
    throw ConfigError(fmt::format(
        "{}: {} = {:.3g} repeated elements, expected <= {} (the world mesh would not fit in "
        "memory); make the structure coarser or smaller",
        prefix, formula, elements, limits::kMaxWorldElements));
}

void check_storage_tank(const StorageTankConfig& c, std::string_view prefix) {
    const double courses = std::ceil(c.height_m / c.course_height_m);
    check_elements(prefix, "height_m / course_height_m x (segments + vertical_seams_per_course)",
                   courses * (c.segments + c.vertical_seams_per_course));
}

void check_urban(const UrbanConfig& c, std::string_view prefix) {
    const double facade_m2 = 2.0 * (c.block_length_m + c.block_width_m) * c.max_height_m;
    check_elements(prefix,
                   "blocks_x x blocks_y x 2 (block_length_m + block_width_m) x max_height_m / "
                   "(storey_height_m x bay_width_m)",
                   c.blocks_x * c.blocks_y * facade_m2 / (c.storey_height_m * c.bay_width_m));
}

/// Each surface obstacle is its own mesh and truth (and plate holes are checked pairwise):
/// counted before any of them is validated or built.
void check_surface_obstacles(const WorldSpec& spec, std::string_view prefix) {
    const std::size_t holes = spec.type == WorldType::kPlate ? spec.plate.holes.size() : 0;
    if (spec.obstacles.size() + holes <= limits::kMaxSurfaceObstacles) return;
    throw ConfigError(fmt::format(
        "{}.obstacles has {} obstacles and {}.plate.holes {} holes, expected at most {} in all",
        prefix, spec.obstacles.size(), prefix, holes, limits::kMaxSurfaceObstacles));
}

}  // namespace

void check_world_size(const WorldSpec& spec, std::string_view prefix) {
    check_surface_obstacles(spec, prefix);
    const std::string p = fmt::format("{}.{}", prefix, to_string(spec.type));
    if (spec.type == WorldType::kStorageTank) check_storage_tank(spec.storage_tank, p);
    if (spec.type == WorldType::kUrban) check_urban(spec.urban, p);
    if (spec.type == WorldType::kMoebius) {
        const MoebiusConfig& c = spec.moebius;
        check_elements(p, "segments_around x segments_across",
                       static_cast<double>(c.segments_around) * c.segments_across);
    }
    const double spacing_m = spec.plate.stiffener_spacing_m;
    if (spec.type == WorldType::kPlate && spacing_m > 0.0 &&
        spacing_m < limits::kMinStructureSpacing_m) {
        // A range cannot say "0 or at least": stiffeners are counted as width / spacing.
        throw ConfigError(
            fmt::format("{}.stiffener_spacing_m = {}, expected 0 (bare plate) or "
                        ">= {} m",
                        p, spacing_m, limits::kMinStructureSpacing_m));
    }
}

}  // namespace scantling::sim::detail
