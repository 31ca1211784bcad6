#include <scantling/core/error.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/io/kitti.hpp>
#include <scantling/io/pcd.hpp>
#include <scantling/io/ply.hpp>

namespace scantling::io {

CloudFormat cloud_format_from_path(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".pcd") return CloudFormat::kPcd;
    if (ext == ".ply") return CloudFormat::kPly;
    if (ext == ".bin") return CloudFormat::kKittiBin;
    throw FileError(path, "unknown point-cloud extension '" + ext +
                              "', supported: .pcd, .ply, .bin (KITTI velodyne)");
}

PointCloud read_cloud(const std::string& path) {
    switch (cloud_format_from_path(path)) {
        case CloudFormat::kPcd:
            return read_pcd(path);
        case CloudFormat::kPly:
            return read_ply(path).cloud;
        case CloudFormat::kKittiBin:
            return read_kitti_bin(path);
    }
    return {};
}

void write_cloud(const std::string& path, const PointCloud& cloud,
                 const CloudWriteOptions& options) {
    switch (cloud_format_from_path(path)) {
        case CloudFormat::kPcd:
            return write_pcd(path, cloud,
                             options.binary ? PcdEncoding::kBinary : PcdEncoding::kAscii);
        case CloudFormat::kPly:
            return write_ply(path, cloud);
        case CloudFormat::kKittiBin:
            return write_kitti_bin(path, cloud);
    }
}

}  // namespace scantling::io
