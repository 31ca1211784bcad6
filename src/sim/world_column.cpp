// Distillation column section with trays and downcomers (SPEC §7 art. F, §10).
#include <scantling/sim/world_builders.hpp>

#include "detail/defect_placement.hpp"
#include "detail/mesh_builder.hpp"
#include "detail/tank_parts.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

using detail::Loop3;
using detail::MeshBuilder;

constexpr std::string_view kPrefix = "distillation_column";
constexpr double kPi = std::numbers::pi;
const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();
const Eigen::Vector3d kY = Eigen::Vector3d::UnitY();
const Eigen::Vector3d kZ = Eigen::Vector3d::UnitZ();

struct Column {
    DistillationColumnConfig config;
    double radius_m = 0.0;
    double height_m = 0.0;
    std::vector<bool> manway_segment;  // wall segment k is cut by the man-way

    Loop3 ring(double z) const {
        return detail::circle_points({0, 0, z}, kZ, kX, radius_m, config.segments);
    }
    double tray_z(int k) const { return config.tray_spacing_m * k; }
    // Downcomer side of tray k: +x for odd k, -x for even k.
    double side(int k) const { return k % 2 == 1 ? 1.0 : -1.0; }
};

double angle_between(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * kPi)); }

Column column_of(const DistillationColumnConfig& c) {
    Column col{c, 0.5 * c.diameter_m, c.tray_spacing_m * (c.num_trays + 1), {}};
    const double half_angle = std::asin(std::min(1.0, 0.5 * c.manway_width_m / col.radius_m));
    const double step = 2.0 * kPi / c.segments;
    for (int k = 0; k < c.segments; ++k) {
        col.manway_segment.push_back(angle_between((k + 0.5) * step, c.manway_azimuth_rad) <=
                                     std::max(half_angle, 0.5 * step));
    }
    return col;
}

void add_shell(MeshBuilder& builder, const Column& col) {
    const auto& c = col.config;
    const int tag = builder.surface("shell");
    const std::vector<double> z{0.0, c.manway_sill_m, c.manway_sill_m + c.manway_height_m,
                                col.height_m};
    for (std::size_t r = 0; r + 1 < z.size(); ++r) {
        const Loop3 bottom = col.ring(z[r]), top = col.ring(z[r + 1]);
        for (int k = 0; k < c.segments; ++k) {
            if (r == 1 && col.manway_segment[k]) continue;
            const int k1 = (k + 1) % c.segments;
            builder.add_quad(bottom[k], top[k], top[k1], bottom[k1], tag);  // faces the axis
        }
    }
    builder.add_polygon(col.ring(0.0), {}, kZ, builder.surface("bottom_head"));
    builder.add_polygon(col.ring(col.height_m), {}, -kZ, builder.surface("top_head"));
}

// The part of the convex `ring` with side * x <= chord_m, and the chord's two end points.
struct Clipped {
    Loop3 deck;
    Eigen::Vector3d chord_a, chord_b;
};

Clipped clip_ring(const Loop3& ring, double side, double chord_m) {
    Clipped out;
    std::vector<Eigen::Vector3d> cuts;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const Eigen::Vector3d& p = ring[i];
        const Eigen::Vector3d& q = ring[(i + 1) % ring.size()];
        const bool p_in = side * p.x() <= chord_m, q_in = side * q.x() <= chord_m;
        if (p_in) out.deck.push_back(p);
        if (p_in != q_in) {
            const double t = (chord_m - side * p.x()) / (side * (q.x() - p.x()));
            cuts.push_back(p + t * (q - p));
            out.deck.push_back(cuts.back());
        }
    }
    out.chord_a = cuts.at(0);
    out.chord_b = cuts.at(1);
    return out;
}

// y extent of the convex ring along the line x = x_m.
std::pair<double, double> chord_at(const Loop3& ring, double x_m) {
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const Eigen::Vector3d& p = ring[i];
        const Eigen::Vector3d& q = ring[(i + 1) % ring.size()];
        if ((p.x() - x_m) * (q.x() - x_m) > 0.0 || p.x() == q.x()) continue;
        const double y = p.y() + (x_m - p.x()) / (q.x() - p.x()) * (q.y() - p.y());
        lo = std::min(lo, y);
        hi = std::max(hi, y);
    }
    return {lo, hi};
}

void add_tray(MeshBuilder& builder, const Column& col, int k) {
    const auto& c = col.config;
    const double z = col.tray_z(k), t = c.tray_thickness_m, s = col.side(k);
    const double chord = col.radius_m - c.downcomer_width_m;
    const Loop3 ring = col.ring(z);
    const Clipped clipped = clip_ring(ring, s, chord);
    builder.add_slab(clipped.deck, {}, kZ, t, builder.surface(fmt::format("tray_{}", k)));
    // Downcomer: from the weir top down to the clearance above the tray (or floor) below.
    const double below = k == 1 ? 0.0 : col.tray_z(k - 1) + 0.5 * t;
    const double z0 = below + c.downcomer_clearance_m, z1 = z + 0.5 * t + c.weir_height_m;
    const Eigen::Vector3d a = clipped.chord_a, b = clipped.chord_b;
    builder.add_slab(
        {{a.x(), a.y(), z0}, {b.x(), b.y(), z0}, {b.x(), b.y(), z1}, {a.x(), a.y(), z1}}, {}, kX, t,
        builder.surface(fmt::format("downcomer_{}", k)));
    const int beams = builder.surface(fmt::format("beams_{}", k));
    for (int j = 1; j <= c.beams_per_tray; ++j) {
        const double x = s * (-col.radius_m + (col.radius_m + chord) * j / (c.beams_per_tray + 1));
        const auto [y0, y1] = chord_at(ring, x);
        builder.add_box(
            detail::box_between(Eigen::Vector3d::Zero(), kX, kY, kZ,
                                {x - 0.5 * c.beam_width_m, y0, z - 0.5 * t - c.beam_height_m},
                                {x + 0.5 * c.beam_width_m, y1, z - 0.5 * t}),
            beams);
    }
}

WorldMetadata metadata_of(const Column& col) {
    const auto& c = col.config;
    WorldMetadata m;
    m.name = std::string(kPrefix);
    const double r = col.radius_m;
    for (int k = 0; k <= c.num_trays; ++k) {
        const double z1 = k == c.num_trays ? col.height_m : col.tray_z(k + 1);
        detail::add_compartment(m, fmt::format("space_{}", k), {-r, -r, col.tray_z(k)}, {r, r, z1});
    }
    for (int k = 1; k <= c.num_trays; ++k) {
        m.frames.push_back(
            {k, Eigen::Vector3d(0, 0, col.tray_z(k)), kZ, fmt::format("tray_{}", k)});
    }
    // The man-way spans whole wall segments: report the opening as built.
    const double step = 2.0 * kPi / c.segments;
    double sin_sum = 0.0, cos_sum = 0.0;
    int count = 0;
    for (int k = 0; k < c.segments; ++k) {
        if (!col.manway_segment[k]) continue;
        sin_sum += std::sin((k + 0.5) * step);
        cos_sum += std::cos((k + 0.5) * step);
        ++count;
    }
    const Eigen::Vector3d radial = Eigen::Vector3d(cos_sum, sin_sum, 0.0).normalized();
    const Eigen::Vector3d centre =
        r * std::cos(0.5 * step) * radial + (c.manway_sill_m + 0.5 * c.manway_height_m) * kZ;
    detail::add_connection(m, {0, ConnectionKind::Entry, 0, Connection::kOutside, centre, radial,
                               2.0 * r * std::sin(0.5 * count * step), c.manway_height_m});
    return m;
}

}  // namespace

World build_distillation_column(const DistillationColumnConfig& config) {
    config.validate(kPrefix);
    const Column col = column_of(config);
    MeshBuilder builder;
    add_shell(builder, col);
    for (int k = 1; k <= config.num_trays; ++k) add_tray(builder, col, k);
    World world = builder.finish(metadata_of(col));
    std::vector<int> walls;
    for (const Surface& s : world.metadata.surfaces) {
        if (s.name.rfind("beams_", 0) != 0) walls.push_back(s.tag);
    }
    detail::place_defects(world, config.defects, walls, fmt::format("{}.defects", kPrefix));
    return world;
}

}  // namespace scantling::sim
