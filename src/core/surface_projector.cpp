#include <scantling/core/error.hpp>
#include <scantling/core/surface_projector.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace scantling {
namespace {

Eigen::Vector3d unit_or_throw(const Eigen::Vector3d& v, const char* what) {
    const double n = v.norm();
    if (!v.allFinite() || !(n > 0.0)) {
        throw InputError(fmt::format("{} = ({}, {}, {}), expected a finite non-zero vector", what,
                                     v.x(), v.y(), v.z()));
    }
    return v / n;
}

/// A unit vector orthogonal to `axis` (unit), fixed for a given axis.
Eigen::Vector3d any_orthogonal(const Eigen::Vector3d& axis) {
    const Eigen::Vector3d helper =
        std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    return axis.cross(helper).normalized();
}

}  // namespace

PlaneSurface::PlaneSurface(const Eigen::Vector3d& point, const Eigen::Vector3d& normal)
    : point_(point), normal_(unit_or_throw(normal, "PlaneSurface normal")) {
    if (!point.allFinite()) throw InputError("PlaneSurface point is not finite");
}

SurfacePoint PlaneSurface::project(const Eigen::Vector3d& p_world) const {
    return {p_world - normal_ * normal_.dot(p_world - point_), normal_};
}

PlateSurface::PlateSurface(const Eigen::Vector3d& centre, const Eigen::Vector3d& normal,
                           const Eigen::Vector3d& x_axis, double half_length_m, double half_width_m)
    : centre_(centre),
      normal_(unit_or_throw(normal, "PlateSurface normal")),
      x_axis_(unit_or_throw(x_axis - x_axis.dot(normal_) * normal_,
                            "PlateSurface x_axis (its part across the normal)")),
      y_axis_(normal_.cross(x_axis_)),
      half_length_m_(half_length_m),
      half_width_m_(half_width_m) {
    if (!centre.allFinite()) throw InputError("PlateSurface centre is not finite");
    if (!(std::isfinite(half_length_m) && half_length_m > 0.0 && std::isfinite(half_width_m) &&
          half_width_m > 0.0)) {
        throw InputError(
            fmt::format("PlateSurface half_length_m = {}, half_width_m = {}, expected finite > 0",
                        half_length_m, half_width_m));
    }
}

SurfacePoint PlateSurface::project(const Eigen::Vector3d& p_world) const {
    const Eigen::Vector3d d = p_world - centre_;
    const double a = std::clamp(d.dot(x_axis_), -half_length_m_, half_length_m_);
    const double b = std::clamp(d.dot(y_axis_), -half_width_m_, half_width_m_);
    return {centre_ + a * x_axis_ + b * y_axis_, normal_};
}

CylinderSurface::CylinderSurface(const Eigen::Vector3d& axis_point,
                                 const Eigen::Vector3d& axis_direction, double radius_m,
                                 CylinderSide side)
    : axis_point_(axis_point),
      axis_(unit_or_throw(axis_direction, "CylinderSurface axis_direction")),
      radius_m_(radius_m),
      side_sign_(side == CylinderSide::kOutside ? 1.0 : -1.0) {
    if (!axis_point.allFinite()) throw InputError("CylinderSurface axis_point is not finite");
    if (!(std::isfinite(radius_m) && radius_m > 0.0)) {
        throw InputError(fmt::format("CylinderSurface radius_m = {}, expected > 0", radius_m));
    }
}

SurfacePoint CylinderSurface::project(const Eigen::Vector3d& p_world) const {
    const Eigen::Vector3d d = p_world - axis_point_;
    const Eigen::Vector3d on_axis = axis_point_ + axis_ * axis_.dot(d);
    const Eigen::Vector3d radial = p_world - on_axis;
    const double n = radial.norm();
    const Eigen::Vector3d outward = n > 0.0 ? Eigen::Vector3d(radial / n) : any_orthogonal(axis_);
    return {on_axis + radius_m_ * outward, side_sign_ * outward};
}

}  // namespace scantling
