#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/triangle_mesh.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace scantling {
namespace {

// Beyond this the cloud alone needs > 48 GB: surely a unit mistake in spacing_m.
constexpr double kMaxSamplePoints = 1e9;

// Closest point on segment [a, b] to p (degenerate-triangle fallback).
Eigen::Vector3d closest_point_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                         const Eigen::Vector3d& b) {
    const Eigen::Vector3d ab = b - a;
    const double len2 = ab.squaredNorm();
    if (len2 == 0.0) return a;
    return a + std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) * ab;
}

Eigen::Vector3d closest_on_degenerate(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                      const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    Eigen::Vector3d best = closest_point_on_segment(p, a, b);
    for (const Eigen::Vector3d& q :
         {closest_point_on_segment(p, b, c), closest_point_on_segment(p, c, a)}) {
        if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    }
    return best;
}

// Running sum of triangle areas: triangle i owns [cumulative[i-1], cumulative[i]).
std::vector<double> cumulative_areas(const TriangleMesh& mesh) {
    std::vector<double> cumulative(mesh.num_triangles());
    double sum = 0.0;
    for (std::size_t i = 0; i < mesh.num_triangles(); ++i) {
        sum += triangle_area(mesh, i);
        cumulative[i] = sum;
    }
    return cumulative;
}

std::size_t pick_triangle(const std::vector<double>& cumulative, double u) {
    const double target = u * cumulative.back();
    auto it = std::upper_bound(cumulative.begin(), cumulative.end(), target);
    // Rounding may put target at the very end; the last positive-area triangle owns it.
    if (it == cumulative.end())
        it = std::lower_bound(cumulative.begin(), cumulative.end(), cumulative.back());
    return static_cast<std::size_t>(it - cumulative.begin());
}

}  // namespace

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d ab = b - a;
    const Eigen::Vector3d ac = c - a;
    if (ab.cross(ac).squaredNorm() == 0.0) return closest_on_degenerate(p, a, b, c);
    // Voronoi regions in the order of Ericson §5.1.5: vertices, edges, then the face.
    const Eigen::Vector3d ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + d1 / (d1 - d3) * ab;
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + d2 / (d2 - d6) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    }
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

MeshClosestPoint closest_point_on_mesh(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
    if (mesh.empty()) throw InputError("closest_point_on_mesh: the mesh has no triangles");
    MeshClosestPoint best;
    best.distance_m = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < mesh.num_triangles(); ++i) {
        const Eigen::Vector3i& tri = mesh.triangles[i];
        const Eigen::Vector3d q = closest_point_on_triangle(
            p, mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
        const double distance_m = (q - p).norm();
        if (distance_m < best.distance_m) best = {q, i, distance_m};
    }
    return best;
}

PointCloud sample_surface_count(const TriangleMesh& mesh, std::size_t count, Rng& rng) {
    check_valid(mesh, "sample_surface");
    PointCloud cloud;
    if (count == 0) return cloud;
    const std::vector<double> cumulative = cumulative_areas(mesh);
    if (cumulative.empty() || !(cumulative.back() > 0.0)) {
        throw InputError("sample_surface: the mesh has zero surface area");
    }
    cloud.points.reserve(count);
    cloud.normals.reserve(count);
    for (std::size_t k = 0; k < count; ++k) {
        const std::size_t t = pick_triangle(cumulative, rng.uniform());
        const Eigen::Vector3i& tri = mesh.triangles[t];
        // sqrt(r1) makes the barycentric point uniform over the triangle's area.
        const double s = std::sqrt(rng.uniform());
        const double r2 = rng.uniform();
        cloud.points.push_back((1.0 - s) * mesh.vertices[tri[0]] +
                               s * (1.0 - r2) * mesh.vertices[tri[1]] +
                               s * r2 * mesh.vertices[tri[2]]);
        cloud.normals.push_back(triangle_normal(mesh, t));
    }
    return cloud;
}

PointCloud sample_surface_spacing(const TriangleMesh& mesh, double spacing_m, Rng& rng) {
    if (!std::isfinite(spacing_m) || !(spacing_m > 0.0)) {
        throw InputError(
            fmt::format("sample_surface: spacing_m = {}, expected finite > 0", spacing_m));
    }
    check_valid(mesh, "sample_surface");
    const double count = std::round(surface_area(mesh) / (spacing_m * spacing_m));
    if (count > kMaxSamplePoints) {
        throw InputError(
            fmt::format("sample_surface: spacing_m = {} gives {:.3g} points, expected <= {:.0g}",
                        spacing_m, count, kMaxSamplePoints));
    }
    return sample_surface_count(mesh, static_cast<std::size_t>(count), rng);
}

}  // namespace scantling
