#pragma once
/// @file
/// Stanford PLY files: point clouds and triangle meshes.
///
/// Vertex properties mapped onto the cloud (others are skipped, lists included):
///   x y z → points; nx ny nz or normal_x normal_y normal_z → normals; intensity,
///   scalar_intensity (CloudCompare) or reflectance → intensities; red green blue → colors
///   (integers as 0..255, floating point as 0..1); rgb / rgba (packed integer) → colors;
///   ring → rings; time / t / timestamp → times_s (integer types: nanoseconds).
/// Faces: element `face` with a list property vertex_indices / vertex_index (any integer
/// types); polygons with n > 3 corners are split into a fan (0, k, k + 1).
/// Elements other than vertex and face are skipped.

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include <scantling/core/point_cloud.hpp>

namespace scantling::io {

// Thread-safety: the functions keep no shared state; concurrent calls on different files are
// safe. Writers go through AtomicFileWriter, so a reader never sees a partial file.

struct PlyData {
    PointCloud cloud;                    ///< the vertices
    std::vector<Eigen::Vector3i> faces;  ///< triangles indexing `cloud.points`
};

/// Reads format ascii, binary_little_endian and binary_big_endian with scalar types char
/// uchar short ushort int uint float double (and int8 uint8 int16 uint16 int32 uint32
/// float32 float64). Throws FileError (missing, unreadable, directory) or ParseError naming
/// the file and the line (header, ascii) or byte offset (binary): bad magic, unknown format,
/// truncated data, too few / too many values, a face index out of range or a polygon with
/// fewer than 3 corners, data left over after the last element (counts disagreeing), no
/// vertex element or no x y z.
/// Hostile headers: the rows all elements declare, times the least bytes a row takes (binary:
/// its scalars and list counts; ascii: two characters a value), are summed with overflow checks
/// and must fit in the data before anything is allocated (otherwise the data is walked without
/// storing it to report where it ends); a list length must fit in the data left. Also refused:
/// an element or property declared twice, two properties feeding one member (nx and
/// normal_x), an ascii integer outside its declared type ("uchar" 300).
/// Cost: one read of the file plus O(values).
PlyData read_ply(const std::string& path);

/// Writes binary little endian: x y z as float (rounded to float32), then the present fields
/// nx ny nz, intensity (float), ring (ushort), time (float), red green blue (uchar); faces as
/// `list uchar int vertex_indices`. Covariances and `stamp_s` are not stored. Atomic.
/// Throws InputError for an inconsistent cloud or a face index outside [0, size), FileError
/// when the file cannot be written.
void write_ply(const std::string& path, const PointCloud& cloud,
               std::span<const Eigen::Vector3i> faces = {});

}  // namespace scantling::io
