#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/io/mesh_io.hpp>
#include <scantling/io/ply.hpp>

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "detail/binary_scalar.hpp"

namespace scantling::io {
namespace {

void check_readable(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw FileError(path, "cannot read: the path is a directory");
    errno = 0;
    std::ifstream probe(path, std::ios::binary);
    if (!probe) {
        const int error_number = errno ? errno : ENOENT;
        throw FileError(path, "cannot open for reading: " +
                                  std::error_code(error_number, std::generic_category()).message());
    }
}

void append_mesh(const aiMesh& mesh, const aiMatrix4x4& T, TriangleMesh& out) {
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) return;
    const int base = static_cast<int>(out.vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiVector3D p = T * mesh.mVertices[v];
        out.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices != 3) continue;  // points and lines survive triangulation
        out.triangles.emplace_back(base + static_cast<int>(face.mIndices[0]),
                                   base + static_cast<int>(face.mIndices[1]),
                                   base + static_cast<int>(face.mIndices[2]));
    }
}

void append_node(const aiScene& scene, const aiNode& node, const aiMatrix4x4& T_world_parent,
                 TriangleMesh& out) {
    const aiMatrix4x4 T_world_node = T_world_parent * node.mTransformation;
    for (unsigned m = 0; m < node.mNumMeshes; ++m) {
        append_mesh(*scene.mMeshes[node.mMeshes[m]], T_world_node, out);
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) {
        append_node(scene, *node.mChildren[c], T_world_node, out);
    }
}

TriangleMesh read_with_assimp(const std::string& path) {
    Assimp::Importer importer;
    // Without per-corner attributes, JoinIdenticalVertices merges corners by position alone.
    importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                                aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                    aiComponent_COLORS | aiComponent_TEXCOORDS);
    const aiScene* scene = importer.ReadFile(
        path, aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
    if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
        throw ParseError(path, {},
                         std::string("assimp cannot read the mesh: ") + importer.GetErrorString());
    }
    TriangleMesh mesh;
    append_node(*scene, *scene->mRootNode, aiMatrix4x4(), mesh);
    return mesh;
}

TriangleMesh read_with_ply(const std::string& path) {
    PlyData data = read_ply(path);
    TriangleMesh mesh;
    mesh.vertices = std::move(data.cloud.points);
    mesh.vertex_normals = std::move(data.cloud.normals);
    mesh.triangles = std::move(data.faces);
    return mesh;
}

void check_writable(const TriangleMesh& mesh, const std::string& path) {
    const auto n = static_cast<long long>(mesh.vertices.size());
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        const Eigen::Vector3i& t = mesh.triangles[f];
        if (t.minCoeff() < 0 || t.maxCoeff() >= n) {
            throw InputError("write_mesh " + path + ": triangle " + std::to_string(f) +
                             " has a vertex index outside [0, " + std::to_string(n) + ")");
        }
    }
    if (!mesh.vertex_normals.empty() && mesh.vertex_normals.size() != mesh.vertices.size()) {
        throw InputError("write_mesh " + path + ": " + std::to_string(mesh.vertex_normals.size()) +
                         " vertex normals for " + std::to_string(n) + " vertices");
    }
}

void append_vector(std::string& out, const Eigen::Vector3d& v) {
    for (int k = 0; k < 3; ++k) detail::append_le(out, static_cast<float>(v[k]));
}

void write_stl(const std::string& path, const TriangleMesh& mesh) {
    // 80-byte header that must not start with "solid" (readers would take it for ascii).
    std::string bytes = "binary STL written by scantling";
    bytes.resize(80, ' ');
    detail::append_le(bytes, static_cast<std::uint32_t>(mesh.triangles.size()));
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3d& a = mesh.vertices[t[0]];
        const Eigen::Vector3d& b = mesh.vertices[t[1]];
        const Eigen::Vector3d& c = mesh.vertices[t[2]];
        append_vector(bytes, (b - a).cross(c - a).stableNormalized());
        for (const Eigen::Vector3d* v : {&a, &b, &c}) append_vector(bytes, *v);
        detail::append_le(bytes, std::uint16_t{0});
    }
    write_file_atomically(path, [&](std::ostream& out) {
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    });
}

}  // namespace

TriangleMesh read_mesh(const std::string& path) {
    check_readable(path);
    TriangleMesh mesh =
        lower_extension(path) == ".ply" ? read_with_ply(path) : read_with_assimp(path);
    if (mesh.triangles.empty()) {
        throw ParseError(
            path, {},
            "the file holds no triangle (" + std::to_string(mesh.vertices.size()) + " vertices)");
    }
    return mesh;
}

void write_mesh(const std::string& path, const TriangleMesh& mesh) {
    const std::string ext = lower_extension(path);
    if (ext != ".ply" && ext != ".stl") {
        throw FileError(path, "unsupported mesh extension '" + ext + "', expected .ply or .stl");
    }
    if (mesh.empty()) throw InputError("write_mesh " + path + ": the mesh has no triangle");
    check_writable(mesh, path);
    if (ext == ".stl") return write_stl(path, mesh);
    PointCloud cloud;
    cloud.points = mesh.vertices;
    cloud.normals = mesh.vertex_normals;
    write_ply(path, cloud, mesh.triangles);
}

}  // namespace scantling::io
