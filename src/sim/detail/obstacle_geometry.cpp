#include "obstacle_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scantling::sim::detail {
namespace {

bool within(double t, double min_range_m, double max_range_m) {
    return t >= min_range_m && t <= max_range_m;
}

/// The nearer of the entry and exit ranges that lies in [min, max], or nullopt.
std::optional<double> first_within(double t_entry, double t_exit, double min_range_m,
                                   double max_range_m) {
    if (within(t_entry, min_range_m, max_range_m)) return t_entry;
    if (within(t_exit, min_range_m, max_range_m)) return t_exit;
    return std::nullopt;
}

/// The slab interval of one axis, or false when the ray runs parallel to it outside the slab.
/// A parallel ray inside the slab leaves the interval unchanged (no 0 · inf).
bool clip_slab(double origin, double direction, double low, double high, int axis, double& t_entry,
               int& entry_axis, double& t_exit, int& exit_axis) {
    if (direction == 0.0) return origin >= low && origin <= high;
    const double t_low = (low - origin) / direction;
    const double t_high = (high - origin) / direction;
    const double t_near = std::min(t_low, t_high);
    const double t_far = std::max(t_low, t_high);
    if (t_near > t_entry) {
        t_entry = t_near;
        entry_axis = axis;
    }
    if (t_far < t_exit) {
        t_exit = t_far;
        exit_axis = axis;
    }
    return true;
}

}  // namespace

std::optional<ShapeHit> intersect_sphere(const Eigen::Vector3d& centre, double radius_m,
                                         const Eigen::Vector3d& origin,
                                         const Eigen::Vector3d& unit_direction, double min_range_m,
                                         double max_range_m) {
    // Distance of the centre from the ray line via the perpendicular vector (not b² − 4ac):
    // no cancellation for a small sphere far away.
    const Eigen::Vector3d to_centre = centre - origin;
    const double t_closest = to_centre.dot(unit_direction);
    const double d2 = (to_centre - t_closest * unit_direction).squaredNorm();
    const double r2 = radius_m * radius_m;
    if (d2 > r2) return std::nullopt;
    const double half_chord_m = std::sqrt(r2 - d2);
    const std::optional<double> t =
        first_within(t_closest - half_chord_m, t_closest + half_chord_m, min_range_m, max_range_m);
    if (!t) return std::nullopt;
    // Normalised rather than divided by the radius: unit to rounding even for a tiny sphere.
    Eigen::Vector3d normal = (origin + *t * unit_direction - centre).normalized();
    if (normal.dot(unit_direction) > 0.0) normal = -normal;
    return ShapeHit{*t, normal};
}

std::optional<ShapeHit> intersect_box(const Eigen::Vector3d& centre,
                                      const Eigen::Vector3d& half_extents_m,
                                      const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& unit_direction, double min_range_m,
                                      double max_range_m) {
    double t_entry = -std::numeric_limits<double>::infinity();
    double t_exit = std::numeric_limits<double>::infinity();
    int entry_axis = -1;
    int exit_axis = -1;
    for (int i = 0; i < 3; ++i) {
        if (!clip_slab(origin[i], unit_direction[i], centre[i] - half_extents_m[i],
                       centre[i] + half_extents_m[i], i, t_entry, entry_axis, t_exit, exit_axis)) {
            return std::nullopt;
        }
    }
    // A unit direction has a non-zero component, so both axes are set past this point.
    if (t_entry > t_exit || entry_axis < 0 || exit_axis < 0) return std::nullopt;
    const std::optional<double> t = first_within(t_entry, t_exit, min_range_m, max_range_m);
    if (!t) return std::nullopt;
    const int axis = *t == t_entry ? entry_axis : exit_axis;
    // Entry or exit face alike: the normal facing the ray points against the direction.
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    normal[axis] = unit_direction[axis] > 0.0 ? -1.0 : 1.0;
    return ShapeHit{*t, normal};
}

double sphere_distance_m(const Eigen::Vector3d& centre, double radius_m, const Eigen::Vector3d& p) {
    return (p - centre).norm() - radius_m;
}

double box_distance_m(const Eigen::Vector3d& centre, const Eigen::Vector3d& half_extents_m,
                      const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = (p - centre).cwiseAbs() - half_extents_m;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

}  // namespace scantling::sim::detail
