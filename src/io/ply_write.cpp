#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/ply.hpp>

#include "detail/binary_scalar.hpp"

namespace scantling::io {
namespace {

std::string header_text(const PointCloud& cloud, std::size_t num_faces) {
    std::string h = "ply\nformat binary_little_endian 1.0\ncomment written by scantling\n";
    h += "element vertex " + std::to_string(cloud.size()) + "\n";
    h += "property float x\nproperty float y\nproperty float z\n";
    if (cloud.has_normals()) h += "property float nx\nproperty float ny\nproperty float nz\n";
    if (cloud.has_intensities()) h += "property float intensity\n";
    if (cloud.has_rings()) h += "property ushort ring\n";
    if (cloud.has_times()) h += "property float time\n";
    if (cloud.has_colors()) h += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    if (num_faces > 0) {
        h += "element face " + std::to_string(num_faces) + "\n";
        h += "property list uchar int vertex_indices\n";
    }
    return h + "end_header\n";
}

void append_vertex(std::string& out, const PointCloud& cloud, std::size_t i) {
    for (int axis = 0; axis < 3; ++axis)
        detail::append_le(out, static_cast<float>(cloud.points[i][axis]));
    if (cloud.has_normals()) {
        for (int axis = 0; axis < 3; ++axis)
            detail::append_le(out, static_cast<float>(cloud.normals[i][axis]));
    }
    if (cloud.has_intensities()) detail::append_le(out, cloud.intensities[i]);
    if (cloud.has_rings()) detail::append_le(out, cloud.rings[i]);
    if (cloud.has_times()) detail::append_le(out, cloud.times_s[i]);
    if (cloud.has_colors()) out.append(reinterpret_cast<const char*>(cloud.colors[i].data()), 3);
}

void append_face(std::string& out, const Eigen::Vector3i& face) {
    detail::append_le(out, std::uint8_t{3});
    for (int k = 0; k < 3; ++k) detail::append_le(out, static_cast<std::int32_t>(face[k]));
}

void check_faces(std::span<const Eigen::Vector3i> faces, std::size_t num_vertices,
                 const std::string& path) {
    for (std::size_t f = 0; f < faces.size(); ++f) {
        for (int k = 0; k < 3; ++k) {
            if (faces[f][k] < 0 || static_cast<std::size_t>(faces[f][k]) >= num_vertices) {
                throw InputError("write_ply " + path + ": face " + std::to_string(f) +
                                 " has vertex index " + std::to_string(faces[f][k]) +
                                 ", expected [0, " + std::to_string(num_vertices) + ")");
            }
        }
    }
}

}  // namespace

void write_ply(const std::string& path, const PointCloud& cloud,
               std::span<const Eigen::Vector3i> faces) {
    check_consistent(cloud, "write_ply " + path);
    check_faces(faces, cloud.size(), path);
    std::string bytes = header_text(cloud, faces.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) append_vertex(bytes, cloud, i);
    for (const Eigen::Vector3i& face : faces) append_face(bytes, face);
    write_file_atomically(path, [&](std::ostream& out) {
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    });
}

}  // namespace scantling::io
