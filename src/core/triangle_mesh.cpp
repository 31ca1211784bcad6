#include <scantling/core/error.hpp>
#include <scantling/core/triangle_mesh.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace scantling {
namespace {

struct CellKey {
    std::int64_t x;
    std::int64_t y;
    std::int64_t z;
    bool operator==(const CellKey&) const = default;
};

struct CellKeyHash {
    std::size_t operator()(const CellKey& k) const {
        // Large odd multipliers spread neighbouring cells over the buckets.
        const auto h = static_cast<std::uint64_t>(k.x) * 0x9E3779B97F4A7C15ULL ^
                       static_cast<std::uint64_t>(k.y) * 0xC2B2AE3D27D4EB4FULL ^
                       static_cast<std::uint64_t>(k.z) * 0x165667B19E3779F9ULL;
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};

// The grid only finds neighbours correctly when the cell is >= tolerance; a larger cell just
// costs more candidates. Keys must fit in int64, so huge coordinates force a larger cell.
double weld_cell_size(const TriangleMesh& mesh, double tolerance_m) {
    double max_abs = 0.0;
    for (const auto& v : mesh.vertices) max_abs = std::max(max_abs, v.cwiseAbs().maxCoeff());
    constexpr double kMaxCellsPerCoordinate = 1e15;
    return std::max({tolerance_m, max_abs / kMaxCellsPerCoordinate, 1e-300});
}

CellKey cell_of(const Eigen::Vector3d& p, double cell_m) {
    return {static_cast<std::int64_t>(std::floor(p.x() / cell_m)),
            static_cast<std::int64_t>(std::floor(p.y() / cell_m)),
            static_cast<std::int64_t>(std::floor(p.z() / cell_m))};
}

class WeldGrid {
  public:
    WeldGrid(double cell_m, double tolerance_m) : cell_m_(cell_m), tolerance_m_(tolerance_m) {}

    /// Index among `kept` of a kept vertex within tolerance of p, or -1.
    int find(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& kept) const {
        const CellKey c = cell_of(p, cell_m_);
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
            for (std::int64_t dy = -1; dy <= 1; ++dy) {
                for (std::int64_t dz = -1; dz <= 1; ++dz) {
                    const auto it = cells_.find({c.x + dx, c.y + dy, c.z + dz});
                    if (it == cells_.end()) continue;
                    for (int k : it->second) {
                        if ((kept[k] - p).norm() <= tolerance_m_) return k;
                    }
                }
            }
        }
        return -1;
    }

    void insert(const Eigen::Vector3d& p, int index) {
        cells_[cell_of(p, cell_m_)].push_back(index);
    }

  private:
    double cell_m_;
    double tolerance_m_;
    std::unordered_map<CellKey, std::vector<int>, CellKeyHash> cells_;
};

bool is_degenerate(const Eigen::Vector3i& tri) {
    return tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2];
}

}  // namespace

void check_valid(const TriangleMesh& mesh, std::string_view what) {
    const auto n = static_cast<long long>(mesh.vertices.size());
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        if (!mesh.vertices[i].allFinite()) {
            throw InputError(fmt::format("{}: vertex {} is not finite", what, i));
        }
    }
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (int corner = 0; corner < 3; ++corner) {
            const int index = mesh.triangles[t][corner];
            if (index < 0 || index >= n) {
                throw InputError(
                    fmt::format("{}: triangle {} corner {} has vertex index {}, expected 0..{}",
                                what, t, corner, index, n - 1));
            }
        }
    }
    if (!mesh.vertex_normals.empty() && mesh.vertex_normals.size() != mesh.vertices.size()) {
        throw InputError(fmt::format("{}: {} vertex_normals for {} vertices", what,
                                     mesh.vertex_normals.size(), mesh.vertices.size()));
    }
}

Aabb compute_bounds(const TriangleMesh& mesh) { return compute_bounds(std::span(mesh.vertices)); }

Eigen::Vector3d triangle_normal(const TriangleMesh& mesh, std::size_t i) {
    const Eigen::Vector3i& tri = mesh.triangles[i];
    const Eigen::Vector3d& a = mesh.vertices[tri[0]];
    const Eigen::Vector3d cross = (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a);
    const double norm = cross.norm();
    return norm > 0.0 ? Eigen::Vector3d(cross / norm) : Eigen::Vector3d::Zero();
}

double triangle_area(const TriangleMesh& mesh, std::size_t i) {
    const Eigen::Vector3i& tri = mesh.triangles[i];
    const Eigen::Vector3d& a = mesh.vertices[tri[0]];
    return 0.5 * (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a).norm();
}

double surface_area(const TriangleMesh& mesh) {
    double area = 0.0;
    for (std::size_t i = 0; i < mesh.num_triangles(); ++i) area += triangle_area(mesh, i);
    return area;
}

void compute_vertex_normals(TriangleMesh& mesh) {
    mesh.vertex_normals.assign(mesh.vertices.size(), Eigen::Vector3d::Zero());
    for (const auto& tri : mesh.triangles) {
        const Eigen::Vector3d& a = mesh.vertices[tri[0]];
        // The unnormalised cross product is 2·area·normal: area weighting for free.
        const Eigen::Vector3d cross = (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a);
        for (int corner = 0; corner < 3; ++corner) mesh.vertex_normals[tri[corner]] += cross;
    }
    for (auto& n : mesh.vertex_normals) {
        const double norm = n.norm();
        if (norm > 0.0) n /= norm;
    }
}

void transform_in_place(TriangleMesh& mesh, const Eigen::Isometry3d& T_to_from) {
    const Eigen::Matrix3d R = T_to_from.linear();
    for (auto& v : mesh.vertices) v = T_to_from * v;
    for (auto& n : mesh.vertex_normals) n = R * n;
}

void append(TriangleMesh& dst, const TriangleMesh& other) {
    const bool dst_was_empty = dst.vertices.empty();
    if (!dst_was_empty && dst.vertex_normals.empty() != other.vertex_normals.empty()) {
        throw InputError("append: vertex_normals present in one mesh only");
    }
    const int offset = static_cast<int>(dst.vertices.size());
    dst.vertices.insert(dst.vertices.end(), other.vertices.begin(), other.vertices.end());
    dst.vertex_normals.insert(dst.vertex_normals.end(), other.vertex_normals.begin(),
                              other.vertex_normals.end());
    dst.triangles.reserve(dst.triangles.size() + other.triangles.size());
    for (const auto& tri : other.triangles) {
        dst.triangles.emplace_back(tri.array() + offset);
    }
}

void weld_vertices(TriangleMesh& mesh, double tolerance_m) {
    check_valid(mesh, "weld_vertices");
    if (!std::isfinite(tolerance_m) || tolerance_m < 0.0) {
        throw InputError(
            fmt::format("weld_vertices: tolerance_m = {}, expected finite >= 0", tolerance_m));
    }
    WeldGrid grid(weld_cell_size(mesh, tolerance_m), tolerance_m);
    std::vector<Eigen::Vector3d> kept;
    std::vector<int> remap(mesh.vertices.size());
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const int found = grid.find(mesh.vertices[i], kept);
        if (found >= 0) {
            remap[i] = found;
            continue;
        }
        remap[i] = static_cast<int>(kept.size());
        grid.insert(mesh.vertices[i], remap[i]);
        kept.push_back(mesh.vertices[i]);
    }
    std::vector<Eigen::Vector3i> triangles;
    triangles.reserve(mesh.triangles.size());
    for (const auto& tri : mesh.triangles) {
        const Eigen::Vector3i welded(remap[tri[0]], remap[tri[1]], remap[tri[2]]);
        if (!is_degenerate(welded)) triangles.push_back(welded);
    }
    const bool had_normals = !mesh.vertex_normals.empty();
    mesh.vertices = std::move(kept);
    mesh.triangles = std::move(triangles);
    mesh.vertex_normals.clear();
    if (had_normals) compute_vertex_normals(mesh);
}

}  // namespace scantling
