// The crawler's mission tasks laid on the surface (surface_tasks.hpp).
#include <scantling/planning/surface_tasks.hpp>

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <utility>

#include <scantling/core/error.hpp>

#include "detail/surface_geometry.hpp"

namespace scantling::planning {
namespace {

using detail::tangent;

constexpr std::array<std::pair<SurfaceTaskType, std::string_view>, 7> kNames{{
    {SurfaceTaskType::kGoTo, "go_to"},
    {SurfaceTaskType::kRectangle, "rectangle"},
    {SurfaceTaskType::kVerticalTransect, "vertical_transect"},
    {SurfaceTaskType::kHorizontalTransect, "horizontal_transect"},
    {SurfaceTaskType::kDriveBetweenStiffeners, "drive_between_stiffeners"},
    {SurfaceTaskType::kDriveOnStiffener, "drive_on_stiffener"},
    {SurfaceTaskType::kDriveOnStiffenerSide, "drive_on_stiffener_side"},
}};

void add_leg(TaskPlan& plan, std::vector<MeshPathSegment> segments, bool inspection) {
    if (segments.empty()) return;  // already there
    plan.waypoints_world_m.push_back(segments.back().end_world_m);
    plan.legs.push_back({std::move(segments), inspection});
}

std::vector<MeshPathSegment> go_to_segments(const SurfaceTask& task,
                                            const SurfaceProjector& surface,
                                            const TriangleMesh* mesh, const Eigen::Vector3d& p,
                                            const SurfaceWalkConfig& walk,
                                            std::string_view prefix) {
    snap_to_surface(surface, task.goal_world_m, walk.max_start_distance_m,
                    fmt::format("{}.goal_m", prefix));
    if (mesh == nullptr) return surface_line(surface, p, task.goal_world_m, walk);
    const MeshPathConfig config{.max_snap_distance_m = walk.max_start_distance_m};
    return shortest_path_on_mesh(*mesh, p, task.goal_world_m, config).segments;
}

TaskPlan rectangle_plan(const SurfaceTask& task, const SurfaceProjector& surface,
                        const Eigen::Vector3d& p, const SurfaceWalkConfig& walk) {
    const SurfaceRectanglePlan rectangle = plan_surface_rectangle(task.rectangle, surface, walk);
    TaskPlan plan;
    plan.transects = rectangle.transects;
    plan.step_m = rectangle.step_m;
    Eigen::Vector3d from = p;
    for (std::size_t i = 0; i < rectangle.waypoints_world_m.size(); ++i) {
        const Eigen::Vector3d& to = rectangle.waypoints_world_m[i];
        add_leg(plan, surface_line(surface, from, to, walk), i > 0);
        from = to;
    }
    return plan;
}

/// A transect's end: `length_m` along the up (vertical) or across (horizontal) direction.
Eigen::Vector3d transect_end(const SurfaceTask& task, const SurfaceProjector& surface,
                             const Eigen::Vector3d& p, const SurfaceWalkConfig& walk,
                             std::string_view prefix) {
    const SurfacePoint start = surface.project(p);
    const Eigen::Vector3d up = tangent(task.up_world, start.normal);
    if (!(up.norm() > 1e-3 * task.up_world.norm())) {
        throw InputError(
            fmt::format("{}.up is along the surface normal at the crawler: no "
                        "vertical (nor horizontal) on this surface",
                        prefix));
    }
    const double sign = task.reverse ? -1.0 : 1.0;
    const Eigen::Vector3d direction =
        task.type == SurfaceTaskType::kVerticalTransect
            ? Eigen::Vector3d(sign * up.normalized())
            : Eigen::Vector3d(sign * up.normalized().cross(start.normal).normalized());
    return walk_on_surface(surface, start.point, direction, task.length_m, walk,
                           fmt::format("{}.length_m: the transect", prefix));
}

}  // namespace

std::string_view to_string(SurfaceTaskType type) {
    for (const auto& [t, name] : kNames) {
        if (t == type) return name;
    }
    return "unknown";
}

std::optional<SurfaceTaskType> surface_task_type_from(std::string_view text) {
    for (const auto& [t, name] : kNames) {
        if (name == text) return t;
    }
    return std::nullopt;
}

std::string surface_task_type_names() {
    std::string names;
    for (const auto& [t, name] : kNames) names += (names.empty() ? "" : ", ") + std::string(name);
    return names;
}

bool SurfaceTask::needs_corridor() const {
    return type == SurfaceTaskType::kDriveBetweenStiffeners ||
           type == SurfaceTaskType::kDriveOnStiffener ||
           type == SurfaceTaskType::kDriveOnStiffenerSide;
}

void SurfaceTask::validate(std::string_view prefix) const {
    const auto fail = [&](std::string_view field, const std::string& what) {
        throw InputError(fmt::format("{}.{}: {}", prefix, field, what));
    };
    if (type == SurfaceTaskType::kGoTo && !goal_world_m.allFinite()) fail("goal_m", "not finite");
    if (type != SurfaceTaskType::kGoTo && type != SurfaceTaskType::kRectangle &&
        !(std::isfinite(length_m) && length_m > 0.0)) {
        fail("length_m", fmt::format("{}, expected finite > 0", length_m));
    }
    if (!up_world.allFinite() || up_world.norm() < 1e-9) fail("up", "expected a finite direction");
}

TaskPlan lay_surface_task(const SurfaceTask& task, const SurfaceProjector& surface,
                          const TriangleMesh* mesh, const Eigen::Vector3d& p_world_m,
                          const SurfaceWalkConfig& walk, std::string_view prefix) {
    task.validate(prefix);
    if (task.needs_corridor()) {
        throw InputError(
            fmt::format("{}: {} is laid on the LiDAR's corridor", prefix, to_string(task.type)));
    }
    if (!p_world_m.allFinite())
        throw InputError(fmt::format("{}: the start is not finite", prefix));
    TaskPlan plan;
    switch (task.type) {
        case SurfaceTaskType::kGoTo:
            add_leg(plan, go_to_segments(task, surface, mesh, p_world_m, walk, prefix), false);
            return plan;
        case SurfaceTaskType::kRectangle:
            return rectangle_plan(task, surface, p_world_m, walk);
        default: {
            const Eigen::Vector3d end = transect_end(task, surface, p_world_m, walk, prefix);
            add_leg(plan, surface_line(surface, p_world_m, end, walk), true);
            return plan;
        }
    }
}

TaskPlan lay_corridor_task(const SurfaceTask& task, const SurfaceProjector& surface,
                           const Eigen::Vector3d& p_world_m, const Eigen::Vector3d& origin_world_m,
                           const Eigen::Vector3d& direction_world, double join_m,
                           const SurfaceWalkConfig& walk, std::string_view prefix) {
    task.validate(prefix);
    if (!p_world_m.allFinite() || !origin_world_m.allFinite() || !direction_world.allFinite() ||
        direction_world.norm() < 1e-9 || !std::isfinite(join_m)) {
        throw InputError(fmt::format("{}: the corridor's centre line is not finite", prefix));
    }
    const Eigen::Vector3d d = direction_world.normalized();
    const Eigen::Vector3d foot = origin_world_m + d * d.dot(p_world_m - origin_world_m);
    const Eigen::Vector3d join = foot + d * join_m;
    const Eigen::Vector3d end = join + d * task.length_m;
    snap_to_surface(surface, join, walk.max_start_distance_m,
                    fmt::format("{}: the corridor's start", prefix));
    snap_to_surface(surface, end, walk.max_start_distance_m,
                    fmt::format("{}.length_m: the corridor's end", prefix));
    TaskPlan plan;
    add_leg(plan, surface_line(surface, p_world_m, join, walk), false);
    add_leg(plan, surface_line(surface, join, end, walk), true);
    return plan;
}

}  // namespace scantling::planning
