#pragma once
/// @file
/// The effective config of each scenario sensor: the preset with the scenario's overrides
/// (rate, size, noise, mount), validated. The runner builds its sensors from these and the
/// scenario's validation and output estimate read rates and frame sizes from the same ones,
/// so what is checked is what runs; a closed-loop mission calibrates its robot's stack from
/// them too (a camera's intrinsics, a sonar's mount). Each throws ConfigError naming `prefix`
/// ("sensors[1]").

#include <string>

#include <scantling/sim/barometer.hpp>
#include <scantling/sim/depth_camera.hpp>
#include <scantling/sim/dvl.hpp>
#include <scantling/sim/imu.hpp>
#include <scantling/sim/multibeam_sonar.hpp>
#include <scantling/sim/pinhole_camera.hpp>
#include <scantling/sim/pressure.hpp>
#include <scantling/sim/range_finder.hpp>
#include <scantling/sim/rosette_lidar.hpp>
#include <scantling/sim/scenario.hpp>
#include <scantling/sim/spinning_lidar.hpp>
#include <scantling/sim/stereo_points.hpp>
#include <scantling/sim/uwb.hpp>
#include <scantling/sim/vio.hpp>
#include <scantling/sim/wheel_odometry.hpp>

namespace scantling::sim::detail {

// scenario_sensors.cpp
SpinningLidarConfig lidar_config(const SensorSpec& spec, const std::string& prefix);
ImuConfig imu_config(const SensorSpec& spec, const std::string& prefix);
VioConfig vio_config(const SensorSpec& spec, const std::string& prefix);
DepthCameraConfig depth_config(const SensorSpec& spec, const std::string& prefix);
PinholeCameraConfig camera_config(const SensorSpec& spec, const std::string& prefix);

// scenario_sensors_extra.cpp
MultibeamSonarConfig sonar_config(const SensorSpec& spec, const std::string& prefix);
RosetteLidarConfig rosette_config(const SensorSpec& spec, const std::string& prefix);
StereoPointsConfig stereo_config(const SensorSpec& spec, const std::string& prefix);

// scenario_sensors_ranging.cpp
RangeFinderConfig range_config(const SensorSpec& spec, const std::string& prefix);
UwbConfig uwb_config(const SensorSpec& spec, const std::string& prefix);
PressureConfig pressure_config(const SensorSpec& spec, const std::string& prefix);
DvlConfig dvl_config(const SensorSpec& spec, const std::string& prefix);
WheelOdometryConfig wheel_config(const SensorSpec& spec, const std::string& prefix);
BarometerConfig barometer_config(const SensorSpec& spec, const std::string& prefix);

}  // namespace scantling::sim::detail
