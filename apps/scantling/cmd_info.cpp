#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/core/triangle_mesh.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/io/mesh_io.hpp>
#include <scantling/io/ply.hpp>

#include "scantling/commands.hpp"

namespace scantling::app {
namespace {

std::string bounds_line(const Aabb& box) {
    if (box.empty()) return "bounds: empty\n";
    // Adding +0.0 turns -0.0 into 0.0, so a keel at z = 0 does not print as "-0.000000".
    const Eigen::Vector3d lo = box.min.array() + 0.0, hi = box.max.array() + 0.0;
    return fmt::format("bounds: {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f}\n", lo.x(), lo.y(),
                       lo.z(), hi.x(), hi.y(), hi.z());
}

struct FiniteBounds {
    Aabb box;
    std::size_t non_finite = 0;
};

// Organised clouds carry NaN placeholders and a mesh file may hold NaN/inf vertices: keep them
// out of the bounds and count them, the same way for clouds and meshes.
FiniteBounds finite_bounds(const std::vector<Eigen::Vector3d>& points) {
    FiniteBounds bounds;
    for (const Eigen::Vector3d& p : points) {
        if (p.allFinite()) {
            bounds.box.extend(p);
        } else {
            ++bounds.non_finite;
        }
    }
    return bounds;
}

std::string cloud_report(const PointCloud& cloud) {
    const FiniteBounds bounds = finite_bounds(cloud.points);
    std::string text = fmt::format("points: {}\n", cloud.size());
    text += fmt::format("fields: {}\n", fmt::join(field_names(cloud), " "));
    text += bounds_line(bounds.box);
    if (bounds.non_finite > 0) text += fmt::format("non_finite: {}\n", bounds.non_finite);
    return text;
}

bool has_finite_corners(const TriangleMesh& mesh, std::size_t t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    return mesh.vertices[tri[0]].allFinite() && mesh.vertices[tri[1]].allFinite() &&
           mesh.vertices[tri[2]].allFinite();
}

/// Triangles with a non-finite corner are left out of the area and counted.
std::string mesh_report(const TriangleMesh& mesh) {
    const FiniteBounds bounds = finite_bounds(mesh.vertices);
    double area_m2 = 0.0;
    std::size_t broken = 0;
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
        if (has_finite_corners(mesh, t)) {
            area_m2 += triangle_area(mesh, t);
        } else {
            ++broken;
        }
    }
    std::string text =
        fmt::format("vertices: {}\ntriangles: {}\n", mesh.num_vertices(), mesh.num_triangles()) +
        bounds_line(bounds.box) + fmt::format("area_m2: {:.6f}\n", area_m2);
    if (bounds.non_finite > 0) {
        text +=
            fmt::format("non_finite: {}\nnon_finite_triangles: {}\n", bounds.non_finite, broken);
    }
    return text;
}

/// A PLY file is a mesh when it has faces, a cloud otherwise.
std::string ply_report(const std::string& path) {
    io::PlyData ply = io::read_ply(path);
    if (ply.faces.empty()) return cloud_report(ply.cloud);
    TriangleMesh mesh;
    mesh.vertices = std::move(ply.cloud.points);
    mesh.triangles = std::move(ply.faces);
    return mesh_report(mesh);
}

}  // namespace

void run_info(const InfoOptions& options, std::ostream& out) {
    const auto start = std::chrono::steady_clock::now();
    const std::string ext = io::lower_extension(options.input);
    std::string report;
    if (ext == ".obj" || ext == ".stl") {
        report = mesh_report(io::read_mesh(options.input));
    } else if (ext == ".ply") {
        report = ply_report(options.input);
    } else if (ext == ".pcd" || ext == ".bin") {
        report = cloud_report(io::read_cloud(options.input));
    } else {
        throw FileError(options.input,
                        "unknown extension '" + ext + "', expected .pcd, .ply, .bin, .obj or .stl");
    }
    spdlog::debug(
        "read {} in {:.1f} ms", options.input,
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    out << report;
}

}  // namespace scantling::app
