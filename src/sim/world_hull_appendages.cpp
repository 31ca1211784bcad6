// Hull appendages (issue 14, item 6; SPEC §5 obstacles): bilge keels, sacrificial anodes and
// sea-chest gratings welded onto the parametric hull section of world_ship_hull.cpp.
#include "detail/hull_appendages.hpp"

#include <scantling/sim/scenario_limits.hpp>

#include "detail/sensor_checks.hpp"
#include "detail/ship_hull_shape.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>

namespace scantling::sim::detail {
namespace {

// Every piece's inner face sits this far inside the shell: it closes the gap between a flat
// base and the faceted, curved shell (well under 1 mm for these sizes) and stays hidden.
constexpr double kWeld_m = 0.01;
const double kCos45 = std::sqrt(0.5);
const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();

double sign_of(HullSide side) { return side == HullSide::kStarboard ? 1.0 : -1.0; }

Eigen::Vector3d mirrored(const Eigen::Vector3d& v, double sign) {
    return {v.x(), sign * v.y(), v.z()};
}

// Orthonormal frame of the +y side shell at (x, z): u along the hull (the chord over
// ±half_length_m, so a flat base follows the curved side), w up the shell, n outward.
struct ShellFrame {
    Eigen::Vector3d p, u, w, n;
};

ShellFrame shell_frame(const ShipHullConfig& c, double x, double z, double half_length_m) {
    const auto point = [&](double xi) { return Eigen::Vector3d(xi, side_y(c, xi, z), z); };
    ShellFrame f;
    f.p = point(x);
    f.u = (point(x + half_length_m) - point(x - half_length_m)).normalized();
    const Eigen::Vector3d up(0.0, std::tan(c.flare_rad), 1.0);
    f.w = (up - up.dot(f.u) * f.u).normalized();
    f.n = f.w.cross(f.u);
    return f;
}

// Box [lo, hi] in (u, w, n) of the frame, on the shell of `side`.
void add_on_shell(MeshBuilder& builder, const ShellFrame& f, HullSide side,
                  const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int tag) {
    const double s = sign_of(side);
    builder.add_box(
        box_between(mirrored(f.p, s), mirrored(f.u, s), mirrored(f.w, s), mirrored(f.n, s), lo, hi),
        tag);
}

void add_anode(MeshBuilder& builder, const ShipHullConfig& c, const HullAnode& a, int tag) {
    const ShellFrame f = shell_frame(c, a.x_m, a.z_m, 0.5 * a.length_m);
    const Eigen::Vector3d half(0.5 * a.length_m, 0.5 * a.height_m, 0.0);
    add_on_shell(builder, f, a.side, {-half.x(), -half.y(), -kWeld_m},
                 {half.x(), half.y(), a.thickness_m}, tag);
}

double grating_length_m(const SeaChestGrating& g) {
    return (g.bar_count - 1) * g.bar_spacing_m + g.bar_width_m;
}

void add_grating(MeshBuilder& builder, const ShipHullConfig& c, const SeaChestGrating& g, int tag) {
    const ShellFrame f = shell_frame(c, g.x_m, g.z_m, 0.5 * grating_length_m(g));
    for (int k = 0; k < g.bar_count; ++k) {
        const double u = (k - 0.5 * (g.bar_count - 1)) * g.bar_spacing_m;
        add_on_shell(builder, f, g.side, {u - 0.5 * g.bar_width_m, -0.5 * g.height_m, -kWeld_m},
                     {u + 0.5 * g.bar_width_m, 0.5 * g.height_m, g.stand_off_m}, tag);
    }
}

// Bilge-keel cross-section on the +y side at x, counter-clockwise in (y, z): a plate along
// the bilge's outward normal at 45° (out and down), centred on the girth through that point.
std::array<Eigen::Vector2d, 4> keel_section(const ShipHullConfig& c, const BilgeKeel& k, double x) {
    const double r = c.bilge_radius_m, z0 = c.keel_height_m + r;
    const Eigen::Vector2d centre(side_y(c, x, z0) - r, z0);  // the bilge arc's, as the sweep's
    const Eigen::Vector2d n(kCos45, -kCos45), t(kCos45, kCos45);
    const Eigen::Vector2d root = centre + (r - kWeld_m) * n, tip = centre + (r + k.depth_m) * n;
    const Eigen::Vector2d half = 0.5 * k.thickness_m * t;
    return {root - half, tip - half, tip + half, root + half};
}

// The section at x on `side` as 3D points, counter-clockwise seen from +x (mirroring
// reverses the order, so the port side is read backwards).
std::array<Eigen::Vector3d, 4> keel_loop(const ShipHullConfig& c, const BilgeKeel& k, double x,
                                         double sign) {
    const auto yz = keel_section(c, k, x);
    std::array<Eigen::Vector3d, 4> loop;
    for (int j = 0; j < 4; ++j) {
        const Eigen::Vector2d& q = yz[sign > 0.0 ? j : 3 - j];
        loop[j] = {x, sign * q.x(), q.y()};
    }
    return loop;
}

// Stations of the hull sweep inside (x_start, x_end), plus both ends: the plate's kinks
// fall where the shell's do, so it follows the faceted bilge exactly.
std::vector<double> keel_stations(const ShipHullConfig& c, const BilgeKeel& k) {
    const int n = steps(c.length_m, c.station_spacing_m);
    std::vector<double> xs{k.x_start_m};
    for (int i = 1; i < n; ++i) {
        const double x = c.length_m * i / n;
        if (x > k.x_start_m && x < k.x_end_m) xs.push_back(x);
    }
    xs.push_back(k.x_end_m);
    return xs;
}

void add_bilge_keel(MeshBuilder& builder, const ShipHullConfig& c, const BilgeKeel& k, double sign,
                    int tag) {
    const std::vector<double> xs = keel_stations(c, k);
    for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
        const auto a = keel_loop(c, k, xs[i], sign), b = keel_loop(c, k, xs[i + 1], sign);
        for (int j = 0; j < 4; ++j)
            builder.add_quad(a[j], a[(j + 1) % 4], b[(j + 1) % 4], b[j], tag);
    }
    const auto first = keel_loop(c, k, xs.front(), sign), last = keel_loop(c, k, xs.back(), sign);
    builder.add_polygon(Loop3(first.begin(), first.end()), {}, -kX, tag);
    builder.add_polygon(Loop3(last.begin(), last.end()), {}, kX, tag);
}

void validate_bilge_keel(const ShipHullConfig& c, const BilgeKeel& k, const std::string& p) {
    const double length = c.length_m;
    require(std::isfinite(k.x_start_m) && k.x_start_m >= 0.0 && k.x_start_m < length, p,
            "x_start_m", k.x_start_m, fmt::format("in [0, {}) (on the hull)", length));
    require(std::isfinite(k.x_end_m) && k.x_end_m > k.x_start_m && k.x_end_m <= length, p,
            "x_end_m", k.x_end_m, fmt::format("in (x_start_m, {}] (on the hull)", length));
    require_positive(p, "depth_m", k.depth_m);
    require_positive(p, "thickness_m", k.thickness_m);
    // Bilge keels stay above the base line; a deeper one would cut into the keel blocks.
    const double r = c.bilge_radius_m, z0 = c.keel_height_m + r;
    require(z0 - (r + k.depth_m) * kCos45 > 0.0, p, "depth_m", k.depth_m,
            fmt::format("< {} (the tip above the keel bottom)", z0 / kCos45 - r));
    require(k.thickness_m < r, p, "thickness_m", k.thickness_m,
            fmt::format("< bilge_radius_m = {}", r));
}

// The shell patch x ± half_length_m, z ± half_height_m lies on the side shell above the bilge,
// below the deck edge and, at a quay (the one place the world knows the draught), under water.
void require_on_side_shell(const ShipHullConfig& c, const std::string& p, double x, double z,
                           double half_length_m, double half_height_m) {
    const double x_lo = half_length_m, x_hi = c.length_m - half_length_m;
    require(std::isfinite(x) && x >= x_lo && x <= x_hi, p, "x_m", x,
            fmt::format("in [{}, {}] (the whole piece on the hull)", x_lo, x_hi));
    const bool afloat = c.surroundings.environment == HullEnvironment::kQuay;
    const double top_z = afloat ? c.surroundings.draught_m : c.depth_m;
    const double z_lo = c.keel_height_m + c.bilge_radius_m + half_height_m;
    const double z_hi = top_z - half_height_m;
    require(std::isfinite(z) && z >= z_lo && z <= z_hi, p, "z_m", z,
            fmt::format("in [{}, {}] (on the side shell, {})", z_lo, z_hi,
                        afloat ? "below the water line at draught_m" : "below the deck edge"));
}

void validate_anode(const ShipHullConfig& c, const HullAnode& a, const std::string& p) {
    require_positive(p, "length_m", a.length_m);
    require_positive(p, "height_m", a.height_m);
    require_positive(p, "thickness_m", a.thickness_m);
    require_on_side_shell(c, p, a.x_m, a.z_m, 0.5 * a.length_m, 0.5 * a.height_m);
}

void validate_grating(const ShipHullConfig& c, const SeaChestGrating& g, const std::string& p) {
    require(g.bar_count >= 1 && g.bar_count <= limits::kMaxSegments, p, "bar_count", g.bar_count,
            fmt::format("in [1, {}]", limits::kMaxSegments));
    require_positive(p, "bar_spacing_m", g.bar_spacing_m);
    require_positive(p, "bar_width_m", g.bar_width_m);
    require(g.bar_width_m < g.bar_spacing_m, p, "bar_width_m", g.bar_width_m,
            fmt::format("< bar_spacing_m = {} (gaps between the bars)", g.bar_spacing_m));
    require_positive(p, "height_m", g.height_m);
    require_positive(p, "stand_off_m", g.stand_off_m);
    require_on_side_shell(c, p, g.x_m, g.z_m, 0.5 * grating_length_m(g), 0.5 * g.height_m);
}

template <class T, class Check>
void validate_list(const ShipHullConfig& c, const std::vector<T>& items, const std::string& key,
                   Check check) {
    require(items.size() <= static_cast<std::size_t>(limits::kMaxStructureCount), key, "size",
            static_cast<double>(items.size()), fmt::format("<= {}", limits::kMaxStructureCount));
    for (std::size_t i = 0; i < items.size(); ++i)
        check(c, items[i], fmt::format("{}[{}]", key, i));
}

}  // namespace

void add_hull_appendages(MeshBuilder& builder, const ShipHullConfig& config) {
    const HullAppendagesConfig& a = config.appendages;
    if (!a.bilge_keels.empty()) {
        const int tag = builder.surface("bilge_keel");
        for (const BilgeKeel& k : a.bilge_keels) {
            add_bilge_keel(builder, config, k, 1.0, tag);
            add_bilge_keel(builder, config, k, -1.0, tag);
        }
    }
    if (!a.anodes.empty()) {
        const int tag = builder.surface("anode");
        for (const HullAnode& anode : a.anodes) add_anode(builder, config, anode, tag);
    }
    if (!a.gratings.empty()) {
        const int tag = builder.surface("sea_chest_grating");
        for (const SeaChestGrating& g : a.gratings) add_grating(builder, config, g, tag);
    }
}

void validate_hull_appendages(const ShipHullConfig& config, const std::string& prefix) {
    const HullAppendagesConfig& a = config.appendages;
    validate_list(config, a.bilge_keels, prefix + ".bilge_keels", validate_bilge_keel);
    validate_list(config, a.anodes, prefix + ".anodes", validate_anode);
    validate_list(config, a.gratings, prefix + ".gratings", validate_grating);
}

}  // namespace scantling::sim::detail
