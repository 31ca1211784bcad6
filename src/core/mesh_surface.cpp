#include <scantling/core/error.hpp>
#include <scantling/core/surface_projector.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace scantling {
namespace {

// Bound on the grid size: beyond it cells grow instead (memory ~ 4 bytes per cell).
constexpr double kMaxCells = 2e6;

/// Barycentric weights of `p` (a point of triangle abc) or nullopt-like (-1) if degenerate.
Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d e0 = b - a, e1 = c - a, ep = p - a;
    const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
    const double d20 = ep.dot(e0), d21 = ep.dot(e1);
    const double det = d00 * d11 - d01 * d01;
    if (!(det > 0.0)) return Eigen::Vector3d::Constant(-1.0);
    const double v = (d11 * d20 - d01 * d21) / det;
    const double w = (d00 * d21 - d01 * d20) / det;
    return {1.0 - v - w, v, w};
}

/// Typical triangle size: mean of the largest bounding-box side of each triangle.
double mean_triangle_extent(const TriangleMesh& mesh) {
    double sum = 0.0;
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3d& a = mesh.vertices[t[0]];
        const Eigen::Vector3d lo = a.cwiseMin(mesh.vertices[t[1]]).cwiseMin(mesh.vertices[t[2]]);
        const Eigen::Vector3d hi = a.cwiseMax(mesh.vertices[t[1]]).cwiseMax(mesh.vertices[t[2]]);
        sum += (hi - lo).maxCoeff();
    }
    return sum / static_cast<double>(mesh.triangles.size());
}

}  // namespace

MeshSurface::MeshSurface(TriangleMesh mesh, bool smooth_normals)
    : mesh_(std::move(mesh)), smooth_normals_(smooth_normals) {
    check_valid(mesh_, "MeshSurface mesh");
    if (mesh_.empty()) throw InputError("MeshSurface mesh has no triangles");
    if (smooth_normals_ && mesh_.vertex_normals.empty()) compute_vertex_normals(mesh_);
    build_grid();
}

void MeshSurface::build_grid() {
    const Aabb box = compute_bounds(mesh_);
    const Eigen::Vector3d extent = (box.max - box.min).cwiseMax(1e-9);
    cell_m_ = std::max({mean_triangle_extent(mesh_), std::cbrt(extent.prod() / kMaxCells), 1e-6});
    origin_ = box.min;
    dims_ = (extent / cell_m_).array().floor().cast<int>() + 1;
    std::vector<std::vector<std::uint32_t>> cells(static_cast<std::size_t>(dims_.prod()));
    std::size_t kept = 0;
    for (std::size_t i = 0; i < mesh_.triangles.size(); ++i) {
        // A triangle without area has no normal (triangle_normal is zero): it adds no surface
        // its neighbours do not have, but as the nearest (ties go to the lowest index) it
        // handed the crawler a zero normal on the edge it lies on.
        if (triangle_normal(mesh_, i).isZero()) continue;
        ++kept;
        const Eigen::Vector3i& t = mesh_.triangles[i];
        const Eigen::Vector3d& a = mesh_.vertices[t[0]];
        const Eigen::Vector3i lo =
            cell_of(a.cwiseMin(mesh_.vertices[t[1]]).cwiseMin(mesh_.vertices[t[2]]));
        const Eigen::Vector3i hi =
            cell_of(a.cwiseMax(mesh_.vertices[t[1]]).cwiseMax(mesh_.vertices[t[2]]));
        for (int z = lo.z(); z <= hi.z(); ++z)
            for (int y = lo.y(); y <= hi.y(); ++y)
                for (int x = lo.x(); x <= hi.x(); ++x)
                    cells[cell_index({x, y, z})].push_back(static_cast<std::uint32_t>(i));
    }
    if (kept == 0) throw InputError("MeshSurface mesh has no triangle with an area");
    cell_start_.assign(1, 0);
    for (const auto& cell : cells) {
        cell_triangles_.insert(cell_triangles_.end(), cell.begin(), cell.end());
        cell_start_.push_back(static_cast<std::uint32_t>(cell_triangles_.size()));
    }
}

Eigen::Vector3i MeshSurface::cell_of(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d f = ((p - origin_) / cell_m_).array().floor();
    const Eigen::Vector3d hi = (dims_ - Eigen::Vector3i::Ones()).cast<double>();
    return f.cwiseMax(Eigen::Vector3d::Zero()).cwiseMin(hi).cast<int>();
}

std::size_t MeshSurface::cell_index(const Eigen::Vector3i& c) const {
    const auto nx = static_cast<std::size_t>(dims_.x());
    const auto ny = static_cast<std::size_t>(dims_.y());
    return (static_cast<std::size_t>(c.z()) * ny + static_cast<std::size_t>(c.y())) * nx +
           static_cast<std::size_t>(c.x());
}

void MeshSurface::visit_cell(const Eigen::Vector3i& c, const Eigen::Vector3d& p, Best& best) const {
    if ((c.array() < 0).any() || (c.array() >= dims_.array()).any()) return;
    const std::size_t k = cell_index(c);
    for (std::uint32_t j = cell_start_[k]; j < cell_start_[k + 1]; ++j) {
        const std::uint32_t i = cell_triangles_[j];
        const Eigen::Vector3i& t = mesh_.triangles[i];
        const Eigen::Vector3d q = closest_point_on_triangle(
            p, mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]]);
        const double d2 = (q - p).squaredNorm();
        // Ties go to the lowest triangle index, so the result does not depend on visit order.
        if (d2 < best.distance2 || (d2 == best.distance2 && i < best.triangle)) {
            best = {d2, q, i};
        }
    }
}

void MeshSurface::visit_ring(const Eigen::Vector3i& centre, int ring, const Eigen::Vector3d& p,
                             Best& best) const {
    for (int dz = -ring; dz <= ring; ++dz) {
        for (int dy = -ring; dy <= ring; ++dy) {
            const bool face = std::abs(dz) == ring || std::abs(dy) == ring;
            // Inside the shell only the two x faces belong to this ring.
            const int step = face ? 1 : std::max(1, 2 * ring);
            for (int dx = -ring; dx <= ring; dx += step) {
                visit_cell(centre + Eigen::Vector3i(dx, dy, dz), p, best);
            }
        }
    }
}

Eigen::Vector3d MeshSurface::normal_at(std::size_t triangle, const Eigen::Vector3d& point) const {
    Eigen::Vector3d face = triangle_normal(mesh_, triangle);
    if (!smooth_normals_) return face;
    const Eigen::Vector3i& t = mesh_.triangles[triangle];
    const Eigen::Vector3d w =
        barycentric(point, mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]]);
    if (w.minCoeff() < -1e-6) return face;  // degenerate triangle
    const Eigen::Vector3d n = w[0] * mesh_.vertex_normals[t[0]] +
                              w[1] * mesh_.vertex_normals[t[1]] + w[2] * mesh_.vertex_normals[t[2]];
    return n.norm() > 1e-12 ? Eigen::Vector3d(n.normalized()) : face;
}

SurfacePoint MeshSurface::project(const Eigen::Vector3d& p_world) const {
    if (!p_world.allFinite()) throw InputError("MeshSurface::project: point is not finite");
    const Eigen::Vector3i c = cell_of(p_world);
    const Eigen::Vector3d lo = origin_ + c.cast<double>() * cell_m_;
    const Eigen::Vector3d hi = lo + Eigen::Vector3d::Constant(cell_m_);
    const double outside_m = (p_world - p_world.cwiseMax(lo).cwiseMin(hi)).norm();
    Best best;
    best.distance2 = std::numeric_limits<double>::infinity();
    best.triangle = std::numeric_limits<std::size_t>::max();
    // Cells of ring r + 1 and beyond are at least r · cell from cell c, hence at least
    // r · cell − outside_m from the point.
    const int max_ring = dims_.maxCoeff();
    for (int ring = 0; ring <= max_ring; ++ring) {
        visit_ring(c, ring, p_world, best);
        const double bound_m = ring * cell_m_ - outside_m;
        if (bound_m > 0.0 && best.distance2 <= bound_m * bound_m) break;
    }
    return {best.point, normal_at(best.triangle, best.point)};
}

}  // namespace scantling
