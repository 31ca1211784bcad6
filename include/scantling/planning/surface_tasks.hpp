#pragma once
/// @file
/// The crawler's mission tasks (SPEC §6; D5.2 §II.3's task list), each laid on the surface as
/// the legs the segment follower drives (control/segment_follower.hpp):
///
///   go_to                    GoToMesh: to a goal on the surface, along the exact geodesic
///                            when the surface is a triangle mesh (planning/mesh_path.hpp,
///                            CGAL), else along the walked line (surface_line).
///   rectangle                start_mission(x, y, z, W, H): the drive to the corner, then the
///                            vertical transects (planning/surface_rectangle.hpp).
///   vertical_transect        one straight leg up (or down) the surface, `length_m`.
///   horizontal_transect      one leg across, keeping the height: aimed at the point `length_m`
///                            across (up × normal, or against it), which on a vertical cylinder
///                            is the horizontal circle.
///   drive_between_stiffeners, drive_on_stiffener, drive_on_stiffener_side
///                            one leg of `length_m` along the centre line of the face the crawler
///                            stands on, bounded by the stiffeners' webs, by the flange's edges
///                            or by the plate and the web's edge: the geometry comes from the
///                            LiDAR at run time (perception/face_corridor.hpp), the leg from
///                            lay_corridor_task.
///
/// Legs are laid from where the crawler is when the task begins (its estimate), so a task list
/// needs no positions but the goals. Every leg is "approach" (to the task's first point:
/// go_to, the drive to a rectangle's corner, the join onto a corridor) or "inspection" (the
/// transects and drives); the mission scores the inspection legs.
///
/// Errors: InputError naming the task's field ("tasks[2].length_m ...") for a non-finite or
/// non-positive size, a goal off the surface, a direction along the normal (no vertical on a
/// floor), or a leg that leaves the surface. Frames: world, metres. Pure functions,
/// deterministic.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/surface_projector.hpp>
#include <scantling/core/triangle_mesh.hpp>
#include <scantling/planning/mesh_path.hpp>
#include <scantling/planning/surface_rectangle.hpp>

namespace scantling::planning {

enum class SurfaceTaskType {
    kGoTo,
    kRectangle,
    kVerticalTransect,
    kHorizontalTransect,
    kDriveBetweenStiffeners,
    kDriveOnStiffener,
    kDriveOnStiffenerSide,
};

/// "go_to", "rectangle", ... as the YAML writes them.
std::string_view to_string(SurfaceTaskType type);
/// The type named `text`; nullopt for an unknown name.
std::optional<SurfaceTaskType> surface_task_type_from(std::string_view text);
/// The "a, b, c" list of the names, for error messages.
std::string surface_task_type_names();

struct SurfaceTask {
    SurfaceTaskType type = SurfaceTaskType::kGoTo;
    Eigen::Vector3d goal_world_m = Eigen::Vector3d::Zero();  ///< go_to
    SurfaceRectangleRequest rectangle{};                     ///< rectangle
    /// Transects and stiffener drives, m, > 0.
    double length_m = 1.0;
    /// Vertical transect: down instead of up; horizontal: against "across" (up × normal: to the
    /// right for a robot facing the surface from outside), i.e. to the left.
    bool reverse = false;
    Eigen::Vector3d up_world = Eigen::Vector3d::UnitZ();  ///< the transects' vertical

    /// True for the three stiffener drives: their leg needs the LiDAR's corridor.
    bool needs_corridor() const;
    /// Throws InputError naming "<prefix>.<field>".
    void validate(std::string_view prefix) const;
};

/// One leg and what it is for.
struct TaskLeg {
    std::vector<MeshPathSegment> segments;
    bool inspection = false;  ///< scored (transects, drives); false: approach
};

struct TaskPlan {
    std::vector<TaskLeg> legs;
    std::vector<Eigen::Vector3d> waypoints_world_m;  ///< every leg's end
    std::size_t transects = 0;                       ///< rectangle: its transects
    double step_m = 0.0;                             ///< rectangle: the adjusted spacing
};

/// A geometric task (not a corridor one: InputError) laid from `p_world_m`. `mesh`: the
/// surface's triangle mesh when it is one (go_to then takes the geodesic), else null.
/// `prefix` names the task in errors ("tasks[1]").
TaskPlan lay_surface_task(const SurfaceTask& task, const SurfaceProjector& surface,
                          const TriangleMesh* mesh, const Eigen::Vector3d& p_world_m,
                          const SurfaceWalkConfig& walk, std::string_view prefix);

/// A corridor task laid from `p_world_m` on the corridor's centre line (`origin_world_m`,
/// `direction_world`, from the LiDAR): an approach leg onto the line `join_m` ahead of the
/// crawler's foot on it, then the inspection leg of `task.length_m` along it. InputError
/// naming `prefix` when the line is not finite or leaves the surface.
TaskPlan lay_corridor_task(const SurfaceTask& task, const SurfaceProjector& surface,
                           const Eigen::Vector3d& p_world_m, const Eigen::Vector3d& origin_world_m,
                           const Eigen::Vector3d& direction_world, double join_m,
                           const SurfaceWalkConfig& walk, std::string_view prefix);

}  // namespace scantling::planning
