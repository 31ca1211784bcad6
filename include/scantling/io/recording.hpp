#pragma once
/// @file
/// Reader of simulator recordings (`scantling sim ... --out DIR`, issue 3 item 4). It knows
/// only the file layout, so algorithms get the same types from a recording as from live data:
///
///   DIR/groundtruth.tum          body pose T_world_body at every clock step (TUM)
///   DIR/lidar/NNNNNN.bin         sweep i, KITTI float32 x y z intensity, SENSOR frame
///   DIR/lidar/NNNNNN.ply         (optional) the same sweep with ring and time per point
///   DIR/lidar/times.txt          sweep start stamp, seconds, one line per sweep
///   DIR/lidar/poses_gt.txt       T_world_sensor at the sweep start, KITTI 3×4, one per sweep
///   DIR/lidar/T_body_sensor.txt  mounting extrinsic, one KITTI 3×4 line
///   DIR/depth/NNNNNN.ply, times.txt, poses_gt.txt      organised ToF frames (NaN = no return),
///                                optical frame; poses_gt is T_world_sensor at the frame stamp
///   DIR/depth/T_body_sensor.txt  depth camera mount, one KITTI 3×4 line (absent in recordings
///                                written before it existed)
///   DIR/images/NNNNNN.png, times.txt, poses_gt.txt     RGB images
///   DIR/images/visible_defects.csv  index,stamp_s,defect_ids (ids in view, ';'-separated)
///   DIR/images/defect_sightings.csv index,stamp_s,defect_id,u_px,v_px,radius_px: where each
///                                visible defect's centre is in the image (a tag detector's output)
///   DIR/images/camera.json, T_body_sensor.txt   the RGB camera's pinhole intrinsics and mount
///                                (both absent in recordings written before them)
///   DIR/rosette/NNNNNN.bin, times.txt, poses_gt.txt    rosette LiDAR frames, as lidar/
///   DIR/stereo/NNNNNN.ply, times.txt, poses_gt.txt     sparse stereo points, optical frame
///   DIR/sonar/NNNNNN.bin         multibeam ping, float32 intensity, beam-major (beam·bins+bin)
///   DIR/sonar/NNNNNN.png         the same ping as a grey image (columns beams, rows bins)
///   DIR/sonar/meta.json          num_beams, num_bins, bearings_rad, ranges_m; times, poses
///   DIR/range.csv                stamp_s,valid,range_m
///   DIR/uwb.csv                  stamp_s,anchor_id,range_m,valid,los (one row per anchor)
///   DIR/pressure.csv             stamp_s,pressure_pa,depth_m
///   DIR/dvl.csv                  stamp_s,valid,vx,vy,vz,altitude_m (body frame)
///   DIR/wheel_odometry.csv       stamp_s,forward_speed_mps,yaw_rate_radps,slipping
///   DIR/imu.csv                  stamp_s,ax,ay,az,wx,wy,wz (sensor frame)
///   DIR/vio.csv                  stamp_s,valid,x,y,z,qx,qy,qz,qw,vx,vy,vz,var_x,...,var_rz,
///                                feature_quality (the last column is absent in old recordings)
///   DIR/world/{map.ply, mesh.ply, metadata.json}  (+ map.ply.fpfh, cached by `scantling localize`)
///   DIR/summary.json             what was simulated (deterministic)
///   DIR/timing.json              wall time of the run (the only non-deterministic file)
///
/// Thread-safety: a Recording is immutable after open_recording; reads are const and may run
/// concurrently. Cost: open reads the text files (poses, stamps, CSVs); sweeps are read lazily.

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <scantling/core/pinhole_intrinsics.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/io/tum.hpp>

namespace scantling::io {

/// File and folder names of the layout (shared with the simulator's writer).
namespace recording_layout {
inline constexpr const char* kGroundTruth = "groundtruth.tum";
inline constexpr const char* kLidarDir = "lidar";
inline constexpr const char* kDepthDir = "depth";
inline constexpr const char* kImagesDir = "images";
inline constexpr const char* kRosetteDir = "rosette";
inline constexpr const char* kStereoDir = "stereo";
inline constexpr const char* kSonarDir = "sonar";
inline constexpr const char* kSonarMeta = "meta.json";
inline constexpr const char* kRange = "range.csv";
inline constexpr const char* kUwb = "uwb.csv";
inline constexpr const char* kPressure = "pressure.csv";
inline constexpr const char* kDvl = "dvl.csv";
inline constexpr const char* kWheelOdometry = "wheel_odometry.csv";
inline constexpr const char* kBarometer = "barometer.csv";
inline constexpr const char* kBarometerHeader = "stamp_s,altitude_m";
inline constexpr const char* kRangeHeader = "stamp_s,valid,range_m";
inline constexpr const char* kUwbHeader = "stamp_s,anchor_id,range_m,valid,los";
inline constexpr const char* kPressureHeader = "stamp_s,pressure_pa,depth_m";
inline constexpr const char* kDvlHeader = "stamp_s,valid,vx,vy,vz,altitude_m";
inline constexpr const char* kWheelOdometryHeader =
    "stamp_s,forward_speed_mps,yaw_rate_radps,slipping";
inline constexpr const char* kTimes = "times.txt";
inline constexpr const char* kPoses = "poses_gt.txt";
inline constexpr const char* kExtrinsic = "T_body_sensor.txt";
inline constexpr const char* kImu = "imu.csv";
inline constexpr const char* kVio = "vio.csv";
inline constexpr const char* kWorldDir = "world";
/// In world/: the FPFH descriptors of map.ply that `scantling localize` caches beside it (a
/// derived file: `sim --force` replaces it with the rest of the recording).
inline constexpr const char* kWorldMapDescriptorCache = "map.ply.fpfh";
inline constexpr const char* kSummary = "summary.json";
inline constexpr const char* kTiming = "timing.json";
inline constexpr const char* kImuHeader = "stamp_s,ax,ay,az,wx,wy,wz";
/// The columns every vio.csv has (recordings written before feature_quality have only these).
inline constexpr const char* kVioHeader =
    "stamp_s,valid,x,y,z,qx,qy,qz,qw,vx,vy,vz,var_x,var_y,var_z,var_rx,var_ry,var_rz";
/// The header the simulator writes: kVioHeader plus the feature quality in [0, 1].
inline constexpr const char* kVioFeatureQualityHeader =
    "stamp_s,valid,x,y,z,qx,qy,qz,qw,vx,vy,vz,var_x,var_y,var_z,var_rx,var_ry,var_rz,"
    "feature_quality";
/// In DIR/images/: one row per image, `index,stamp_s,defect_ids` with the ids of the defects
/// in view (world/metadata.json) ascending and separated by ';' (empty field: none).
inline constexpr const char* kVisibleDefects = "visible_defects.csv";
inline constexpr const char* kVisibleDefectsHeader = "index,stamp_s,defect_ids";
/// In DIR/images/: one row per defect in view per image, images in order.
inline constexpr const char* kDefectSightings = "defect_sightings.csv";
inline constexpr const char* kDefectSightingsHeader = "index,stamp_s,defect_id,u_px,v_px,radius_px";
/// In DIR/images/: {"width", "height", "fx", "fy", "cx", "cy"} (core/pinhole_intrinsics.hpp).
inline constexpr const char* kCameraIntrinsics = "camera.json";
/// "000042": the zero-padded 6-digit stem of frame `index`.
std::string frame_stem(std::size_t index);
}  // namespace recording_layout

/// One IMU sample: specific force and angular rate in the IMU frame.
struct ImuRecord {
    double stamp_s = 0.0;
    Eigen::Vector3d specific_force_mps2 = Eigen::Vector3d::Zero();
    Eigen::Vector3d angular_rate_radps = Eigen::Vector3d::Zero();
};

/// One VIO sample: body pose in the odometry frame, body velocity, and the variances of the
/// pose error (δp in m², δθ in rad², odom frame; the diagonal of the simulator's covariance).
struct VioRecord {
    double stamp_s = 0.0;
    bool valid = false;
    Eigen::Isometry3d T_odom_body = Eigen::Isometry3d::Identity();
    Eigen::Vector3d v_body_mps = Eigen::Vector3d::Zero();
    Eigen::Matrix<double, 6, 1> variances = Eigen::Matrix<double, 6, 1>::Zero();
    /// Share of textured, lit surface in the VIO camera's view the sample was simulated with,
    /// in [0, 1] (1 = good); empty for recordings without the column.
    std::optional<double> feature_quality;
};

/// One defect seen in one image: what a fiducial-tag detector returns (the simulator's visible
/// defects stand for the tags of the sources, SPEC §7). Pixels follow core/pinhole_intrinsics.hpp
/// (pixel centres at integers).
struct DefectSighting {
    std::size_t image = 0;  ///< index of the image
    double stamp_s = 0.0;
    int defect_id = 0;                                ///< Defect::id in world/metadata.json
    Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  ///< the defect centre, (u, v)
    double radius_px = 0.0;  ///< apparent radius of the patch (or half-length of the crack)
};

/// One single-beam range (NaN when invalid).
struct RangeRecord {
    double stamp_s = 0.0;
    bool valid = false;
    double range_m = 0.0;
};

/// One UWB range to one anchor (NaN when invalid); `line_of_sight` is ground truth.
struct UwbRecord {
    double stamp_s = 0.0;
    int anchor_id = 0;
    double range_m = 0.0;
    bool valid = false;
    bool line_of_sight = true;
};

/// One pressure sample: absolute pressure and the depth below the surface derived from it.
struct PressureRecord {
    double stamp_s = 0.0;
    double pressure_pa = 0.0;
    double depth_m = 0.0;
};

/// One DVL sample: body velocity and altitude (NaN without bottom lock).
struct DvlRecord {
    double stamp_s = 0.0;
    bool valid = false;
    Eigen::Vector3d v_body_mps = Eigen::Vector3d::Zero();
    double altitude_m = 0.0;
};

/// One wheel-odometry sample; `slipping` is ground truth (for evaluation).
struct WheelOdometryRecord {
    double stamp_s = 0.0;
    double forward_speed_mps = 0.0;
    double yaw_rate_radps = 0.0;
    bool slipping = false;
};

/// One barometric altitude (world z of the sensor, with the barometer's offset and noise).
struct BarometerRecord {
    double stamp_s = 0.0;
    double altitude_m = 0.0;
};

/// A stream of frames (lidar sweeps, depth frames, images): stamps and sensor poses.
struct FrameIndex {
    std::string directory;                    ///< empty when the recording has no such stream
    std::vector<double> stamps_s;             ///< one per frame
    std::vector<Eigen::Isometry3d> poses_gt;  ///< T_world_sensor, one per frame
    std::size_t size() const { return stamps_s.size(); }
};

class Recording {
  public:
    const std::string& directory() const { return directory_; }
    std::size_t num_sweeps() const { return lidar_.size(); }
    /// Sweep i in the sensor frame, `stamp_s` from times.txt; points and intensities from the
    /// .bin, plus rings and times_s when the .ply exists (then read from it). Throws
    /// InputError for i out of range, FileError/ParseError for a missing or malformed file.
    PointCloud read_sweep(std::size_t i) const;
    double sweep_stamp_s(std::size_t i) const;
    /// T_world_sensor at the start of sweep i (InputError when out of range).
    const Eigen::Isometry3d& sweep_pose_gt(std::size_t i) const;
    /// LiDAR mounting extrinsic (identity when the file is absent).
    const Eigen::Isometry3d& lidar_T_body_sensor() const { return lidar_T_body_sensor_; }

    std::size_t num_depth_frames() const { return depth_.size(); }
    /// Organised frame i (NaN where no return), optical frame, stamp from times.txt.
    PointCloud read_depth_frame(std::size_t i) const;
    const FrameIndex& depth_frames() const { return depth_; }
    /// Depth camera mounting extrinsic (optical frame), or nullopt when depth/T_body_sensor.txt
    /// is absent (recordings written before it existed).
    const std::optional<Eigen::Isometry3d>& depth_T_body_sensor() const {
        return depth_T_body_sensor_;
    }

    std::size_t num_images() const { return images_.size(); }
    /// Path of image i (PNG).
    std::string image_path(std::size_t i) const;
    const FrameIndex& images() const { return images_; }
    /// Ids of the defects in view in each image (images/visible_defects.csv): one entry per
    /// image, or empty when the recording has no such file (older recordings).
    const std::vector<std::vector<int>>& image_visible_defects() const {
        return image_visible_defects_;
    }
    /// Every defect sighting (images/defect_sightings.csv), in image order; empty when the
    /// recording has no such file.
    const std::vector<DefectSighting>& defect_sightings() const { return defect_sightings_; }
    /// The RGB camera's intrinsics (images/camera.json) and mount (images/T_body_sensor.txt),
    /// or nullopt when the file is absent.
    const std::optional<PinholeIntrinsics>& image_intrinsics() const { return image_intrinsics_; }
    const std::optional<Eigen::Isometry3d>& image_T_body_sensor() const {
        return image_T_body_sensor_;
    }

    const FrameIndex& lidar_sweeps() const { return lidar_; }
    /// Rosette LiDAR frame i in the sensor frame (KITTI .bin, or the .ply of an empty frame).
    PointCloud read_rosette_frame(std::size_t i) const;
    const FrameIndex& rosette_frames() const { return rosette_; }
    /// Sparse stereo frame i (left optical frame).
    PointCloud read_stereo_frame(std::size_t i) const;
    const FrameIndex& stereo_frames() const { return stereo_; }
    /// Intensities of sonar ping i, beam-major (sizes in sonar/meta.json).
    std::vector<float> read_sonar_intensity(std::size_t i) const;
    const FrameIndex& sonar_pings() const { return sonar_; }
    const std::vector<RangeRecord>& ranges() const { return range_; }
    const std::vector<UwbRecord>& uwb() const { return uwb_; }
    const std::vector<PressureRecord>& pressure() const { return pressure_; }
    const std::vector<DvlRecord>& dvl() const { return dvl_; }
    const std::vector<WheelOdometryRecord>& wheel_odometry() const { return wheel_odometry_; }
    const std::vector<BarometerRecord>& barometer() const { return barometer_; }
    /// Body poses at every clock step.
    const std::vector<StampedPose>& ground_truth() const { return ground_truth_; }
    const std::vector<ImuRecord>& imu() const { return imu_; }
    const std::vector<VioRecord>& vio() const { return vio_; }
    /// DIR/world/map.ply, mesh.ply, metadata.json (may not exist: export.world = false).
    std::string world_map_path() const;
    std::string world_mesh_path() const;
    std::string world_metadata_path() const;

  private:
    friend Recording open_recording(const std::string& directory);
    /// rosette/, stereo/, sonar/ and the CSVs of the ranging and odometry sensors.
    void read_extra_streams(const std::string& directory);
    /// images/visible_defects.csv when present (its rows must match the images).
    void read_visible_defects();
    /// images/defect_sightings.csv, camera.json and T_body_sensor.txt when present
    /// (recording_images.cpp).
    void read_image_camera();
    std::string directory_;
    FrameIndex lidar_;
    FrameIndex depth_;
    FrameIndex images_;
    std::vector<std::vector<int>> image_visible_defects_;
    std::vector<DefectSighting> defect_sightings_;
    std::optional<PinholeIntrinsics> image_intrinsics_;
    std::optional<Eigen::Isometry3d> image_T_body_sensor_;
    FrameIndex rosette_;
    FrameIndex stereo_;
    FrameIndex sonar_;
    std::vector<RangeRecord> range_;
    std::vector<UwbRecord> uwb_;
    std::vector<PressureRecord> pressure_;
    std::vector<DvlRecord> dvl_;
    std::vector<WheelOdometryRecord> wheel_odometry_;
    std::vector<BarometerRecord> barometer_;
    Eigen::Isometry3d lidar_T_body_sensor_ = Eigen::Isometry3d::Identity();
    std::optional<Eigen::Isometry3d> depth_T_body_sensor_;
    std::vector<StampedPose> ground_truth_;
    std::vector<ImuRecord> imu_;
    std::vector<VioRecord> vio_;
};

/// Opens a recording: reads groundtruth.tum (required), the stamps and poses of each frame
/// stream present (lidar/, depth/, images/: times.txt and poses_gt.txt must both exist and
/// agree in count; also rosette/, stereo/, sonar/), and every CSV present. Throws FileError when
/// DIR or groundtruth.tum is missing, ParseError naming the file and line for a malformed file or a
/// count mismatch ("lidar/poses_gt.txt: 12 poses but lidar/times.txt has 13 stamps").
///
/// Refused, not repaired, because every choice would be a silent guess at what the recording
/// meant (ParseError naming the file and line):
/// - stamps that repeat or go backwards in any times.txt or CSV (UWB: backwards only, its
///   rounds share a stamp per anchor) and non-finite stamps;
/// - frame files and stamps that disagree: a stamp whose frame file (NNNNNN.bin/.ply/.png, the
///   one the stream's reader needs) is missing, or a frame file with no stamp (index >= the
///   number of stamps), as a truncated or hand-edited recording has. Frames would otherwise be
///   dropped without a word or fail in the middle of a run.
Recording open_recording(const std::string& directory);

/// Readers of the CSV files (exposed for tests and tools). Throw FileError / ParseError
/// naming the line (wrong header, wrong column count, non-number, a non-finite stamp or one
/// not after the previous; uwb.csv: one before the previous).
std::vector<ImuRecord> read_imu_csv(const std::string& path);
/// Accepts kVioFeatureQualityHeader and the older kVioHeader (feature_quality left empty).
std::vector<VioRecord> read_vio_csv(const std::string& path);
/// images/visible_defects.csv: the ids per row; ParseError unless rows are numbered 0, 1, ...
std::vector<std::vector<int>> read_visible_defects_csv(const std::string& path);
/// images/defect_sightings.csv: ParseError naming the line unless image indices never decrease,
/// ids are >= 0, pixels finite and radii >= 0 (their agreement with the images' stamps is
/// checked by open_recording).
std::vector<DefectSighting> read_defect_sightings_csv(const std::string& path);
/// images/camera.json: ParseError naming the field for a missing, unknown or impossible one
/// (sizes >= 1, fx, fy > 0, finite cx, cy).
PinholeIntrinsics read_camera_intrinsics(const std::string& path);
/// The JSON read_camera_intrinsics reads.
std::string camera_intrinsics_json(const PinholeIntrinsics& intrinsics);
std::vector<RangeRecord> read_range_csv(const std::string& path);
std::vector<UwbRecord> read_uwb_csv(const std::string& path);
std::vector<PressureRecord> read_pressure_csv(const std::string& path);
std::vector<DvlRecord> read_dvl_csv(const std::string& path);
std::vector<WheelOdometryRecord> read_wheel_odometry_csv(const std::string& path);
std::vector<BarometerRecord> read_barometer_csv(const std::string& path);
/// One number per line (blank lines skipped), finite and strictly increasing; ParseError
/// naming the line otherwise.
std::vector<double> read_stamps(const std::string& path);

}  // namespace scantling::io
