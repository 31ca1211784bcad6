// KITTI-like city of streets, blocks and detailed buildings (issue 4, item 4).
#include <scantling/sim/world_urban.hpp>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>

#include "detail/defect_placement.hpp"
#include "detail/mesh_builder.hpp"
#include "detail/sensor_checks.hpp"
#include "detail/tank_parts.hpp"
#include "detail/urban_parts.hpp"

#include <fmt/format.h>

#include <cmath>

namespace scantling::sim {
namespace {

using detail::StreetSide;

constexpr std::string_view kPrefix = "urban";
constexpr double kCarSlot_m = 6.0;
// No parked cars this close to a block corner, so crossings stay clear.
constexpr double kCornerClearance_m = 8.0;
// Street furniture keeps this far from the block corners.
constexpr double kFurnitureEndMargin_m = 1.0;
constexpr double kMinCrownRadius_m = 1.2;
constexpr double kMaxCrownRadius_m = 2.0;

// Cells (a, b) with a in [-1, blocks_x], b in [-1, blocks_y]: the blocks between the streets
// and the ring of blocks around them.
struct Grid {
    const UrbanConfig& c;

    bool has_block(int a, int b) const {
        return a >= -1 && a <= c.blocks_x && b >= -1 && b <= c.blocks_y;
    }
    Eigen::Vector2d block_min(int a, int b) const {
        return {a * c.pitch_x_m() + 0.5 * c.street_width_m,
                b * c.pitch_y_m() + 0.5 * c.street_width_m};
    }
    Eigen::Vector2d block_max(int a, int b) const {
        return {(a + 1) * c.pitch_x_m() - 0.5 * c.street_width_m,
                (b + 1) * c.pitch_y_m() - 0.5 * c.street_width_m};
    }
    Eigen::Vector2d node(const UrbanRouteNode& n) const {
        return {n.i * c.pitch_x_m(), n.j * c.pitch_y_m()};
    }
};

Eigen::Vector3d on_ground(const Eigen::Vector2d& p) { return {p.x(), p.y(), 0.0}; }

// The road: everything but the blocks, out to the margin.
void add_road(detail::MeshBuilder& builder, const Grid& g, int tag) {
    const auto& c = g.c;
    const Eigen::Vector2d lo = g.block_min(-1, -1) - Eigen::Vector2d::Constant(c.ground_margin_m);
    const Eigen::Vector2d hi =
        g.block_max(c.blocks_x, c.blocks_y) + Eigen::Vector2d::Constant(c.ground_margin_m);
    const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY();
    std::vector<detail::Loop3> holes;
    for (int b = -1; b <= c.blocks_y; ++b) {
        for (int a = -1; a <= c.blocks_x; ++a) {
            const Eigen::Vector2d m = g.block_min(a, b), M = g.block_max(a, b);
            holes.push_back(
                detail::rectangle(Eigen::Vector3d::Zero(), x, y, m.x(), M.x(), m.y(), M.y()));
        }
    }
    builder.add_polygon(
        detail::rectangle(Eigen::Vector3d::Zero(), x, y, lo.x(), hi.x(), lo.y(), hi.y()), holes,
        Eigen::Vector3d::UnitZ(), tag);
}

// Buildings along [start, end] of a side, each followed by a gap now and then; a building
// that would leave less than min_frontage_m before the end runs to the end. `corner_start`
// and `corner_end` say whether the cross streets at the ends see the corner buildings' sides.
void add_buildings(detail::MeshBuilder& builder, const UrbanConfig& c,
                   const detail::UrbanTags& tags, const StreetSide& side, double start_m,
                   double end_m, bool corner_start, bool corner_end, Rng& rng) {
    double u = start_m;
    while (u + c.min_frontage_m <= end_m) {
        detail::BuildingSpec b;
        b.start_m = u;
        b.frontage_m = rng.uniform(c.min_frontage_m, c.max_frontage_m);
        const bool to_end = end_m - (u + b.frontage_m) < c.min_frontage_m;
        if (to_end) b.frontage_m = end_m - u;
        b.depth_m = rng.uniform(c.min_depth_m, c.max_depth_m);
        b.height_m = rng.uniform(c.min_height_m, c.max_height_m);
        b.door_bay = static_cast<int>(
            rng.uniform_index(static_cast<std::size_t>(detail::bay_count(c, b.frontage_m))));
        b.balconies = rng.uniform() < c.balcony_probability;
        b.corner_start = corner_start && u == start_m;
        b.corner_end = corner_end && to_end;
        detail::add_building(builder, c, tags, side, b);
        if (to_end) return;
        u += b.frontage_m;
        if (rng.uniform() < c.gap_probability) u += rng.uniform(c.min_gap_m, c.max_gap_m);
    }
}

// Lamp posts every pole_spacing_m, trees between them, parked cars in the kerb lane.
void add_street_furniture(detail::MeshBuilder& builder, const UrbanConfig& c,
                          const detail::UrbanTags& tags, const StreetSide& side, Rng& rng) {
    const double last = side.length_m - kFurnitureEndMargin_m;
    for (double u = 0.5 * c.pole_spacing_m; u <= last; u += c.pole_spacing_m) {
        detail::add_lamp_post(builder, c, tags, side, u);
        const double tree_at = u + 0.5 * c.pole_spacing_m;
        const double trunk_m = rng.uniform(2.0, 3.0);
        const double crown_m = rng.uniform(kMinCrownRadius_m, kMaxCrownRadius_m);
        if (tree_at <= last && rng.uniform() < c.tree_probability) {
            detail::add_tree(builder, c, tags, side, tree_at, trunk_m, crown_m);
        }
    }
    const int slots =
        static_cast<int>(std::floor((side.length_m - 2.0 * kCornerClearance_m) / kCarSlot_m));
    for (int k = 0; k < slots; ++k) {
        const double shift_m = rng.uniform(-0.4, 0.4);
        if (rng.uniform() < c.parked_car_probability) {
            detail::add_parked_car(builder, tags, side, kCornerClearance_m + (k + 0.5) * kCarSlot_m,
                                   shift_m);
        }
    }
}

// The block's platform and, on each side that faces a street, its buildings and furniture.
// Sides run counter-clockwise round the block (inward = up × along).
void add_block(detail::MeshBuilder& builder, const Grid& g, const detail::UrbanTags& tags, int a,
               int b, Rng& rng) {
    const auto& c = g.c;
    const Eigen::Vector2d m = g.block_min(a, b), M = g.block_max(a, b);
    detail::add_block_platform(builder, c, tags, m, M);
    const double L = M.x() - m.x(), W = M.y() - m.y();
    const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY();
    struct Candidate {
        StreetSide side;
        bool faces_street;
        bool along_x;
    };
    const Candidate sides[4] = {
        {{on_ground(m), x, y, L}, g.has_block(a, b - 1), true},
        {{on_ground({M.x(), m.y()}), y, -x, W}, g.has_block(a + 1, b), false},
        {{on_ground(M), -x, -y, L}, g.has_block(a, b + 1), true},
        {{on_ground({m.x(), M.y()}), -y, x, W}, g.has_block(a - 1, b), false}};
    for (int k = 0; k < 4; ++k) {
        const Candidate& s = sides[k];
        if (!s.faces_street) continue;
        // Sides along x run corner to corner (their corner buildings get a facade on the cross
        // street too); sides along y stop short of those buildings.
        const double inset = c.sidewalk_width_m + (s.along_x ? 0.0 : c.max_depth_m);
        const bool corner_start = s.along_x && sides[(k + 3) % 4].faces_street;
        const bool corner_end = s.along_x && sides[(k + 1) % 4].faces_street;
        add_buildings(builder, c, tags, s.side, inset, s.side.length_m - inset, corner_start,
                      corner_end, rng);
        add_street_furniture(builder, c, tags, s.side, rng);
    }
}

WorldMetadata metadata_of(const Grid& g) {
    const auto& c = g.c;
    WorldMetadata m;
    m.name = std::string(kPrefix);
    const Eigen::Vector2d lo = g.block_min(-1, -1), hi = g.block_max(c.blocks_x, c.blocks_y);
    const double half = 0.5 * c.street_width_m;
    for (int i = 0; i <= c.blocks_x; ++i) {
        const double x = i * c.pitch_x_m();
        detail::add_compartment(m, fmt::format("street_i{}", i), {x - half, lo.y(), 0.0},
                                {x + half, hi.y(), c.max_height_m});
    }
    for (int j = 0; j <= c.blocks_y; ++j) {
        const double y = j * c.pitch_y_m();
        detail::add_compartment(m, fmt::format("street_j{}", j), {lo.x(), y - half, 0.0},
                                {hi.x(), y + half, c.max_height_m});
    }
    return m;
}

}  // namespace

World build_urban(const UrbanConfig& config) {
    config.validate(kPrefix);
    const Grid grid{config};
    detail::MeshBuilder builder;
    const detail::UrbanTags tags = detail::add_urban_surfaces(builder);
    add_road(builder, grid, tags.road);
    Rng rng(config.seed);
    for (int b = -1; b <= config.blocks_y; ++b) {
        for (int a = -1; a <= config.blocks_x; ++a) add_block(builder, grid, tags, a, b, rng);
    }
    World world = builder.finish(metadata_of(grid));
    detail::place_defects(world, config.defects, std::span<const int>(&tags.facade, 1),
                          fmt::format("{}.defects", kPrefix));
    return world;
}

std::vector<Eigen::Vector3d> urban_route(const UrbanConfig& config, double height_m) {
    config.validate(kPrefix);
    const Grid grid{config};
    const std::size_t n = config.route.size();
    std::vector<Eigen::Vector3d> corners;
    for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Vector2d prev = grid.node(config.route[(k + n - 1) % n]);
        const Eigen::Vector2d p = grid.node(config.route[k]);
        const Eigen::Vector2d next = grid.node(config.route[(k + 1) % n]);
        const Eigen::Vector2d d_in = (p - prev).normalized(), d_out = (next - p).normalized();
        const Eigen::Vector2d right_in(d_in.y(), -d_in.x()), right_out(d_out.y(), -d_out.x());
        // Crossing of the two legs moved right by the lane offset (valid for any turn short
        // of a U-turn, which validate() rejects).
        const Eigen::Vector2d q =
            p + config.lane_offset_m * (right_in + right_out) / (1.0 + d_in.dot(d_out));
        corners.emplace_back(q.x(), q.y(), height_m);
    }
    return corners;
}

double urban_route_length_m(const UrbanConfig& config) {
    const std::vector<Eigen::Vector3d> corners = urban_route(config);
    double length_m = 0.0;
    for (std::size_t k = 0; k < corners.size(); ++k) {
        length_m += (corners[(k + 1) % corners.size()] - corners[k]).norm();
    }
    return length_m;
}

}  // namespace scantling::sim
