// The crawler's rectangle mission and lines laid on the surface (surface_rectangle.hpp).
//
// Leaving the surface. On a smooth surface the projection of a step's target moves it along
// the normal only; at the surface's border (an open mesh edge, a hole's rim, or a sharp fold
// such as the 1 cm rim of a plate or of the thick Möbius strip) it pulls the target back along
// the surface instead. A step is refused when it advances by less than half its length (a
// border met head on), or when the pull, summed over consecutive steps that are each pulled
// by more than 2 % of their length, exceeds half a step: a walk meeting the border at a
// grazing angle otherwise slides along it with full progress, and a rectangle laid too close
// to the edge came back silently clamped onto the border (the Möbius strip's geodesic bottom
// edge, 4 m long). A fold of a faceted hull (20°) pulls one or two steps by a few per cent
// and passes; a smooth surface pulls none.
#include <scantling/planning/surface_rectangle.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

#include "detail/surface_geometry.hpp"

namespace scantling::planning {
namespace {

using detail::point_text;
using detail::tangent;

// A step that advances by less than this share of its length hit the surface's edge.
constexpr double kMinProgress = 0.5;
// A step pulled back along the surface by more than this share of its length was clamped at
// the border (curvature pulls ~ds²κ², a 20° fold ~0.06 ds, both once, not step after step).
constexpr double kClampedShare = 0.02;
// The pull of consecutive clamped steps that means the walk is sliding along the border.
constexpr double kMaxSlideShare = 0.5;

/// A walk's steps on the surface, refused at the border as the file's comment says.
class Walker {
  public:
    Walker(const SurfaceProjector& surface, std::string_view what)
        : surface_(surface), what_(what) {}

    /// One step from `p` along the tangent `direction` (unit); InputError at the border.
    SurfacePoint step(const Eigen::Vector3d& p, const Eigen::Vector3d& direction, double ds) {
        const Eigen::Vector3d target = p + ds * direction;
        const SurfacePoint q = surface_.project(target);
        const double pulled_m = tangent(q.point - target, q.normal).norm();
        slide_m_ = pulled_m > kClampedShare * ds ? slide_m_ + pulled_m : 0.0;
        if (!((q.point - p).norm() >= kMinProgress * ds && slide_m_ <= kMaxSlideShare * ds)) {
            throw InputError(fmt::format("{} leaves the surface at {} (an edge or a hole of it)",
                                         what_, point_text(p)));
        }
        return q;
    }

  private:
    const SurfaceProjector& surface_;
    std::string what_;
    double slide_m_ = 0.0;  ///< the pull of the current run of clamped steps
};

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

SurfacePoint snap_to_surface(const SurfaceProjector& surface, const Eigen::Vector3d& p_world,
                             double max_distance_m, std::string_view field) {
    if (!p_world.allFinite()) {
        throw InputError(fmt::format("{} = {} is not finite", field, point_text(p_world)));
    }
    const SurfacePoint snapped = surface.project(p_world);
    const double off_m = (snapped.point - p_world).norm();
    if (!(off_m <= max_distance_m)) {
        throw InputError(fmt::format("{} = {} is {:.3f} m from the surface, expected <= {} m",
                                     field, point_text(p_world), off_m, max_distance_m));
    }
    return snapped;
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
    Walker walker(surface, what);
    for (double remaining = distance_m; remaining > 1e-12; remaining -= config.march_step_m) {
        const double ds = std::min(config.march_step_m, remaining);
        p = walker.step(p.point, d, ds);
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
    Walker walker(surface, "the line");
    while ((g - p.point).norm() > 1e-9) {
        const Eigen::Vector3d to_goal = g - p.point;
        if (to_goal.norm() <= config.march_step_m) {
            p.point = g;
        } else {
            const Eigen::Vector3d d = tangent(to_goal, p.normal);
            p = walker.step(p.point, d.normalized(), config.march_step_m);
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
    const SurfacePoint start =
        snap_to_surface(surface, request.start_world_m, config.max_start_distance_m,
                        "surface_rectangle.start_world_m");
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
        const double across_m = plan.step_m * static_cast<double>(i);
        const Eigen::Vector3d bottom = walk_on_surface(
            surface, start.point, plan.across_world, across_m, config,
            fmt::format("surface_rectangle.width_m: the bottom edge ({:.3f} m across to transect "
                        "{} of {})",
                        across_m, i + 1, plan.transects));
        const Eigen::Vector3d top = walk_on_surface(
            surface, bottom, request.up_world, request.height_m, config,
            fmt::format("surface_rectangle.height_m: transect {} of {} ({:.3f} m up from {})",
                        i + 1, plan.transects, request.height_m, point_text(bottom)));
        const bool upwards = i % 2 == 0;
        plan.waypoints_world_m.push_back(upwards ? bottom : top);
        plan.waypoints_world_m.push_back(upwards ? top : bottom);
    }
    return plan;
}

}  // namespace scantling::planning
