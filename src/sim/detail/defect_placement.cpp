#include "defect_placement.hpp"

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/sim/ray_caster.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scantling::sim::detail {
namespace {

// A patch must be visible from this far in front of it: it is then on open wall, not under a
// stiffener flange or in a corner where the camera could not see it.
constexpr double kStandoff_m = 0.05;
constexpr int kRingSamples = 8;
constexpr int kAttemptsPerDefect = 200;
// Give up after this many rejections in a row: the surfaces are full.
constexpr int kMaxConsecutiveRejections = 5000;
// The plane-refined ray ranges are exact to ~1e-12 m; 1e-6 m separates "same plane" from a
// member overlapping the wall.
constexpr double kSamePlaneTolerance_m = 1e-6;

struct AreaTable {
    std::vector<std::size_t> triangles;
    std::vector<double> cumulative;  // running area sum, m²
};

AreaTable eligible_area(const World& world, std::span<const int> tags) {
    AreaTable table;
    double sum = 0.0;
    for (std::size_t i = 0; i < world.mesh.num_triangles(); ++i) {
        if (std::find(tags.begin(), tags.end(), world.surface_tags[i]) == tags.end()) continue;
        sum += triangle_area(world.mesh, i);
        table.triangles.push_back(i);
        table.cumulative.push_back(sum);
    }
    return table;
}

std::size_t pick_triangle(const AreaTable& table, Rng& rng) {
    const double u = rng.uniform() * table.cumulative.back();
    const auto it = std::upper_bound(table.cumulative.begin(), table.cumulative.end(), u);
    const auto k = std::min<std::size_t>(it - table.cumulative.begin(), table.triangles.size() - 1);
    return table.triangles[k];
}

Eigen::Vector3d uniform_point(const TriangleMesh& mesh, std::size_t triangle, Rng& rng) {
    double r1 = rng.uniform();
    double r2 = rng.uniform();
    if (r1 + r2 > 1.0) {
        r1 = 1.0 - r1;
        r2 = 1.0 - r2;
    }
    const Eigen::Vector3i& t = mesh.triangles[triangle];
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    return a + r1 * (mesh.vertices[t[1]] - a) + r2 * (mesh.vertices[t[2]] - a);
}

// The surface at `p` is in plane with normal `n` and seen from kStandoff_m in front.
bool seen_in_plane(const RayCaster& caster, const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
    const RayHit hit = caster.cast(p + kStandoff_m * n, -n, 2.0 * kStandoff_m);
    return hit.hit && std::abs(hit.range_m - kStandoff_m) < kSamePlaneTolerance_m;
}

bool patch_visible(const RayCaster& caster, const Defect& d) {
    if (!seen_in_plane(caster, d.centre, d.normal)) return false;
    const Eigen::Vector3d side = d.normal.cross(d.direction);
    for (int k = 0; k < kRingSamples; ++k) {
        const double angle = 2.0 * std::numbers::pi * k / kRingSamples;
        const Eigen::Vector3d p =
            d.centre + d.radius_m * (std::cos(angle) * d.direction + std::sin(angle) * side);
        if (!seen_in_plane(caster, p, d.normal)) return false;
    }
    return true;
}

bool overlaps(const std::vector<Defect>& placed, const Defect& d) {
    return std::any_of(placed.begin(), placed.end(), [&](const Defect& other) {
        return (other.centre - d.centre).norm() < other.radius_m + d.radius_m;
    });
}

Defect draw_defect(const World& world, const AreaTable& table, const DefectPlacementConfig& config,
                   Rng& rng) {
    Defect d;
    const std::size_t triangle = pick_triangle(table, rng);
    d.centre = uniform_point(world.mesh, triangle, rng);
    d.normal = triangle_normal(world.mesh, triangle);
    d.surface_tag = world.surface_tags[triangle];
    d.radius_m = rng.uniform(config.min_radius_m, config.max_radius_m);
    d.kind = rng.uniform() < config.crack_fraction ? DefectKind::Crack : DefectKind::Corrosion;
    const double angle = rng.uniform(0.0, 2.0 * std::numbers::pi);
    const Eigen::Vector3d e1 = d.normal.unitOrthogonal();
    d.direction = std::cos(angle) * e1 + std::sin(angle) * d.normal.cross(e1);
    return d;
}

}  // namespace

void place_defects(World& world, const DefectPlacementConfig& config,
                   std::span<const int> eligible_tags, std::string_view prefix) {
    if (config.count == 0) return;
    const AreaTable table = eligible_area(world, eligible_tags);
    std::vector<Defect>& defects = world.metadata.defects;
    const std::size_t before = defects.size();
    const std::size_t wanted = before + static_cast<std::size_t>(config.count);
    if (!table.triangles.empty()) {
        RayCasterConfig caster_config;
        caster_config.build_quality = BuildQuality::Medium;  // a few hundred rays only
        const RayCaster caster(world.mesh, world.surface_tags, caster_config);
        Rng rng(config.seed);
        const double min_patch_area = std::numbers::pi * config.min_radius_m * config.min_radius_m;
        const bool can_fit = table.cumulative.back() >= config.count * min_patch_area;
        int rejections = 0;
        for (long attempt = 0; can_fit && attempt < long{kAttemptsPerDefect} * config.count &&
                               rejections < kMaxConsecutiveRejections;
             ++attempt) {
            if (defects.size() == wanted) break;
            Defect d = draw_defect(world, table, config, rng);
            if (overlaps(defects, d) || !patch_visible(caster, d)) {
                ++rejections;
                continue;
            }
            rejections = 0;
            d.id = static_cast<int>(defects.size());
            d.compartment =
                io::compartment_at(world.metadata, d.centre + kStandoff_m * d.normal).value_or(-1);
            defects.push_back(d);
        }
    }
    if (defects.size() != wanted) {
        throw ConfigError(
            fmt::format("{}.count = {}, expected a number that fits: only {} "
                        "defects of radius [{}, {}] m could be placed",
                        prefix, config.count, defects.size() - before, config.min_radius_m,
                        config.max_radius_m));
    }
}

}  // namespace scantling::sim::detail
