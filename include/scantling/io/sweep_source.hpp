#pragma once
/// @file
/// A sequence of LiDAR sweeps read from disk, whatever produced it, so that the odometry runs
/// the same way on a simulator recording, a KITTI sequence and a folder of scans:
///
///   - a simulator recording (a folder with groundtruth.tum and lidar/): sweeps in the sensor
///     frame, stamps from lidar/times.txt, ground truth T_world_sensor from lidar/poses_gt.txt;
///   - a KITTI odometry sequence folder (velodyne/NNNNNN.bin; stamps from times.txt beside it
///     when present, else `period_s` apart);
///   - a folder of clouds (*.pcd, *.ply or *.bin, one format, read in file-name order, stamps
///     `period_s` apart, or the cloud's own stamp when every file has one).
///
/// Thread-safety: a SweepSource is immutable after opening; read() is const and may run
/// concurrently with other reads.
#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <scantling/core/point_cloud.hpp>

namespace scantling::io {

enum class SweepSourceKind { kRecording, kKittiSequence, kCloudFolder };

/// "recording", "kitti", "folder".
const char* to_string(SweepSourceKind kind);

struct SweepSourceOptions {
    /// Time between sweeps when the source has no stamps of its own, seconds (> 0).
    double period_s = 0.1;
};

class SweepSource {
  public:
    virtual ~SweepSource() = default;
    virtual SweepSourceKind kind() const = 0;
    /// The path it was opened from.
    virtual const std::string& path() const = 0;
    virtual std::size_t size() const = 0;
    /// Sweep i in the sensor frame, with `stamp_s` set. Throws InputError for i out of range and
    /// FileError / ParseError (naming the file) for a missing or malformed file.
    virtual PointCloud read(std::size_t i) const = 0;
    /// Stamp of sweep i, seconds (InputError when out of range).
    virtual double stamp_s(std::size_t i) const = 0;
    /// File of sweep i (for messages).
    virtual std::string file_of(std::size_t i) const = 0;
    /// Ground-truth T_world_sensor per sweep when the source has it (recordings), else empty.
    virtual std::optional<std::vector<Eigen::Isometry3d>> ground_truth() const = 0;
};

/// Opens `path` as a recording (it has groundtruth.tum), a KITTI sequence (it has velodyne/) or a
/// folder of clouds, in that order. Throws FileError when the path does not exist, is not a
/// folder, or holds no sweeps ("no .pcd, .ply or .bin files"), or mixes cloud formats.
std::unique_ptr<SweepSource> open_sweep_source(const std::string& path,
                                               const SweepSourceOptions& options = {});

}  // namespace scantling::io
