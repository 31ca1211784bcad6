#pragma once
/// @file
/// Triangle-mesh files (worlds, CAD hulls, tanks).

#include <string>

#include <scantling/core/triangle_mesh.hpp>

namespace scantling::io {

/// Reads a mesh in metres as stored in the file (no unit conversion).
///   .ply (any case): our own reader (read_ply); vertex normals are kept when present.
///   anything else (.obj, .stl ascii and binary, and the other formats assimp knows): assimp
///   with aiProcess_Triangulate and aiProcess_JoinIdenticalVertices, normals/colours/texture
///   coordinates removed first so that corners with equal positions are merged (STL stores
///   each facet's corners separately). The triangle count is preserved, but vertex counts
///   differ from the file's; `vertex_normals` stays empty (see compute_vertex_normals()).
///   All meshes of the scene are concatenated with their node transforms applied; points and
///   lines are dropped.
/// Vertices are returned as stored, NaN/inf included, as the cloud readers return points
/// (`scantling info` counts them; check_valid() refuses them before a mesh is used).
/// Throws FileError (missing, unreadable, directory) or ParseError naming the file with
/// assimp's message (unknown or malformed content), or when the file holds no triangle.
/// Thread-safe (each call uses its own importer).
TriangleMesh read_mesh(const std::string& path);

/// Writes by extension (case-insensitive): .ply → binary little endian PLY (vertices as float,
/// normals when present); .stl → binary STL (facet normals computed, vertices as float).
/// Atomic. Throws FileError for another extension or an unwritable path, InputError for a
/// mesh without triangles (read_mesh would reject the file), a triangle index outside
/// [0, num_vertices) or normals not one per vertex.
void write_mesh(const std::string& path, const TriangleMesh& mesh);

}  // namespace scantling::io
