#pragma once
/// @file
/// Writes a simulator recording in the layout of io/recording.hpp. Frames (sweeps, depth
/// frames, images) are written as they come; the text streams (ground truth, stamps, poses,
/// IMU, VIO) are buffered and written by `finish`. Everything goes to a temporary folder beside
/// the recording's ("<name>.partial-<pid>-<n>"), which `commit` renames into place: a run that
/// fails, is interrupted or meets a full disk leaves no partial recording (the writer removes
/// the temporary folder when destroyed uncommitted; only SIGKILL or a power loss can leave it).
///
/// Determinism: the bytes written depend only on the data given (numbers as the shortest text
/// that reads back exactly), never on time or threads. Not thread-safe: one writer per run.

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <scantling/core/point_cloud.hpp>
#include <scantling/io/output_transaction.hpp>
#include <scantling/io/tum.hpp>
#include <scantling/sim/dvl.hpp>
#include <scantling/sim/imu.hpp>
#include <scantling/sim/multibeam_sonar.hpp>
#include <scantling/sim/pinhole_camera.hpp>
#include <scantling/sim/pressure.hpp>
#include <scantling/sim/range_finder.hpp>
#include <scantling/sim/sensor_reading.hpp>
#include <scantling/sim/uwb.hpp>
#include <scantling/sim/vio.hpp>
#include <scantling/sim/wheel_odometry.hpp>
#include <scantling/sim/world.hpp>
#include <scantling/sim/world_export.hpp>

namespace scantling::sim {

/// What summary.json says about the run (besides the per-stream counts the writer keeps).
struct RecordingSummary {
    std::string scenario;     ///< scenario name
    std::string description;  ///< scenario description
    std::string world;        ///< world type
    double duration_s = 0.0;  ///< simulated time
    double dt_s = 0.0;
    std::uint64_t seed = 0;
    /// Sensor names with their rates, e.g. {"spinning_lidar", 10.0}.
    std::vector<std::pair<std::string, double>> sensors;
};

/// Counts of what was written.
struct RecordingCounts {
    std::int64_t ground_truth = 0;
    std::int64_t lidar_sweeps = 0;
    std::int64_t lidar_points = 0;
    std::int64_t depth_frames = 0;
    std::int64_t images = 0;
    std::int64_t imu = 0;
    std::int64_t vio = 0;
    std::int64_t sonar_pings = 0;
    std::int64_t rosette_frames = 0;
    std::int64_t rosette_points = 0;
    std::int64_t stereo_frames = 0;
    std::int64_t stereo_points = 0;
    std::int64_t ranges = 0;
    std::int64_t uwb_rounds = 0;
    std::int64_t pressure = 0;
    std::int64_t dvl = 0;
    std::int64_t wheel_odometry = 0;
    std::int64_t barometer = 0;
};

/// Accepts a folder that holds only what a recording holds: at the top the files and folders
/// of io/recording.hpp, in the frame folders the frames (NNNNNN.bin, .ply, .png) and the files
/// the writer puts there, in world/ the files of write_world; no symlinks. Otherwise throws
/// FileError naming `directory` and the first foreign entry ("holds 'notes.txt', ...").
void check_replaceable_recording(const std::string& directory);

class RecordingWriter {
  public:
    /// Creates the temporary folder beside `directory` (and the parents of `directory`).
    /// Refuses (FileError naming it) a `directory` that exists and is not empty unless
    /// `overwrite`, and with `overwrite` one that is not a recording
    /// (check_replaceable_recording). Nothing is removed here: `commit` replaces the old
    /// recording once the new one is complete.
    RecordingWriter(std::string directory, bool overwrite);

    RecordingWriter(const RecordingWriter&) = delete;
    RecordingWriter& operator=(const RecordingWriter&) = delete;

    /// DIR/world/ (write_world).
    void write_world(const World& world, const WorldExportConfig& config);
    void add_ground_truth(double stamp_s, const Eigen::Isometry3d& T_world_body);
    /// Writes lidar/NNNNNN.bin (and .ply with rings and times when `with_ply`); `sweep` in
    /// the sensor frame, stamped at the sweep start; T_world_sensor at the sweep start.
    void add_lidar_sweep(const PointCloud& sweep, const Eigen::Isometry3d& T_world_sensor,
                         bool with_ply);
    void set_lidar_extrinsic(const Eigen::Isometry3d& T_body_sensor);
    /// Writes depth/NNNNNN.ply (organised, NaN where no return).
    void add_depth_frame(const PointCloud& frame, const Eigen::Isometry3d& T_world_sensor);
    /// The depth camera's mount (optical frame), written as depth/T_body_sensor.txt by finish
    /// when there are depth frames.
    void set_depth_extrinsic(const Eigen::Isometry3d& T_body_sensor);
    /// Writes images/NNNNNN.png; the sightings (PinholeCamera::sight_defects) go to
    /// images/visible_defects.csv (their ids) and images/defect_sightings.csv (their pixels,
    /// with this image's index and stamp).
    void add_image(const RgbImage& image, double stamp_s, const Eigen::Isometry3d& T_world_sensor,
                   std::span<const io::DefectSighting> sightings);
    /// The RGB camera's intrinsics and mount (optical frame), written as images/camera.json and
    /// images/T_body_sensor.txt by finish when there are images.
    void set_image_camera(const PinholeIntrinsics& intrinsics,
                          const Eigen::Isometry3d& T_body_sensor);
    void add_imu(const ImuSample& sample);
    void add_vio(const VioSample& sample);
    /// Writes sonar/NNNNNN.bin (float32, beam-major), sonar/NNNNNN.png (grey, columns = beams,
    /// rows = bins, scaled by the ping's peak) and, with the first ping, sonar/meta.json.
    void add_sonar(const SonarImage& image, const Eigen::Isometry3d& T_world_sensor);
    /// Writes rosette/NNNNNN.bin (as add_lidar_sweep, without rings).
    void add_rosette_frame(const PointCloud& frame, const Eigen::Isometry3d& T_world_sensor);
    /// Writes stereo/NNNNNN.ply (left optical frame).
    void add_stereo_frame(const PointCloud& frame, const Eigen::Isometry3d& T_world_sensor);
    void add_range(const RangeMeasurement& measurement);
    /// One row per anchor.
    void add_uwb(const UwbMeasurement& measurement);
    void add_pressure(const PressureSample& sample);
    void add_dvl(const DvlSample& sample);
    void add_wheel_odometry(const WheelOdometrySample& sample);
    void add_barometer(const BarometerSample& sample);
    /// Writes one sensor reading with the add_* of its type; a frame stream's mount is taken
    /// from its first frame (recording_writer_reading.cpp).
    void add(const SensorReading& reading);
    /// Writes the buffered streams and summary.json. Call once, last.
    void finish(const RecordingSummary& summary);
    /// Writes timing.json (wall time; kept out of summary.json so that recordings of the
    /// same scenario and seed are byte-identical).
    void write_timing(double wall_time_s, double real_time_factor) const;
    /// Moves the complete recording to `directory`, replacing what was there (checked again
    /// as in the constructor). Call after finish and write_timing; nothing is written after.
    void commit();

    const RecordingCounts& counts() const { return counts_; }
    /// The recording's folder (where it is once committed).
    const std::string& directory() const { return directory_; }
    /// Where the files are written until `commit`.
    const std::string& staging_directory() const { return staging_directory_; }

  private:
    struct Stream {
        std::vector<double> stamps_s;
        std::vector<Eigen::Isometry3d> poses;
    };
    std::string path(const std::string& relative) const;
    void write_stream(const std::string& folder, const Stream& stream) const;
    /// <folder>/T_body_sensor.txt, one KITTI line.
    void write_extrinsic(const std::string& folder, const Eigen::Isometry3d& T_body_sensor) const;
    std::string summary_json(const RecordingSummary& summary) const;
    void write_sonar_meta(const SonarImage& image) const;
    /// Streams and CSVs of add_sonar ... add_wheel_odometry (recording_writer_extra.cpp).
    void finish_extra() const;

    std::string directory_;
    io::OutputTransaction transaction_;
    std::string staging_directory_;  // after transaction_: staged by it
    RecordingCounts counts_;
    std::vector<io::StampedPose> ground_truth_;
    Stream lidar_;
    Stream depth_;
    Stream images_;
    bool has_lidar_extrinsic_ = false;
    Eigen::Isometry3d lidar_T_body_sensor_ = Eigen::Isometry3d::Identity();
    std::optional<Eigen::Isometry3d> depth_T_body_sensor_;
    std::string imu_csv_;
    std::string vio_csv_;
    std::string visible_defects_csv_;
    std::string defect_sightings_csv_;
    std::optional<PinholeIntrinsics> image_intrinsics_;
    Eigen::Isometry3d image_T_body_sensor_ = Eigen::Isometry3d::Identity();
    Stream sonar_;
    Stream rosette_;
    Stream stereo_;
    std::string range_csv_;  // the extra CSVs start with their header on the first row
    std::string uwb_csv_;
    std::string pressure_csv_;
    std::string dvl_csv_;
    std::string wheel_odometry_csv_;
    std::string barometer_csv_;
};

}  // namespace scantling::sim
