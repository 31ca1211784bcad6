#pragma once
// Builds tagged world meshes from planar polygons, plates and boxes (private to the simulator).
//
// Watertightness: every primitive emits exactly the 3D points it is given (or computes them
// once and reuses them), so edges shared by two primitives match bit for bit when the callers
// pass the same points; `finish` then merges identical vertices.

#include <scantling/sim/world.hpp>

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

namespace scantling::sim::detail {

using Loop3 = std::vector<Eigen::Vector3d>;

/// An oriented box: centre, three orthonormal axes (columns, right-handed) and half sizes.
struct Box {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
    Eigen::Vector3d half_size_m = Eigen::Vector3d::Zero();
};

/// Box of the points origin + a u + b v + c w with (a, b, c) in [lo, hi], for orthonormal
/// u, v, w of either handedness.
Box box_between(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                const Eigen::Vector3d& w, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

class MeshBuilder {
  public:
    /// Tag of the surface `name`, registering it on first use.
    int surface(const std::string& name, bool textured = true, double albedo = 0.5);

    void add_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      int tag);
    /// Quad a-b-c-d, counter-clockwise seen from the side it faces; split along a-c.
    void add_quad(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d, int tag);

    /// Planar polygon with holes (coplanar 3D loops, any orientation) facing `normal`.
    void add_polygon(const Loop3& outer, const std::vector<Loop3>& holes,
                     const Eigen::Vector3d& normal, int tag);

    /// Plate of `thickness_m` whose mid-plane is the polygon: both faces and the rims of the
    /// outline (unless `outline_rim` is false, e.g. where it is welded to a wall) and of the
    /// holes, all facing out of the material.
    void add_slab(const Loop3& outer, const std::vector<Loop3>& holes,
                  const Eigen::Vector3d& normal, double thickness_m, int tag,
                  bool outline_rim = true);

    /// Closed box, faces outward.
    void add_box(const Box& box, int tag);

    /// Regular `segments`-gon prism (a cylinder) of `radius_m` from `base` along unit `axis`
    /// for `length_m`; lateral faces outward (or inward), optional end caps facing the same
    /// way. Vertex k sits at angle 2πk/segments from `radial` (unit, ⟂ axis).
    void add_cylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& axis,
                      const Eigen::Vector3d& radial, double radius_m, double length_m, int segments,
                      bool outward, bool caps, int tag);

    std::size_t num_triangles() const { return triangles_.size(); }

    /// Merges identical vertices and returns the world with `metadata.surfaces` filled in.
    World finish(WorldMetadata metadata) const;

  private:
    std::vector<Eigen::Vector3d> vertices_;
    std::vector<Eigen::Vector3i> triangles_;
    std::vector<int> tags_;
    std::vector<Surface> surfaces_;
};

/// The ring of `segments` points at `radius_m` around `centre` in the plane ⟂ `axis`, starting
/// along `radial` and turning counter-clockwise about `axis`.
Loop3 circle_points(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis,
                    const Eigen::Vector3d& radial, double radius_m, int segments);

/// Rectangle [u0, u1] x [v0, v1] of the plane through `origin` spanned by unit u and v.
Loop3 rectangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                double u0, double u1, double v0, double v1);

}  // namespace scantling::sim::detail
