// The large two-level ballast tank of SPEC §8 (exploration, PhD art. G).
#include <scantling/core/error.hpp>
#include <scantling/sim/world_builders.hpp>

#include "detail/defect_placement.hpp"
#include "detail/mesh_builder.hpp"
#include "detail/tank_parts.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace scantling::sim {
namespace {

using detail::Loop3;
using detail::MeshBuilder;
using detail::Wall;

constexpr std::string_view kPrefix = "ballast_tank_large";
// Distance a deck opening keeps from the bulkheads of the level above.
constexpr double kBulkheadClearance_m = 0.1;

const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();
const Eigen::Vector3d kY = Eigen::Vector3d::UnitY();
const Eigen::Vector3d kZ = Eigen::Vector3d::UnitZ();

struct Level {
    int first_compartment = 0;
    int count = 0;
    double floor_m = 0.0;    // z of the floor (tank bottom or deck mid-plane)
    double ceiling_m = 0.0;  // z of the ceiling
    std::vector<FrameLine> longitudinals;
};

struct Layout {
    BallastTankLargeConfig config;
    std::vector<double> frame_x;  // every transverse member (ends included), ascending
    Level lower, upper;

    double bulkhead_x(const Level& level, int k) const { return config.length_m * k / level.count; }
    int frame_number(double x) const {
        const auto it = std::lower_bound(frame_x.begin(), frame_x.end(), x - 1e-9);
        return static_cast<int>(it - frame_x.begin());
    }
    double transition_x(int lower_compartment) const {
        return config.length_m * (lower_compartment + 0.5) / lower.count;
    }
    int upper_compartment_at(double x) const {
        return std::min(upper.count - 1, static_cast<int>(x / config.length_m * upper.count));
    }
};

Layout layout_of(const BallastTankLargeConfig& c) {
    Layout l{c,
             {},
             {0, c.lower_compartments, 0.0, c.level_height_m, {}},
             {c.lower_compartments, c.upper_compartments, c.level_height_m, c.height_m, {}}};
    for (const Level* level : {&l.lower, &l.upper}) {
        for (int k = 0; k <= level->count; ++k) l.frame_x.push_back(l.bulkhead_x(*level, k));
    }
    std::sort(l.frame_x.begin(), l.frame_x.end());
    l.frame_x.erase(std::unique(l.frame_x.begin(), l.frame_x.end(),
                                [](double a, double b) { return std::abs(a - b) < 1e-9; }),
                    l.frame_x.end());
    return l;
}

void check_transitions(const Layout& l) {
    const auto& c = l.config;
    for (std::size_t i = 0; i < c.transition_compartments.size(); ++i) {
        const double x = l.transition_x(c.transition_compartments[i]);
        const double half = 0.5 * c.transition_length_m + kBulkheadClearance_m;
        for (int k = 1; k < l.upper.count; ++k) {
            if (std::abs(x - l.bulkhead_x(l.upper, k)) >= half) continue;
            throw ConfigError(
                fmt::format("{}.transition_compartments[{}] = {}, expected a lower "
                            "compartment whose centre is at least {} m from the "
                            "upper bulkheads",
                            kPrefix, i, c.transition_compartments[i], half));
        }
    }
}

Loop3 transverse_rect(double x, double y0, double y1, double z0, double z1) {
    return {{x, y0, z0}, {x, y1, z0}, {x, y1, z1}, {x, y0, z1}};
}

void add_shell(MeshBuilder& builder, Layout& l) {
    const auto& c = l.config;
    const double L = c.length_m, W = c.width_m, H = c.height_m;
    const Wall floor{"bottom", {0, 0, 0}, {L, 0, 0}, {L, W, 0}, {0, W, 0}, kZ, {}};
    const double entry_x = 0.5 * l.bulkhead_x(l.upper, 1);
    const Wall top{"top",
                   {0, 0, H},
                   {L, 0, H},
                   {L, W, H},
                   {0, W, H},
                   -kZ,
                   {{entry_x - 0.5 * c.entry_length_m, entry_x + 0.5 * c.entry_length_m,
                     0.5 * (W - c.entry_width_m), 0.5 * (W + c.entry_width_m)}}};
    const Wall side_0{"side_shell_0", {0, 0, 0}, {L, 0, 0}, {L, 0, H}, {0, 0, H}, kY, {}};
    const Wall side_1{"side_shell_1", {0, W, 0}, {L, W, 0}, {L, W, H}, {0, W, H}, -kY, {}};
    for (const Wall* wall : {&floor, &top, &side_0, &side_1}) {
        detail::add_wall(builder, *wall, builder.surface(wall->name));
    }
    builder.add_polygon(transverse_rect(0, 0, W, 0, H), {}, kX, builder.surface("aft_end"));
    builder.add_polygon(transverse_rect(L, 0, W, 0, H), {}, -kX, builder.surface("fore_end"));
    int number = 1;
    for (Level* level : {&l.lower, &l.upper}) {
        const double height = level->ceiling_m - level->floor_m;
        for (const Wall* side : {&side_0, &side_1}) {
            for (const double v : detail::even_positions(height, c.longitudinal_spacing_m)) {
                level->longitudinals.push_back(detail::add_longitudinal(
                    builder, *side, level->floor_m + v, c.stiffener, number++));
            }
        }
    }
}

void add_deck(MeshBuilder& builder, const Layout& l) {
    const auto& c = l.config;
    const double z = c.level_height_m;
    std::vector<Loop3> openings;
    for (const int k : c.transition_compartments) {
        const Eigen::Vector3d centre(l.transition_x(k), 0.5 * c.width_m, z);
        openings.push_back(detail::rectangle(
            centre, kX, kY, -0.5 * c.transition_length_m, 0.5 * c.transition_length_m,
            -0.5 * c.transition_width_m, 0.5 * c.transition_width_m));
    }
    const Loop3 outline{
        {0, 0, z}, {c.length_m, 0, z}, {c.length_m, c.width_m, z}, {0, c.width_m, z}};
    builder.add_slab(outline, openings, kZ, c.plate_thickness_m, builder.surface("deck"), false);
}

// Lowest z of a passage in a level: above the floor, or above the deck plate.
double passage_bottom(const Layout& l, const Level& level) {
    const double plate = level.floor_m > 0.0 ? 0.5 * l.config.plate_thickness_m : 0.0;
    return level.floor_m + plate + l.config.passage_sill_m;
}

void add_bulkheads(MeshBuilder& builder, const Layout& l, WorldMetadata& m) {
    const auto& c = l.config;
    const double y0 = 0.5 * (c.width_m - c.passage_width_m);
    const double y1 = 0.5 * (c.width_m + c.passage_width_m);
    for (const Level* level : {&l.lower, &l.upper}) {
        const double z0 = passage_bottom(l, *level);
        for (int k = 1; k < level->count; ++k) {
            const double x = l.bulkhead_x(*level, k);
            const int tag = builder.surface(fmt::format("frame_{}", l.frame_number(x)));
            builder.add_slab(transverse_rect(x, 0, c.width_m, level->floor_m, level->ceiling_m),
                             {transverse_rect(x, y0, y1, z0, z0 + c.passage_height_m)}, kX,
                             c.plate_thickness_m, tag, false);
            const int a = level->first_compartment + k - 1;
            detail::add_connection(m, {0,
                                       ConnectionKind::Manhole,
                                       a,
                                       a + 1,
                                       {x, 0.5 * c.width_m, z0 + 0.5 * c.passage_height_m},
                                       kX,
                                       c.passage_width_m,
                                       c.passage_height_m});
        }
    }
}

void add_compartments(const Layout& l, WorldMetadata& m) {
    const auto& c = l.config;
    const double half_t = 0.5 * c.plate_thickness_m;
    for (const Level* level : {&l.lower, &l.upper}) {
        const int level_index = level == &l.lower ? 0 : 1;
        for (int k = 0; k < level->count; ++k) {
            const double x0 = l.bulkhead_x(*level, k), x1 = l.bulkhead_x(*level, k + 1);
            const int id = level->first_compartment + k;
            detail::add_compartment(
                m, fmt::format("{}_{}", level_index == 0 ? "lower" : "upper", k + 1),
                {x0, 0, level->floor_m}, {x1, c.width_m, level->ceiling_m}, level_index);
            const double face0 = k == 0 ? x0 : x0 + half_t;
            const double face1 = k + 1 == level->count ? x1 : x1 - half_t;
            detail::add_frame_landmarks(m, id, m.frames[l.frame_number(x0)], face0,
                                        level->longitudinals);
            detail::add_frame_landmarks(m, id, m.frames[l.frame_number(x1)], face1,
                                        level->longitudinals);
        }
    }
}

void add_frames(const Layout& l, WorldMetadata& m) {
    const auto& c = l.config;
    for (std::size_t i = 0; i < l.frame_x.size(); ++i) {
        const bool aft = i == 0, fore = i + 1 == l.frame_x.size();
        m.frames.push_back({static_cast<int>(i),
                            Eigen::Vector3d(l.frame_x[i], 0.5 * c.width_m, 0.5 * c.height_m), kX,
                            aft ? "aft_end" : (fore ? "fore_end" : fmt::format("frame_{}", i))});
    }
}

void add_openings(const Layout& l, WorldMetadata& m) {
    const auto& c = l.config;
    for (const int k : c.transition_compartments) {
        const double x = l.transition_x(k);
        detail::add_connection(m, {0,
                                   ConnectionKind::LevelTransition,
                                   l.lower.first_compartment + k,
                                   l.upper.first_compartment + l.upper_compartment_at(x),
                                   {x, 0.5 * c.width_m, c.level_height_m},
                                   kZ,
                                   c.transition_width_m,
                                   c.transition_length_m});
    }
    detail::add_connection(m, {0,
                               ConnectionKind::Entry,
                               l.upper.first_compartment,
                               Connection::kOutside,
                               {0.5 * l.bulkhead_x(l.upper, 1), 0.5 * c.width_m, c.height_m},
                               kZ,
                               c.entry_width_m,
                               c.entry_length_m});
}

}  // namespace

World build_ballast_tank_large(const BallastTankLargeConfig& config) {
    config.validate(kPrefix);
    Layout layout = layout_of(config);
    check_transitions(layout);
    MeshBuilder builder;
    WorldMetadata m;
    m.name = std::string(kPrefix);
    add_shell(builder, layout);
    add_deck(builder, layout);
    add_frames(layout, m);
    add_compartments(layout, m);
    m.longitudinals = layout.lower.longitudinals;
    m.longitudinals.insert(m.longitudinals.end(), layout.upper.longitudinals.begin(),
                           layout.upper.longitudinals.end());
    add_bulkheads(builder, layout, m);
    add_openings(layout, m);
    World world = builder.finish(std::move(m));
    std::vector<int> walls;
    for (const Surface& s : world.metadata.surfaces) {
        if (s.name.rfind("longitudinal_", 0) != 0) walls.push_back(s.tag);
    }
    detail::place_defects(world, config.defects, walls, fmt::format("{}.defects", kPrefix));
    return world;
}

}  // namespace scantling::sim
