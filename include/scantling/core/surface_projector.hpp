#pragma once
/// @file
/// Surfaces a crawler drives on (SPEC §6, §10): a projection of any nearby point onto the
/// surface, with the unit surface normal there (pointing into free space, the side the
/// crawler is on). Analytic plane, bounded plate and cylinder (storage tank wall), and any
/// triangle mesh.
///
/// Thread-safety: `project` is const and may be called concurrently. Determinism: pure.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include <scantling/core/triangle_mesh.hpp>

namespace scantling {

struct SurfacePoint {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();    ///< on the surface, world frame
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit, into free space
};

class SurfaceProjector {
  public:
    virtual ~SurfaceProjector() = default;

    /// The surface point closest to `p_world` and the normal there.
    virtual SurfacePoint project(const Eigen::Vector3d& p_world) const = 0;
};

/// An unbounded plane (a flat plate; its edges are the mission's business). O(1).
class PlaneSurface final : public SurfaceProjector {
  public:
    /// Plane through `point` with normal `normal` (normalised here; the crawler's side).
    /// Throws InputError for a non-finite point or a zero / non-finite normal.
    PlaneSurface(const Eigen::Vector3d& point, const Eigen::Vector3d& normal);
    SurfacePoint project(const Eigen::Vector3d& p_world) const override;

  private:
    Eigen::Vector3d point_;
    Eigen::Vector3d normal_;
};

/// A flat rectangular plate (the `plate` world): the plane's projection clamped to the
/// rectangle centre ± half_length_m · x_axis ± half_width_m · (normal × x_axis), so that a
/// walk on it stops at its edges (planning/surface_rectangle.hpp refuses a rectangle that runs
/// over them) where the unbounded plane would carry it on into the air. O(1).
class PlateSurface final : public SurfaceProjector {
  public:
    /// `x_axis` is made orthogonal to the normal. Throws InputError for non-finite input, a
    /// zero normal, an x_axis along the normal or a half size not > 0.
    PlateSurface(const Eigen::Vector3d& centre, const Eigen::Vector3d& normal,
                 const Eigen::Vector3d& x_axis, double half_length_m, double half_width_m);
    SurfacePoint project(const Eigen::Vector3d& p_world) const override;

  private:
    Eigen::Vector3d centre_;
    Eigen::Vector3d normal_;
    Eigen::Vector3d x_axis_;
    Eigen::Vector3d y_axis_;
    double half_length_m_;
    double half_width_m_;
};

enum class CylinderSide { kOutside, kInside };

/// An unbounded circular cylinder (a storage-tank shell), driven on from outside (normal away
/// from the axis) or inside (normal towards it). Points on the axis project along an
/// arbitrary but fixed radial direction. O(1).
class CylinderSurface final : public SurfaceProjector {
  public:
    /// Throws InputError for non-finite input, a zero axis or radius_m not > 0.
    CylinderSurface(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis_direction,
                    double radius_m, CylinderSide side = CylinderSide::kOutside);
    SurfacePoint project(const Eigen::Vector3d& p_world) const override;

  private:
    Eigen::Vector3d axis_point_;
    Eigen::Vector3d axis_;
    double radius_m_;
    double side_sign_;  ///< +1 outside, −1 inside
};

/// Any triangle mesh (ship hull, tank, Möbius strip). The normal is the triangle's normal
/// (counter-clockwise = free side, as in world.hpp) or, with `smooth_normals`, the
/// barycentric blend of the vertex normals (computed when the mesh has none), which turns
/// the body smoothly across edges instead of in jumps. Triangles without area are skipped (they
/// have no normal; a normal is never zero). Non-manifold meshes (an edge of three triangles, a
/// double-sided sheet) are projected onto like any other: the nearest triangle wins, ties to
/// the lowest index, so the answer is deterministic.
/// Cost: O(T) build of a uniform grid of triangle bounding boxes; a query visits the cells
/// around the point until no unvisited cell can hold a closer triangle (a few cells for a
/// point near the surface; degrades towards O(T) far from it).
class MeshSurface final : public SurfaceProjector {
  public:
    /// Throws InputError for an invalid or empty mesh, or one with no triangle with an area.
    explicit MeshSurface(TriangleMesh mesh, bool smooth_normals = true);
    SurfacePoint project(const Eigen::Vector3d& p_world) const override;

    const TriangleMesh& mesh() const { return mesh_; }

  private:
    struct Best {
        double distance2 = 0.0;
        Eigen::Vector3d point = Eigen::Vector3d::Zero();
        std::size_t triangle = 0;
    };

    void build_grid();
    Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const;
    std::size_t cell_index(const Eigen::Vector3i& c) const;
    void visit_cell(const Eigen::Vector3i& c, const Eigen::Vector3d& p, Best& best) const;
    void visit_ring(const Eigen::Vector3i& centre, int ring, const Eigen::Vector3d& p,
                    Best& best) const;
    Eigen::Vector3d normal_at(std::size_t triangle, const Eigen::Vector3d& point) const;

    TriangleMesh mesh_;
    bool smooth_normals_;
    Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
    double cell_m_ = 1.0;
    Eigen::Vector3i dims_ = Eigen::Vector3i::Ones();
    std::vector<std::uint32_t> cell_start_;  ///< CSR offsets, one per cell + 1
    std::vector<std::uint32_t> cell_triangles_;
};

}  // namespace scantling
