// The two-compartment topside ballast-tank mock-up (SPEC §7 art. B–E, §10).
#include <scantling/core/error.hpp>
#include <scantling/sim/world_builders.hpp>

#include "detail/defect_placement.hpp"
#include "detail/mesh_builder.hpp"
#include "detail/tank_parts.hpp"

#include <fmt/format.h>

#include <array>

namespace scantling::sim {
namespace {

using detail::Loop3;
using detail::MeshBuilder;
using detail::Wall;

constexpr std::string_view kPrefix = "ballast_tank_mockup";
// Free steel kept around an opening beyond the stiffeners (room for the reinforcement).
constexpr double kOpeningMargin_m = 0.05;

// The tank's cross-section in (y, z), counter-clockwise, and the wall each edge i -> i+1 is.
struct Section {
    std::array<Eigen::Vector2d, 5> points;
    std::array<std::string_view, 5> walls{"bottom", "side_shell", "deck", "inboard_side", "hopper"};
};

Section section_of(const BallastTankMockupConfig& c) {
    return {{Eigen::Vector2d(c.hopper_width_m, 0.0), Eigen::Vector2d(c.width_m, 0.0),
             Eigen::Vector2d(c.width_m, c.height_m), Eigen::Vector2d(0.0, c.height_m),
             Eigen::Vector2d(0.0, c.hopper_height_m)}};
}

Eigen::Vector3d at(double x, const Eigen::Vector2d& yz) { return {x, yz.x(), yz.y()}; }

Loop3 section_at(const Section& s, double x) {
    Loop3 loop;
    for (const auto& p : s.points) loop.push_back(at(x, p));
    return loop;
}

// Distance of q inside the section edge i (negative outside).
double inside_distance(const Section& s, int i, const Eigen::Vector2d& q) {
    const Eigen::Vector2d& a = s.points[i];
    const Eigen::Vector2d e = (s.points[(i + 1) % 5] - a).normalized();
    return Eigen::Vector2d(-e.y(), e.x()).dot(q - a);
}

void check_manhole(const BallastTankMockupConfig& c, const Section& s) {
    const double clearance = c.stiffener.height_m + kOpeningMargin_m;
    for (const double dy : {-0.5, 0.5}) {
        for (const double dz : {-0.5, 0.5}) {
            const Eigen::Vector2d q(c.manhole_centre_y_m + dy * c.manhole_width_m,
                                    c.manhole_centre_z_m + dz * c.manhole_height_m);
            for (int i = 0; i < 5; ++i) {
                if (inside_distance(s, i, q) >= clearance) continue;
                throw ConfigError(fmt::format(
                    "{}.manhole_centre_y_m = {}, manhole_centre_z_m = {}: expected the {} x {} m "
                    "manhole at least {} m inside the web frame (too close to the {})",
                    kPrefix, c.manhole_centre_y_m, c.manhole_centre_z_m, c.manhole_width_m,
                    c.manhole_height_m, clearance, s.walls[i]));
            }
        }
    }
}

void check_entry(const BallastTankMockupConfig& c) {
    const double x0 = c.entry_centre_x_m - 0.5 * c.entry_length_m;
    const double x1 = c.entry_centre_x_m + 0.5 * c.entry_length_m;
    if (!(x0 >= kOpeningMargin_m &&
          x1 <= 0.5 * (c.length_m - c.plate_thickness_m) - kOpeningMargin_m)) {
        throw ConfigError(
            fmt::format("{}.entry_centre_x_m = {}, expected the entry manhole "
                        "inside the deck of the first compartment",
                        kPrefix, c.entry_centre_x_m));
    }
    const double y0 = c.entry_centre_y_m - 0.5 * c.entry_width_m;
    const double y1 = c.entry_centre_y_m + 0.5 * c.entry_width_m;
    if (!(y0 >= kOpeningMargin_m && y1 <= c.width_m - kOpeningMargin_m)) {
        throw ConfigError(
            fmt::format("{}.entry_centre_y_m = {}, expected the entry manhole "
                        "inside the deck",
                        kPrefix, c.entry_centre_y_m));
    }
}

Wall wall_of(const BallastTankMockupConfig& c, const Section& s, int i) {
    const Eigen::Vector2d& a = s.points[i];
    const Eigen::Vector2d& b = s.points[(i + 1) % 5];
    const Eigen::Vector2d e = (b - a).normalized();
    Wall wall{std::string(s.walls[i]),
              at(0.0, a),
              at(c.length_m, a),
              at(c.length_m, b),
              at(0.0, b),
              Eigen::Vector3d(0.0, -e.y(), e.x()),
              {}};
    if (s.walls[i] == "deck") {  // v runs from the side shell (y = width) inboard
        const double v_centre = c.width_m - c.entry_centre_y_m;
        wall.holes.push_back({c.entry_centre_x_m - 0.5 * c.entry_length_m,
                              c.entry_centre_x_m + 0.5 * c.entry_length_m,
                              v_centre - 0.5 * c.entry_width_m, v_centre + 0.5 * c.entry_width_m});
    }
    return wall;
}

std::vector<FrameLine> add_shell(MeshBuilder& builder, const BallastTankMockupConfig& c,
                                 const Section& s) {
    std::vector<FrameLine> longitudinals;
    for (int i = 0; i < 5; ++i) {
        const Wall wall = wall_of(c, s, i);
        detail::add_wall(builder, wall, builder.surface(wall.name));
        for (const double v : detail::even_positions(wall.width_m(), c.longitudinal_spacing_m)) {
            const int number = static_cast<int>(longitudinals.size()) + 1;
            longitudinals.push_back(
                detail::add_longitudinal(builder, wall, v, c.stiffener, number));
        }
    }
    builder.add_polygon(section_at(s, 0.0), {}, Eigen::Vector3d::UnitX(),
                        builder.surface("aft_bulkhead"));
    builder.add_polygon(section_at(s, c.length_m), {}, -Eigen::Vector3d::UnitX(),
                        builder.surface("fore_bulkhead"));
    return longitudinals;
}

void add_web_frame(MeshBuilder& builder, const BallastTankMockupConfig& c, const Section& s) {
    const double x = 0.5 * c.length_m;
    const Loop3 manhole = detail::rectangle(
        Eigen::Vector3d(x, c.manhole_centre_y_m, c.manhole_centre_z_m), Eigen::Vector3d::UnitY(),
        Eigen::Vector3d::UnitZ(), -0.5 * c.manhole_width_m, 0.5 * c.manhole_width_m,
        -0.5 * c.manhole_height_m, 0.5 * c.manhole_height_m);
    builder.add_slab(section_at(s, x), {manhole}, Eigen::Vector3d::UnitX(), c.plate_thickness_m,
                     builder.surface("web_frame"), false);
}

FrameLine frame_line(int number, double x, const BallastTankMockupConfig& c, std::string surface) {
    return {number, Eigen::Vector3d(x, 0.5 * c.width_m, 0.5 * c.height_m), Eigen::Vector3d::UnitX(),
            std::move(surface)};
}

WorldMetadata metadata_of(const BallastTankMockupConfig& c, std::vector<FrameLine> longitudinals) {
    WorldMetadata m;
    m.name = std::string(kPrefix);
    const double mid = 0.5 * c.length_m;
    const double half_t = 0.5 * c.plate_thickness_m;
    detail::add_compartment(m, "compartment_1", {0, 0, 0}, {mid, c.width_m, c.height_m});
    detail::add_compartment(m, "compartment_2", {mid, 0, 0}, {c.length_m, c.width_m, c.height_m});
    m.frames = {frame_line(0, 0.0, c, "aft_bulkhead"), frame_line(1, mid, c, "web_frame"),
                frame_line(2, c.length_m, c, "fore_bulkhead")};
    m.longitudinals = std::move(longitudinals);
    detail::add_frame_landmarks(m, 0, m.frames[0], 0.0, m.longitudinals);
    detail::add_frame_landmarks(m, 0, m.frames[1], mid - half_t, m.longitudinals);
    detail::add_frame_landmarks(m, 1, m.frames[1], mid + half_t, m.longitudinals);
    detail::add_frame_landmarks(m, 1, m.frames[2], c.length_m, m.longitudinals);
    detail::add_connection(m, {0, ConnectionKind::Manhole, 0, 1,
                               Eigen::Vector3d(mid, c.manhole_centre_y_m, c.manhole_centre_z_m),
                               Eigen::Vector3d::UnitX(), c.manhole_width_m, c.manhole_height_m});
    detail::add_connection(m, {0, ConnectionKind::Entry, 0, Connection::kOutside,
                               Eigen::Vector3d(c.entry_centre_x_m, c.entry_centre_y_m, c.height_m),
                               Eigen::Vector3d::UnitZ(), c.entry_width_m, c.entry_length_m});
    return m;
}

}  // namespace

World build_ballast_tank_mockup(const BallastTankMockupConfig& config) {
    config.validate(kPrefix);
    const Section section = section_of(config);
    check_manhole(config, section);
    check_entry(config);
    MeshBuilder builder;
    std::vector<FrameLine> longitudinals = add_shell(builder, config, section);
    add_web_frame(builder, config, section);
    World world = builder.finish(metadata_of(config, std::move(longitudinals)));
    std::vector<int> walls;
    for (const char* name : {"bottom", "side_shell", "deck", "inboard_side", "hopper",
                             "aft_bulkhead", "fore_bulkhead", "web_frame"}) {
        walls.push_back(find_surface(world.metadata, name));
    }
    detail::place_defects(world, config.defects, walls, fmt::format("{}.defects", kPrefix));
    return world;
}

}  // namespace scantling::sim
