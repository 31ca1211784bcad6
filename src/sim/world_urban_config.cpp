// Validation of the urban world's config (world_urban.hpp).
#include <scantling/sim/world_urban.hpp>

#include <scantling/core/error.hpp>

#include "detail/sensor_checks.hpp"

#include <fmt/format.h>

#include <cmath>

namespace scantling::sim {
namespace {

using detail::require;

bool finite_at_least(double value, double min) { return std::isfinite(value) && value >= min; }

std::string node_text(const UrbanRouteNode& n) { return fmt::format("({}, {})", n.i, n.j); }

// A closed loop of crossings joined by straight streets, never turning back.
void check_route(const UrbanConfig& c, std::string_view prefix) {
    const std::size_t n = c.route.size();
    require(n >= 4, prefix, "route.size", static_cast<double>(n), ">= 4 crossings (a closed loop)");
    for (std::size_t k = 0; k < n; ++k) {
        const UrbanRouteNode& p = c.route[k];
        if (p.i < 0 || p.i > c.blocks_x || p.j < 0 || p.j > c.blocks_y) {
            throw ConfigError(
                fmt::format("{}.route[{}] = {}, expected i in [0, {}] and j in [0, {}]", prefix, k,
                            node_text(p), c.blocks_x, c.blocks_y));
        }
    }
    for (std::size_t k = 0; k < n; ++k) {
        const UrbanRouteNode& p = c.route[k];
        const UrbanRouteNode& q = c.route[(k + 1) % n];
        if ((p.i == q.i) == (p.j == q.j)) {
            throw ConfigError(fmt::format(
                "{}.route[{}] = {}, expected a straight street from route[{}] = {} (the same i or "
                "the same j, not both)",
                prefix, (k + 1) % n, node_text(q), k, node_text(p)));
        }
    }
    for (std::size_t k = 0; k < n; ++k) {
        const UrbanRouteNode& p = c.route[k];
        const UrbanRouteNode& q = c.route[(k + 1) % n];
        const UrbanRouteNode& r = c.route[(k + 2) % n];
        const int dot = (q.i - p.i) * (r.i - q.i) + (q.j - p.j) * (r.j - q.j);
        if (dot < 0) {
            throw ConfigError(
                fmt::format("{}.route[{}] = {}: the route turns back on itself there, expected "
                            "turns of at most 90 degrees",
                            prefix, (k + 1) % n, node_text(q)));
        }
    }
}

void check_buildings(const UrbanConfig& c, std::string_view prefix) {
    detail::require_positive(prefix, "min_height_m", c.min_height_m);
    require(finite_at_least(c.max_height_m, c.min_height_m), prefix, "max_height_m", c.max_height_m,
            fmt::format(">= min_height_m = {}", c.min_height_m));
    require(finite_at_least(c.storey_height_m, 2.5), prefix, "storey_height_m", c.storey_height_m,
            ">= 2.5 (sill, window and lintel)");
    require(finite_at_least(c.bay_width_m, 1.5), prefix, "bay_width_m", c.bay_width_m, ">= 1.5");
    require(finite_at_least(c.min_frontage_m, 2.0), prefix, "min_frontage_m", c.min_frontage_m,
            ">= 2");
    require(finite_at_least(c.max_frontage_m, c.min_frontage_m), prefix, "max_frontage_m",
            c.max_frontage_m, fmt::format(">= min_frontage_m = {}", c.min_frontage_m));
    detail::require_positive(prefix, "facade_recess_m", c.facade_recess_m);
    require(finite_at_least(c.min_depth_m, 2.0 * c.facade_recess_m), prefix, "min_depth_m",
            c.min_depth_m, fmt::format(">= 2 facade_recess_m = {}", 2.0 * c.facade_recess_m));
    require(finite_at_least(c.max_depth_m, c.min_depth_m), prefix, "max_depth_m", c.max_depth_m,
            fmt::format(">= min_depth_m = {}", c.min_depth_m));
    detail::require_probability(prefix, "gap_probability", c.gap_probability);
    detail::require_positive(prefix, "min_gap_m", c.min_gap_m);
    require(finite_at_least(c.max_gap_m, c.min_gap_m), prefix, "max_gap_m", c.max_gap_m,
            fmt::format(">= min_gap_m = {}", c.min_gap_m));
    detail::require_probability(prefix, "balcony_probability", c.balcony_probability);
}

void check_blocks(const UrbanConfig& c, std::string_view prefix) {
    require(c.blocks_x >= 1, prefix, "blocks_x", c.blocks_x, ">= 1");
    require(c.blocks_y >= 1, prefix, "blocks_y", c.blocks_y, ">= 1");
    detail::require_positive(prefix, "street_width_m", c.street_width_m);
    require(finite_at_least(c.sidewalk_width_m, 2.0), prefix, "sidewalk_width_m",
            c.sidewalk_width_m, ">= 2 (lamp posts and trees stand on it)");
    require(finite_at_least(c.kerb_height_m, 0.0) && c.kerb_height_m <= 0.5, prefix,
            "kerb_height_m", c.kerb_height_m, "in [0, 0.5]");
    detail::require_positive(prefix, "ground_margin_m", c.ground_margin_m);
    // Buildings line all four sides, so the short sides start behind the long sides' depth.
    const double min_block_m = 2.0 * (c.sidewalk_width_m + c.max_depth_m);
    require(std::isfinite(c.block_length_m) && c.block_length_m > min_block_m, prefix,
            "block_length_m", c.block_length_m,
            fmt::format("> 2 (sidewalk_width_m + max_depth_m) = {}", min_block_m));
    require(std::isfinite(c.block_width_m) && c.block_width_m > min_block_m, prefix,
            "block_width_m", c.block_width_m,
            fmt::format("> 2 (sidewalk_width_m + max_depth_m) = {}", min_block_m));
}

}  // namespace

void UrbanConfig::validate(std::string_view prefix) const {
    check_buildings(*this, prefix);
    check_blocks(*this, prefix);
    require(finite_at_least(pole_spacing_m, 2.0), prefix, "pole_spacing_m", pole_spacing_m, ">= 2");
    detail::require_probability(prefix, "tree_probability", tree_probability);
    detail::require_probability(prefix, "parked_car_probability", parked_car_probability);
    require(finite_at_least(lane_offset_m, 0.0) && lane_offset_m < 0.5 * street_width_m, prefix,
            "lane_offset_m", lane_offset_m,
            fmt::format("in [0, street_width_m / 2 = {})", 0.5 * street_width_m));
    check_route(*this, prefix);
    defects.validate(detail::sub(prefix, "defects"));
}

}  // namespace scantling::sim
