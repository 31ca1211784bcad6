// Vertical storage tank seen from outside: weld seams and nozzles (SPEC §10).
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

constexpr std::string_view kPrefix = "storage_tank";
constexpr double kPi = std::numbers::pi;
// Seams and nozzles reach this far into the shell, so no slit shows at their foot.
constexpr double kEmbed_m = 0.002;
constexpr int kNozzleSegments = 24;
constexpr double kFlangeRadiusFactor = 1.4;
constexpr double kFlangeThickness_m = 0.04;
// Nozzles sit between 1.2 m above the bottom and 1.2 m below the roof.
constexpr double kNozzleMargin_m = 1.2;
const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();
const Eigen::Vector3d kZ = Eigen::Vector3d::UnitZ();

struct Tank {
    StorageTankConfig config;
    double radius_m = 0.0;
    double facet_radius_m = 0.0;  // axis to the middle of a shell facet

    // Unit radial direction through the middle of the facet nearest to `angle`.
    Eigen::Vector3d facet_direction(double angle) const {
        const double step = 2.0 * kPi / config.segments;
        const double mid = (std::floor(angle / step) + 0.5) * step;
        return {std::cos(mid), std::sin(mid), 0.0};
    }
};

// Ring seam: a band proud of the shell, with annular top and bottom faces.
void add_ring_seam(MeshBuilder& builder, const Tank& tank, double z, int tag) {
    const auto& c = tank.config;
    const double z0 = z - 0.5 * c.seam_width_m, z1 = z + 0.5 * c.seam_width_m;
    const double outer = tank.radius_m + c.seam_height_m;
    const double inner = tank.facet_radius_m - kEmbed_m;
    builder.add_cylinder({0, 0, z0}, kZ, kX, outer, c.seam_width_m, c.segments, true, false, tag);
    const auto ring = [&](double r, double zz) {
        return detail::circle_points({0, 0, zz}, kZ, kX, r, c.segments);
    };
    builder.add_polygon(ring(outer, z1), {ring(inner, z1)}, kZ, tag);
    builder.add_polygon(ring(outer, z0), {ring(inner, z0)}, -kZ, tag);
}

void add_vertical_seam(MeshBuilder& builder, const Tank& tank, double angle, double z0, double z1,
                       int tag) {
    const auto& c = tank.config;
    const Eigen::Vector3d radial = tank.facet_direction(angle);
    const Eigen::Vector3d tangent = kZ.cross(radial);
    const double r0 = tank.facet_radius_m - kEmbed_m;
    builder.add_box(
        detail::box_between(Eigen::Vector3d::Zero(), radial, tangent, kZ,
                            {r0, -0.5 * c.seam_width_m, z0},
                            {tank.facet_radius_m + c.seam_height_m, 0.5 * c.seam_width_m, z1}),
        tag);
}

void add_seams(MeshBuilder& builder, const Tank& tank) {
    const auto& c = tank.config;
    const int ring_tag = builder.surface("ring_seams");
    const int vertical_tag = builder.surface("vertical_seams");
    const int courses = static_cast<int>(std::ceil(c.height_m / c.course_height_m - 1e-9));
    for (int j = 0; j < courses; ++j) {
        const double z0 = j * c.course_height_m;
        const double z1 = std::min(c.height_m, z0 + c.course_height_m);
        if (j > 0) add_ring_seam(builder, tank, z0, ring_tag);
        for (int i = 0; i < c.vertical_seams_per_course; ++i) {
            // Staggered by half a plate between courses, as plates are laid.
            const double angle = 2.0 * kPi * (i + 0.5 * (j % 2)) / c.vertical_seams_per_course;
            add_vertical_seam(builder, tank, angle + 1e-6, z0, z1, vertical_tag);
        }
    }
}

double nozzle_height(const Tank& tank, int i) {
    const auto& c = tank.config;
    if (c.num_nozzles == 1) return kNozzleMargin_m;
    const double span = std::max(0.0, c.height_m - 2.0 * kNozzleMargin_m);
    return std::min(c.height_m - c.nozzle_radius_m * kFlangeRadiusFactor,
                    kNozzleMargin_m + span * i / (c.num_nozzles - 1));
}

void add_nozzles(MeshBuilder& builder, const Tank& tank) {
    const auto& c = tank.config;
    const int tag = builder.surface("nozzles");
    for (int i = 0; i < c.num_nozzles; ++i) {
        const Eigen::Vector3d radial = tank.facet_direction(2.0 * kPi * (i + 0.25) / c.num_nozzles);
        const double z = nozzle_height(tank, i);
        // The pipe starts inside the shell (its open end is hidden) and ends in a blind flange.
        const double r0 = tank.facet_radius_m - c.nozzle_radius_m;
        const double length = tank.radius_m + c.nozzle_length_m - r0;
        const Eigen::Vector3d base = r0 * radial + z * kZ;
        builder.add_cylinder(base, radial, kZ, c.nozzle_radius_m, length, kNozzleSegments, true,
                             false, tag);
        builder.add_cylinder(base + (length - kFlangeThickness_m) * radial, radial, kZ,
                             kFlangeRadiusFactor * c.nozzle_radius_m, kFlangeThickness_m,
                             kNozzleSegments, true, true, tag);
    }
}

WorldMetadata metadata_of(const Tank& tank) {
    const auto& c = tank.config;
    WorldMetadata m;
    m.name = std::string(kPrefix);
    const double r = tank.radius_m;
    detail::add_compartment(m, "interior", {-r, -r, 0.0}, {r, r, c.height_m});
    const int courses = static_cast<int>(std::ceil(c.height_m / c.course_height_m - 1e-9));
    for (int j = 1; j < courses; ++j) {  // ring seams: surveyors count courses
        m.frames.push_back({j, Eigen::Vector3d(0, 0, j * c.course_height_m), kZ, "ring_seams"});
    }
    return m;
}

// Ground slab, square bund wall (0.3 m thick) and three pipe supports outside the bund.
void add_tank_farm(MeshBuilder& builder, const StorageTankConfig& c) {
    const double b = c.bund_half_size_m;
    const double t = 0.3;
    const int ground = builder.surface("ground");
    const int bund = builder.surface("bund");
    const double g = b + 15.0;
    builder.add_box({{0.0, 0.0, -0.25}, Eigen::Matrix3d::Identity(), {g, g, 0.25}}, ground);
    const double h = c.bund_height_m;
    builder.add_box({{0.0, b, 0.5 * h}, Eigen::Matrix3d::Identity(), {b + t, 0.5 * t, 0.5 * h}},
                    bund);
    builder.add_box({{0.0, -b, 0.5 * h}, Eigen::Matrix3d::Identity(), {b + t, 0.5 * t, 0.5 * h}},
                    bund);
    builder.add_box({{b, 0.0, 0.5 * h}, Eigen::Matrix3d::Identity(), {0.5 * t, b - t, 0.5 * h}},
                    bund);
    builder.add_box({{-b, 0.0, 0.5 * h}, Eigen::Matrix3d::Identity(), {0.5 * t, b - t, 0.5 * h}},
                    bund);
    const int supports = builder.surface("pipe_supports");
    for (int i = 0; i < 3; ++i) {
        const double y = -0.5 * b + 0.5 * b * i;
        builder.add_box({{b + 4.0, y, 2.0}, Eigen::Matrix3d::Identity(), {0.2, 0.2, 2.0}},
                        supports);
        builder.add_box({{b + 4.0, y, 4.1}, Eigen::Matrix3d::Identity(), {1.5, 0.2, 0.1}},
                        supports);
    }
}

}  // namespace

World build_storage_tank(const StorageTankConfig& config) {
    config.validate(kPrefix);
    const double radius = 0.5 * config.diameter_m;
    const Tank tank{config, radius, radius * std::cos(kPi / config.segments)};
    MeshBuilder builder;
    builder.add_cylinder(Eigen::Vector3d::Zero(), kZ, kX, radius, config.height_m, config.segments,
                         true, false, builder.surface("shell"));
    builder.add_polygon(
        detail::circle_points({0, 0, config.height_m}, kZ, kX, radius, config.segments), {}, kZ,
        builder.surface("roof"));
    builder.add_polygon(
        detail::circle_points(Eigen::Vector3d::Zero(), kZ, kX, radius, config.segments), {}, -kZ,
        builder.surface("bottom"));
    add_seams(builder, tank);
    add_nozzles(builder, tank);
    if (config.bund_half_size_m > 0.0) add_tank_farm(builder, config);
    World world = builder.finish(metadata_of(tank));
    const int shell = find_surface(world.metadata, "shell");
    detail::place_defects(world, config.defects, std::span<const int>(&shell, 1),
                          fmt::format("{}.defects", kPrefix));
    return world;
}

}  // namespace scantling::sim
