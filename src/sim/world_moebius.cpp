// Möbius strip of the crawler runs (SPEC §6, issue 3, item 1 `moebius`).
#include <scantling/sim/world_hull.hpp>

#include "detail/defect_placement.hpp"
#include "detail/hull_surroundings.hpp"
#include "detail/mesh_builder.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

constexpr std::string_view kPrefix = "moebius";
constexpr double kPi = std::numbers::pi;

// Grid of the strip: column i (u = 2πi/n), row j (v from -w/2 to w/2); column n is column 0
// with v reversed and, for a thick strip, on the other face (the seam).
struct Strip {
    MoebiusConfig c;
    std::vector<Eigen::Vector3d> faces[2];  // [face][i * (m + 1) + j], face 1 = −n side

    int rows() const { return c.segments_across + 1; }
    const Eigen::Vector3d& point(int face, int i, int j) const {
        if (i == c.segments_around)
            return faces[c.thickness_m > 0.0 ? 1 - face : face]
                        [static_cast<std::size_t>(c.segments_across - j)];
        return faces[face][static_cast<std::size_t>(i * rows() + j)];
    }
};

double u_of(const MoebiusConfig& c, int i) { return 2.0 * kPi * i / c.segments_around; }
double v_of(const MoebiusConfig& c, int j) {
    return c.width_m * (double(j) / c.segments_across - 0.5);
}

Eigen::Vector3d mid_point(double r, double u, double v) {
    const double a = r + v * std::cos(0.5 * u);
    return {a * std::cos(u), a * std::sin(u), v * std::sin(0.5 * u)};
}

Eigen::Vector3d d_dv(double u) {
    return {std::cos(0.5 * u) * std::cos(u), std::cos(0.5 * u) * std::sin(u), std::sin(0.5 * u)};
}

// Unit n = ∂p/∂u × ∂p/∂v.
Eigen::Vector3d normal_at(double r, double u, double v) {
    const double a = r + v * std::cos(0.5 * u), h = -0.5 * v * std::sin(0.5 * u);
    const Eigen::Vector3d d_du(h * std::cos(u) - a * std::sin(u), h * std::sin(u) + a * std::cos(u),
                               0.5 * v * std::cos(0.5 * u));
    return d_du.cross(d_dv(u)).normalized();
}

Strip make_strip(const MoebiusConfig& c) {
    Strip s{c, {}};
    const double half_t = 0.5 * c.thickness_m;
    for (int i = 0; i < c.segments_around; ++i) {
        for (int j = 0; j < s.rows(); ++j) {
            const double u = u_of(c, i), v = v_of(c, j);
            const Eigen::Vector3d p = mid_point(c.radius_m, u, v), n = normal_at(c.radius_m, u, v);
            s.faces[0].push_back(p + half_t * n);
            if (c.thickness_m > 0.0) s.faces[1].push_back(p - half_t * n);
        }
    }
    return s;
}

// Quad a-b-c-d wound so that it faces `outward`.
void add_facing(detail::MeshBuilder& builder, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                const Eigen::Vector3d& c, const Eigen::Vector3d& d, const Eigen::Vector3d& outward,
                int tag) {
    if ((c - a).cross(d - b).dot(outward) >= 0.0) {
        builder.add_quad(a, b, c, d, tag);
    } else {
        builder.add_quad(a, d, c, b, tag);
    }
}

void add_faces(detail::MeshBuilder& builder, const Strip& s, int tag) {
    const auto& c = s.c;
    const int num_faces = c.thickness_m > 0.0 ? 2 : 1;
    for (int f = 0; f < num_faces; ++f) {
        for (int i = 0; i < c.segments_around; ++i) {
            for (int j = 0; j < c.segments_across; ++j) {
                const double u = u_of(c, i) + kPi / c.segments_around;
                const double v = v_of(c, j) + 0.5 * c.width_m / c.segments_across;
                const Eigen::Vector3d n = (f == 0 ? 1.0 : -1.0) * normal_at(c.radius_m, u, v);
                add_facing(builder, s.point(f, i, j), s.point(f, i + 1, j),
                           s.point(f, i + 1, j + 1), s.point(f, i, j + 1), n, tag);
            }
        }
    }
}

// Closes a thick strip along both edges (v = ±w/2), facing away from the centre line.
void add_rims(detail::MeshBuilder& builder, const Strip& s, int tag) {
    const auto& c = s.c;
    for (int i = 0; i < c.segments_around; ++i) {
        const double u = u_of(c, i) + kPi / c.segments_around;
        for (const int j : {0, c.segments_across}) {
            const Eigen::Vector3d out = (j == 0 ? -1.0 : 1.0) * d_dv(u);
            add_facing(builder, s.point(0, i, j), s.point(0, i + 1, j), s.point(1, i + 1, j),
                       s.point(1, i, j), out, tag);
        }
    }
}

}  // namespace

World build_moebius(const MoebiusConfig& config) {
    config.validate(kPrefix);
    const Strip strip = make_strip(config);
    detail::MeshBuilder builder;
    const int tag = builder.surface("strip");
    add_faces(builder, strip, tag);
    if (config.thickness_m > 0.0) add_rims(builder, strip, builder.surface("rim"));
    WorldMetadata metadata;
    metadata.name = std::string(kPrefix);
    World world = builder.finish(std::move(metadata));
    detail::place_defects(world, config.defects, std::span<const int>(&tag, 1),
                          fmt::format("{}.defects", kPrefix));
    return world;
}

void MoebiusConfig::validate(std::string_view prefix) const {
    detail::require_positive(prefix, "radius_m", radius_m);
    detail::require(std::isfinite(width_m) && width_m > 0.0 && width_m < radius_m, prefix,
                    "width_m", width_m, fmt::format("in (0, radius_m = {})", radius_m));
    detail::require(std::isfinite(thickness_m) && thickness_m >= 0.0 && thickness_m < width_m,
                    prefix, "thickness_m", thickness_m, "in [0, width_m) (0 = a single sheet)");
    detail::require(segments_around >= 8, prefix, "segments_around", segments_around, ">= 8");
    detail::require(segments_across >= 1, prefix, "segments_across", segments_across, ">= 1");
    defects.validate(fmt::format("{}.defects", prefix));
}

}  // namespace scantling::sim
