#include "hull_surroundings.hpp"

#include <scantling/core/error.hpp>

#include <fmt/format.h>

#include <cmath>

namespace scantling::sim::detail {
namespace {

const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();
const Eigen::Vector3d kY = Eigen::Vector3d::UnitY();
const Eigen::Vector3d kZ = Eigen::Vector3d::UnitZ();
constexpr int kBollardSegments = 16;
// Bollards stand this far back from the quay edge, as on real quays (lines lead over the edge).
constexpr double kBollardSetback_m = 1.0;
// Concrete and water reflect little; the steel hull (0.5) stands out.
constexpr double kConcreteAlbedo = 0.35;
constexpr double kWaterAlbedo = 0.05;

// Horizontal rectangle [x0, x1] x [y0, y1] at height z, facing up.
void add_floor(MeshBuilder& builder, double x0, double x1, double y0, double y1, double z,
               int tag) {
    builder.add_quad({x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}, tag);
}

// Vertical rectangle at y over [x0, x1] x [z0, z1], facing +y or -y.
void add_y_wall(MeshBuilder& builder, double y, double x0, double x1, double z0, double z1,
                bool facing_plus_y, int tag) {
    const Loop3 loop{{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}};
    builder.add_polygon(loop, {}, facing_plus_y ? kY : Eigen::Vector3d(-kY), tag);
}

void add_dry_dock(MeshBuilder& builder, const HullExtent& hull, const HullSurroundingsConfig& c) {
    const double x0 = hull.x_min_m - c.end_margin_m, x1 = hull.x_max_m + c.end_margin_m;
    const double w = hull.half_breadth_m + c.wall_clearance_m;
    const double floor_z = hull.keel_z_m - c.keel_block_height_m;
    add_floor(builder, x0, x1, -w, w, floor_z,
              builder.surface("dock_floor", true, kConcreteAlbedo));
    const int wall = builder.surface("dock_wall", true, kConcreteAlbedo);
    add_y_wall(builder, w, x0, x1, floor_z, floor_z + c.dock_wall_height_m, false, wall);
    add_y_wall(builder, -w, x0, x1, floor_z, floor_z + c.dock_wall_height_m, true, wall);
    const int blocks = builder.surface("keel_blocks", true, kConcreteAlbedo);
    const Eigen::Vector3d half(0.5 * c.keel_block_length_m, 0.5 * c.keel_block_width_m, 0.0);
    for (const double x : hull.block_x_m) {
        builder.add_box(
            box_between({x, 0.0, floor_z}, kX, kY, kZ, -half, half + c.keel_block_height_m * kZ),
            blocks);
    }
}

void add_quay(MeshBuilder& builder, const HullExtent& hull, const HullSurroundingsConfig& c) {
    const double x0 = hull.x_min_m - c.end_margin_m, x1 = hull.x_max_m + c.end_margin_m;
    const double quay_y = hull.half_breadth_m + c.fender_gap_m;
    const double far_y = -(hull.half_breadth_m + c.water_extent_m);
    const double water_z = hull.keel_z_m + c.draught_m;
    const double seabed_z = water_z - c.water_depth_m, deck_z = water_z + c.quay_height_m;
    add_floor(builder, x0, x1, far_y, quay_y, water_z,
              builder.surface("water", false, kWaterAlbedo));
    add_floor(builder, x0, x1, far_y, quay_y, seabed_z, builder.surface("seabed"));
    add_y_wall(builder, quay_y, x0, x1, seabed_z, deck_z, false,
               builder.surface("quay_wall", true, kConcreteAlbedo));
    add_floor(builder, x0, x1, quay_y, quay_y + c.quay_apron_m, deck_z,
              builder.surface("quay_deck", true, kConcreteAlbedo));
    const int bollards = builder.surface("bollards");
    const double bollard_y = quay_y + kBollardSetback_m + c.bollard_radius_m;
    for (const double x : centred_positions(x0, x1, c.bollard_spacing_m)) {
        builder.add_cylinder({x, bollard_y, deck_z}, kZ, kX, c.bollard_radius_m, c.bollard_height_m,
                             kBollardSegments, true, true, bollards);
    }
}

}  // namespace

void add_surroundings(MeshBuilder& builder, const HullExtent& hull,
                      const HullSurroundingsConfig& config) {
    if (config.environment == HullEnvironment::kDryDock) add_dry_dock(builder, hull, config);
    if (config.environment == HullEnvironment::kQuay) add_quay(builder, hull, config);
}

std::vector<double> centred_positions(double x_min_m, double x_max_m, double spacing) {
    const int n = static_cast<int>(std::floor((x_max_m - x_min_m) / spacing + 1e-9)) + 1;
    const double first = 0.5 * (x_min_m + x_max_m) - 0.5 * (n - 1) * spacing;
    std::vector<double> xs;
    for (int k = 0; k < n; ++k) xs.push_back(first + k * spacing);
    return xs;
}

}  // namespace scantling::sim::detail

namespace scantling::sim {

void HullSurroundingsConfig::validate(std::string_view prefix) const {
    using detail::require_positive;
    detail::require(environment == HullEnvironment::kNone ||
                        environment == HullEnvironment::kDryDock ||
                        environment == HullEnvironment::kQuay,
                    prefix, "environment", static_cast<int>(environment), "none, dry_dock or quay");
    detail::require_non_negative(prefix, "end_margin_m", end_margin_m);
    require_positive(prefix, "wall_clearance_m", wall_clearance_m);
    require_positive(prefix, "dock_wall_height_m", dock_wall_height_m);
    require_positive(prefix, "keel_block_height_m", keel_block_height_m);
    require_positive(prefix, "keel_block_length_m", keel_block_length_m);
    require_positive(prefix, "keel_block_width_m", keel_block_width_m);
    detail::require(
        std::isfinite(keel_block_spacing_m) && keel_block_spacing_m > keel_block_length_m, prefix,
        "keel_block_spacing_m", keel_block_spacing_m,
        fmt::format("> keel_block_length_m = {}", keel_block_length_m));
    require_positive(prefix, "draught_m", draught_m);
    require_positive(prefix, "fender_gap_m", fender_gap_m);
    require_positive(prefix, "quay_height_m", quay_height_m);
    require_positive(prefix, "quay_apron_m", quay_apron_m);
    detail::require(std::isfinite(water_depth_m) && water_depth_m > draught_m, prefix,
                    "water_depth_m", water_depth_m, fmt::format("> draught_m = {}", draught_m));
    require_positive(prefix, "water_extent_m", water_extent_m);
    require_positive(prefix, "bollard_radius_m", bollard_radius_m);
    require_positive(prefix, "bollard_height_m", bollard_height_m);
    detail::require(std::isfinite(bollard_spacing_m) && bollard_spacing_m > 2.0 * bollard_radius_m,
                    prefix, "bollard_spacing_m", bollard_spacing_m, "> 2 bollard_radius_m");
    detail::require(2.0 * (detail::kBollardSetback_m + bollard_radius_m) <= quay_apron_m, prefix,
                    "quay_apron_m", quay_apron_m, "room for the bollards (>= 2.6 m by default)");
}

std::string_view to_string(HullEnvironment environment) {
    switch (environment) {
        case HullEnvironment::kNone:
            return "none";
        case HullEnvironment::kDryDock:
            return "dry_dock";
        case HullEnvironment::kQuay:
            return "quay";
    }
    return "unknown";
}

}  // namespace scantling::sim
