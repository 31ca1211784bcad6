// Parametric hull section of SPEC §5 (issue 3, item 1 `ship_hull`): a cross-section profile
// swept along x, closed by a deck and end bulkheads, standing in a dry dock or at a quay.
#include <scantling/sim/world_hull.hpp>

#include "detail/defect_placement.hpp"
#include "detail/hull_appendages.hpp"
#include "detail/hull_surroundings.hpp"
#include "detail/mesh_builder.hpp"
#include "detail/ship_hull_shape.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

using detail::Loop3;
using detail::MeshBuilder;
using detail::s_squared;
using detail::side_y;
using detail::steps;

constexpr std::string_view kPrefix = "ship_hull";
constexpr double kPi = std::numbers::pi;
const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();
// The site compartment reaches this far beyond the mesh, so points just off a surface are in.
constexpr double kSiteMargin_m = 1.0;

enum Part { Keel, Bottom, Bilge, Side, Deck, kNumParts };
constexpr std::array<const char*, kNumParts> kPartNames{"keel", "bottom", "bilge", "side_shell",
                                                        "deck"};

// A profile point (y, z) and the part of the segment that starts at it.
struct ProfilePoint {
    Eigen::Vector2d yz;
    Part part;
};
using Profile = std::vector<ProfilePoint>;

// Appends the points from a to b (b excluded) in n steps.
void add_segment(Profile& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b, int n, Part part) {
    for (int k = 0; k < n; ++k) p.push_back({a + (b - a) * (double(k) / n), part});
}

// Starboard half from the keel-bottom centre to the deck edge (included, part Deck).
Profile starboard_half(const ShipHullConfig& c, double x) {
    const double kw = 0.5 * c.keel_width_m, kh = c.keel_height_m, r = c.bilge_radius_m;
    const double inward = c.side_curvature_m * s_squared(c, x);
    const double bilge_y = c.half_breadth_m - r - inward, side_z0 = kh + r;
    const double top_z = c.depth_m + c.sheer_m * s_squared(c, x);
    const double flat_bottom = c.half_breadth_m - r - kw;  // at midship: the grid is fixed
    Profile p;
    add_segment(p, {0, 0}, {kw, 0}, steps(kw, c.panel_size_m), Keel);
    add_segment(p, {kw, 0}, {kw, kh}, steps(kh, c.panel_size_m), Keel);
    add_segment(p, {kw, kh}, {bilge_y, kh}, steps(flat_bottom, c.panel_size_m), Bottom);
    for (int k = 0; k < c.bilge_segments; ++k) {
        const double a = -0.5 * kPi + 0.5 * kPi * k / c.bilge_segments;
        p.push_back({{bilge_y + r * std::cos(a), side_z0 + r * std::sin(a)}, Bilge});
    }
    const Eigen::Vector2d side_top(bilge_y + r + std::tan(c.flare_rad) * (top_z - side_z0), top_z);
    add_segment(p, {bilge_y + r, side_z0}, side_top, steps(c.depth_m - side_z0, c.panel_size_m),
                Side);
    p.push_back({side_top, Deck});
    return p;
}

// The closed section at x, counter-clockwise in (y, z): keel, starboard, deck, port.
Profile section(const ShipHullConfig& c, double x) {
    Profile p = starboard_half(c, x);
    const Eigen::Vector2d edge = p.back().yz;
    const Eigen::Vector2d port_edge(-edge.x(), edge.y());
    // A fixed count (the midship width) keeps the stations' points in step.
    const double side_z0 = c.keel_height_m + c.bilge_radius_m;
    const int n_deck = steps(
        2.0 * (c.half_breadth_m + std::tan(c.flare_rad) * (c.depth_m - side_z0)), c.panel_size_m);
    for (int k = 1; k < n_deck; ++k)
        p.push_back({edge + (port_edge - edge) * (double(k) / n_deck), Deck});
    const std::size_t half = p.size() - static_cast<std::size_t>(n_deck - 1);
    for (std::size_t j = half - 1; j >= 1; --j) {
        p.push_back({{-p[j].yz.x(), p[j].yz.y()}, p[j - 1].part});
    }
    return p;
}

Eigen::Vector3d at(double x, const ProfilePoint& p) { return {x, p.yz.x(), p.yz.y()}; }

void add_sweep(MeshBuilder& builder, const ShipHullConfig& c,
               const std::array<int, kNumParts>& tags) {
    const int n = steps(c.length_m, c.station_spacing_m);
    Profile prev = section(c, 0.0);
    for (int i = 1; i <= n; ++i) {
        const double x0 = c.length_m * (i - 1) / n, x1 = c.length_m * i / n;
        const Profile next = section(c, x1);
        for (std::size_t k = 0; k < prev.size(); ++k) {
            const std::size_t k1 = (k + 1) % prev.size();
            // Counter-clockwise seen from outside for a counter-clockwise section.
            builder.add_quad(at(x0, prev[k]), at(x0, prev[k1]), at(x1, next[k1]), at(x1, next[k]),
                             tags[prev[k].part]);
        }
        prev = next;
    }
}

void add_end(MeshBuilder& builder, const ShipHullConfig& c, double x, double facing, int tag) {
    Loop3 loop;
    for (const ProfilePoint& p : section(c, x)) loop.push_back(at(x, p));
    builder.add_polygon(loop, {}, facing * kX, tag);
}

WorldMetadata metadata_of(const ShipHullConfig& c) {
    WorldMetadata m;
    m.name = std::string(kPrefix);
    m.compartments.push_back({0, "site", {}, 0});
    const double side_z0 = c.keel_height_m + c.bilge_radius_m;
    for (int j = 1; side_z0 + j * c.longitudinal_spacing_m < c.depth_m; ++j) {
        const double z = side_z0 + j * c.longitudinal_spacing_m;
        const double x = 0.5 * c.length_m;
        m.longitudinals.push_back({j, {x, side_y(c, x, z), z}, kX, "side_shell"});
    }
    for (int k = 0; k * c.frame_spacing_m <= c.length_m + 1e-9; ++k) {
        const double x = k * c.frame_spacing_m;
        m.frames.push_back({k, {x, 0.0, 0.0}, kX, "side_shell"});
        for (const FrameLine& l : m.longitudinals) {
            const Eigen::Vector3d p(x, side_y(c, x, l.point.z()), l.point.z());
            m.landmarks.push_back({static_cast<int>(m.landmarks.size()),
                                   LandmarkKind::FrameLongitudinal, p, 0, k, l.number, -1});
        }
    }
    return m;
}

detail::HullExtent extent_of(const ShipHullConfig& c) {
    const double top_z = c.depth_m + c.sheer_m;
    const double widest =
        c.half_breadth_m + std::tan(c.flare_rad) * (top_z - c.keel_height_m - c.bilge_radius_m);
    const auto& s = c.surroundings;
    return {0.0, c.length_m, widest, 0.0,
            detail::centred_positions(0.5 * s.keel_block_length_m,
                                      c.length_m - 0.5 * s.keel_block_length_m,
                                      s.keel_block_spacing_m)};
}

}  // namespace

World build_ship_hull(const ShipHullConfig& config) {
    config.validate(kPrefix);
    MeshBuilder builder;
    std::array<int, kNumParts> tags{};
    for (int p = 0; p < kNumParts; ++p) tags[p] = builder.surface(kPartNames[p]);
    const int ends = builder.surface("section_end");
    add_sweep(builder, config, tags);
    add_end(builder, config, 0.0, -1.0, ends);
    add_end(builder, config, config.length_m, 1.0, ends);
    detail::add_surroundings(builder, extent_of(config), config.surroundings);
    // After the surroundings, so their tags do not move when appendages are added.
    detail::add_hull_appendages(builder, config);
    World world = builder.finish(metadata_of(config));
    Aabb site = compute_bounds(world.mesh);
    site.min.array() -= kSiteMargin_m;
    site.max.array() += kSiteMargin_m;
    world.metadata.compartments[0].bounds = site;
    const std::array<int, 3> shell{tags[Side], tags[Bilge], tags[Bottom]};
    detail::place_defects(world, config.defects, shell, fmt::format("{}.defects", kPrefix));
    return world;
}

void ShipHullConfig::validate(std::string_view prefix) const {
    using detail::require;
    using detail::require_positive;
    require_positive(prefix, "length_m", length_m);
    require_positive(prefix, "half_breadth_m", half_breadth_m);
    require_positive(prefix, "keel_width_m", keel_width_m);
    require_positive(prefix, "keel_height_m", keel_height_m);
    require_positive(prefix, "bilge_radius_m", bilge_radius_m);
    const double room = half_breadth_m - bilge_radius_m - 0.5 * keel_width_m;
    require(room > 0.0, prefix, "bilge_radius_m", bilge_radius_m,
            "< half_breadth_m - keel_width_m / 2 (room for a flat bottom)");
    require(std::isfinite(depth_m) && depth_m > keel_height_m + bilge_radius_m, prefix, "depth_m",
            depth_m, "> keel_height_m + bilge_radius_m (room for a side)");
    require(std::isfinite(flare_rad) && std::abs(flare_rad) < 0.5, prefix, "flare_rad", flare_rad,
            "in (-0.5, 0.5)");
    require(std::isfinite(side_curvature_m) && side_curvature_m >= 0.0 && side_curvature_m < room,
            prefix, "side_curvature_m", side_curvature_m,
            fmt::format("in [0, {}) (narrower than the flat bottom)", room));
    detail::require_non_negative(prefix, "sheer_m", sheer_m);
    require_positive(prefix, "station_spacing_m", station_spacing_m);
    require_positive(prefix, "panel_size_m", panel_size_m);
    require(bilge_segments >= 2, prefix, "bilge_segments", bilge_segments, ">= 2");
    require_positive(prefix, "frame_spacing_m", frame_spacing_m);
    require_positive(prefix, "longitudinal_spacing_m", longitudinal_spacing_m);
    surroundings.validate(fmt::format("{}.surroundings", prefix));
    require(surroundings.environment != HullEnvironment::kQuay || surroundings.draught_m < depth_m,
            prefix, "surroundings.draught_m", surroundings.draught_m, "< depth_m (afloat)");
    defects.validate(fmt::format("{}.defects", prefix));
    detail::validate_hull_appendages(*this, fmt::format("{}.appendages", prefix));
}

}  // namespace scantling::sim
