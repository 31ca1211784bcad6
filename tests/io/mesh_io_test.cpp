#include <gtest/gtest.h>

#include <scantling/core/error.hpp>
#include <scantling/io/mesh_io.hpp>

#include "test_files.hpp"

namespace scantling::io {
namespace {

using test::TempDir;

/// A tetrahedron with float-exact vertices, outward counter-clockwise triangles.
TriangleMesh tetrahedron() {
    TriangleMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1.5, 0, 0}, {0, 2.25, 0}, {0, 0, -0.75}};
    mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return mesh;
}

/// Same triangles, possibly re-indexed: compares corner positions in order.
void expect_same_geometry(const TriangleMesh& expected, const TriangleMesh& actual) {
    ASSERT_EQ(expected.num_triangles(), actual.num_triangles());
    for (std::size_t t = 0; t < expected.num_triangles(); ++t) {
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(expected.vertices[expected.triangles[t][k]],
                      actual.vertices[actual.triangles[t][k]])
                << "triangle " << t << " corner " << k;
        }
    }
}

TEST(MeshIo, RoundTripsPlyMeshWithNormalsBitExact) {
    TempDir dir;
    TriangleMesh mesh = tetrahedron();
    mesh.vertex_normals = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
    write_mesh(dir.file("tet.PLY"), mesh);
    const TriangleMesh back = read_mesh(dir.file("tet.PLY"));
    EXPECT_EQ(back.vertices, mesh.vertices);
    EXPECT_EQ(back.triangles, mesh.triangles);
    EXPECT_EQ(back.vertex_normals, mesh.vertex_normals);
}

TEST(MeshIo, WritesBinaryStlThatAssimpReadsBackWelded) {
    TempDir dir;
    const TriangleMesh mesh = tetrahedron();
    write_mesh(dir.file("tet.stl"), mesh);
    EXPECT_EQ(std::filesystem::file_size(dir.file("tet.stl")), 84u + 4u * 50u);
    const TriangleMesh back = read_mesh(dir.file("tet.stl"));
    EXPECT_EQ(back.num_vertices(), 4u);  // 12 facet corners merged by position
    expect_same_geometry(mesh, back);
    EXPECT_TRUE(back.vertex_normals.empty());
}

TEST(MeshIo, ReadsObjPolygonsOfSeveralObjectsAsTriangles) {
    TempDir dir;
    test::write_bytes(dir.file("quads.obj"),
                      "# two unit squares\no first\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                      "f 1 2 3 4\no second\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 5 6 7 8\n");
    const TriangleMesh mesh = read_mesh(dir.file("quads.obj"));
    EXPECT_EQ(mesh.num_triangles(), 4u);
    EXPECT_EQ(mesh.num_vertices(), 8u);
    const Aabb box = compute_bounds(std::span<const Eigen::Vector3d>(mesh.vertices));
    EXPECT_EQ(box.min, Eigen::Vector3d(0, 0, 0));
    EXPECT_EQ(box.max, Eigen::Vector3d(1, 1, 1));
}

TEST(MeshIo, ReadsAsciiStl) {
    TempDir dir;
    test::write_bytes(dir.file("one.stl"),
                      "solid one\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
                      "   vertex 2 0 0\n   vertex 0 3 0\n  endloop\n endfacet\nendsolid one\n");
    const TriangleMesh mesh = read_mesh(dir.file("one.stl"));
    ASSERT_EQ(mesh.num_triangles(), 1u);
    EXPECT_EQ(mesh.vertices[mesh.triangles[0][1]], Eigen::Vector3d(2, 0, 0));
    EXPECT_EQ(mesh.vertices[mesh.triangles[0][2]], Eigen::Vector3d(0, 3, 0));
}

TEST(MeshIo, AppliesNodeTransformsOfTheScene) {
    TempDir dir;
    // Collada: one triangle instanced by a node translated by (10, 20, 30).
    test::write_bytes(dir.file("moved.dae"), R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Y_UP</up_axis></asset>
  <library_geometries><geometry id="tri"><mesh>
    <source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
      <technique_common><accessor source="#pa" count="3" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s">
    <node id="n"><matrix>1 0 0 10 0 1 0 20 0 0 1 30 0 0 0 1</matrix>
      <instance_geometry url="#tri"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)");
    const TriangleMesh mesh = read_mesh(dir.file("moved.dae"));
    ASSERT_EQ(mesh.num_triangles(), 1u);
    const Aabb box = compute_bounds(std::span<const Eigen::Vector3d>(mesh.vertices));
    EXPECT_EQ(box.min, Eigen::Vector3d(10, 20, 30));
    EXPECT_EQ(box.max, Eigen::Vector3d(11, 21, 30));
}

TEST(MeshIo, WriterRejectsBadIndicesAndUnknownExtensionsLeavingNothing) {
    TempDir dir;
    TriangleMesh mesh = tetrahedron();
    EXPECT_THROW(write_mesh(dir.file("tet.obj"), mesh), FileError);
    mesh.triangles.push_back({0, 1, 4});
    EXPECT_THROW(write_mesh(dir.file("tet.ply"), mesh), InputError);
    EXPECT_THROW(write_mesh(dir.file("tet.stl"), mesh), InputError);
    EXPECT_THROW(write_mesh(dir.file("empty.ply"), TriangleMesh{}), InputError);
    EXPECT_TRUE(dir.list().empty());
}

}  // namespace
}  // namespace scantling::io
