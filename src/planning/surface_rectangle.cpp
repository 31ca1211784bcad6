// The crawler's rectangle mission and lines laid on the surface (surface_rectangle.hpp).
#include <scantling/planning/surface_rectangle.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::planning {
namespace {

// A step that advances by less than this share of its length hit the surface's edge.
constexpr double kMinProgress = 0.5;

Eigen::Vector3d tangent(const Eigen::Vector3d& v, const Eigen::Vector3d& normal) {
    return v - v.dot(normal) * normal;
}

std::string point_text(const Eigen::Vector3d& p) {
    return fmt::format("({:.3f}, {:.3f}, {:.3f})", p.x(), p.y(), p.z());
}

/// One walking step from `p` along the tangent `direction` (unit); InputError at an edge.
SurfacePoint step_on(const SurfaceProjector& surface, const Eigen::Vector3d& p,
                     const Eigen::Vector3d& direction, double ds, std::string_view what) {
    const SurfacePoint q = surface.project(p + ds * direction);
    if (!((q.point - p).norm() >= kMinProgress * ds)) {
        throw InputError(fmt::format("{} leaves the surface at {}", what, point_text(p)));
    }
    return q;
}

void require_size(double value, std::string_view field) {
    if (!(std::isfinite(value) && value > 0.0)) {
        throw InputError(
            fmt::format("surface_rectangle.{} = {}, expected finite > 0", field, value));
    }
}

}  // namespace

void SurfaceWalkConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(march_step_m, prefix, "march_step_m");
    require_positive(segment_length_m, prefix, "segment_length_m");
    require_positive(max_start_distance_m, prefix, "max_start_distance_m");
}

Eigen::Vector3d walk_on_surface(const SurfaceProjector& surface, const Eigen::Vector3d& start,
                                const Eigen::Vector3d& direction_world, double distance_m,
                                const SurfaceWalkConfig& config, std::string_view what) {
    config.validate();
    SurfacePoint p = surface.project(start);
    Eigen::Vector3d d = tangent(direction_world, p.normal);
    if (!(d.norm() > 1e-9 * std::max(1.0, direction_world.norm()))) {
        throw InputError(fmt::format("{}: the direction is along the surface normal at {}", what,
                                     point_text(p.point)));
    }
    d.normalize();
    for (double remaining = distance_m; remaining > 1e-12; remaining -= config.march_step_m) {
        const double ds = std::min(config.march_step_m, remaining);
        p = step_on(surface, p.point, d, ds, what);
        d = tangent(d, p.normal).normalized();  // transported, as the crawler's heading
    }
    return p.point;
}

std::vector<MeshPathSegment> surface_line(const SurfaceProjector& surface,
                                          const Eigen::Vector3d& start, const Eigen::Vector3d& goal,
                                          const SurfaceWalkConfig& config) {
    config.validate();
    SurfacePoint p = surface.project(start);
    const Eigen::Vector3d g = surface.project(goal).point;
    const double budget_m = 3.0 * (g - p.point).norm() + 10.0 * config.march_step_m;
    std::vector<MeshPathSegment> segments;
    Eigen::Vector3d begin = p.point;
    double walked_m = 0.0;
    while ((g - p.point).norm() > 1e-9) {
        const Eigen::Vector3d to_goal = g - p.point;
        if (to_goal.norm() <= config.march_step_m) {
            p.point = g;
        } else {
            const Eigen::Vector3d d = tangent(to_goal, p.normal);
            p = step_on(surface, p.point, d.normalized(), config.march_step_m, "the line");
        }
        walked_m += config.march_step_m;
        if (walked_m > budget_m) {
            throw InputError(fmt::format("the line from {} does not reach {} on the surface",
                                         point_text(start), point_text(goal)));
        }
        const bool at_goal = (g - p.point).norm() <= 1e-9;
        if ((p.point - begin).norm() >= config.segment_length_m || at_goal) {
            if ((p.point - begin).norm() >= 1e-6) {
                const Eigen::Vector3d normal = surface.project(0.5 * (begin + p.point)).normal;
                segments.push_back({begin, p.point, normal, 0});
            }
            begin = p.point;
        }
    }
    return segments;
}

SurfaceRectanglePlan plan_surface_rectangle(const SurfaceRectangleRequest& request,
                                            const SurfaceProjector& surface,
                                            const SurfaceWalkConfig& config) {
    config.validate();
    require_size(request.width_m, "width_m");
    require_size(request.height_m, "height_m");
    require_size(request.max_step_m, "max_step_m");
    if (!request.start_world_m.allFinite() || !request.up_world.allFinite()) {
        throw InputError("surface_rectangle: start_world_m and up_world must be finite");
    }
    const SurfacePoint start = surface.project(request.start_world_m);
    const double off_m = (start.point - request.start_world_m).norm();
    if (!(off_m <= config.max_start_distance_m)) {
        throw InputError(fmt::format(
            "surface_rectangle.start_world_m = {} is {:.3f} m from the surface, expected <= {} m",
            point_text(request.start_world_m), off_m, config.max_start_distance_m));
    }
    SurfaceRectanglePlan plan;
    const Eigen::Vector3d up = tangent(request.up_world, start.normal);
    if (!(up.norm() > 1e-3 * request.up_world.norm())) {
        throw InputError(
            "surface_rectangle.up_world is along the surface normal at the start: no vertical "
            "transects on this surface");
    }
    plan.up_world = up.normalized();
    plan.across_world = plan.up_world.cross(start.normal).normalized();
    plan.transects =
        static_cast<std::size_t>(std::ceil(request.width_m / request.max_step_m - 1e-9)) + 1;
    plan.step_m = request.width_m / static_cast<double>(plan.transects - 1);
    for (std::size_t i = 0; i < plan.transects; ++i) {
        const Eigen::Vector3d bottom =
            walk_on_surface(surface, start.point, plan.across_world,
                            plan.step_m * static_cast<double>(i), config, "the rectangle's width");
        const Eigen::Vector3d top = walk_on_surface(
            surface, bottom, request.up_world, request.height_m, config, "the rectangle's height");
        const bool upwards = i % 2 == 0;
        plan.waypoints_world_m.push_back(upwards ? bottom : top);
        plan.waypoints_world_m.push_back(upwards ? top : bottom);
    }
    return plan;
}

}  // namespace scantling::planning
