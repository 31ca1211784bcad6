#pragma once
/// @file
/// What a simulated sensor returns when it fires: its data, not a file. The scenario runner
/// hands each reading to the RecordingWriter (RecordingWriter::add); the closed loop
/// (mission) hands it to the robot's stack and to the writer. One type per kind of data; the
/// frame readings carry the sensor's mount and its ground-truth pose for the recording.
///
/// Frames: every cloud and image is in its sensor's frame (optical frame for cameras),
/// stamped at its start; `T_world_sensor` is the ground-truth pose at that stamp.

#include <Eigen/Geometry>
#include <cstddef>
#include <variant>
#include <vector>

#include <scantling/core/pinhole_intrinsics.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/sim/barometer.hpp>
#include <scantling/sim/dvl.hpp>
#include <scantling/sim/imu.hpp>
#include <scantling/sim/multibeam_sonar.hpp>
#include <scantling/sim/pinhole_camera.hpp>
#include <scantling/sim/pressure.hpp>
#include <scantling/sim/range_finder.hpp>
#include <scantling/sim/uwb.hpp>
#include <scantling/sim/vio.hpp>
#include <scantling/sim/wheel_odometry.hpp>

namespace scantling::sim {

/// One spinning-LiDAR sweep.
struct LidarReading {
    PointCloud sweep;  ///< sensor frame, stamped at the sweep start
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();
    bool write_ply = false;  ///< the recording keeps rings and per-point times (.ply)
};

/// A depth-camera frame (organised, NaN where no return) or a rosette/stereo frame.
struct DepthReading {
    PointCloud frame;
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();
};
struct RosetteReading {
    PointCloud frame;
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
};
struct StereoReading {
    PointCloud frame;
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
};

/// An RGB image with the defects in view (the stand-in for a tag detector's output).
struct ImageReading {
    RgbImage image;
    double stamp_s = 0.0;
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
    PinholeIntrinsics intrinsics;
    Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();
    std::vector<io::DefectSighting> sightings;
    /// Ground truth of the camera's laser spots in this image (empty without lasers); not
    /// written to recordings.
    std::vector<LaserSpot> laser_spots;
};

struct SonarReading {
    SonarImage image;
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
};

using SensorData =
    std::variant<LidarReading, ImuSample, VioSample, DepthReading, ImageReading, SonarReading,
                 RosetteReading, StereoReading, RangeMeasurement, UwbMeasurement, PressureSample,
                 DvlSample, WheelOdometrySample, BarometerSample>;

struct SensorReading {
    std::size_t sensor_index = 0;  ///< position in Scenario::sensors
    double stamp_s = 0.0;          ///< nominal firing time
    SensorData data;
};

}  // namespace scantling::sim
