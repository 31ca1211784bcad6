#pragma once
/// @file Point-cloud files by extension: .pcd, .ply, .bin (KITTI velodyne).

#include <string>

#include <scantling/core/point_cloud.hpp>

namespace scantling::io {

enum class CloudFormat { kPcd, kPly, kKittiBin };

/// Format from the file extension (case-insensitive); throws FileError for an unknown one,
/// listing the supported extensions.
CloudFormat cloud_format_from_path(const std::string& path);

/// Reads any supported cloud file. Throws FileError (missing/unreadable) or ParseError
/// (malformed: names file, byte offset or line, and what was expected).
PointCloud read_cloud(const std::string& path);

struct CloudWriteOptions {
    bool binary = true;  ///< PCD: binary or ascii (PLY is always written binary little endian)
};

/// Writes atomically (temporary file + rename: no partial file is ever left behind).
/// Fields the format cannot hold are dropped (KITTI .bin keeps x y z intensity only).
void write_cloud(const std::string& path, const PointCloud& cloud,
                 const CloudWriteOptions& options = {});

}  // namespace scantling::io
