// Names of the scenario's enumerations as written in YAML (scenario.hpp).
#include <scantling/sim/scenario.hpp>

namespace scantling::sim {

std::string_view to_string(SensorType type) {
    switch (type) {
        case SensorType::kSpinningLidar:
            return "spinning_lidar";
        case SensorType::kImu:
            return "imu";
        case SensorType::kVio:
            return "vio";
        case SensorType::kDepthCamera:
            return "depth_camera";
        case SensorType::kCamera:
            return "camera";
        case SensorType::kMultibeamSonar:
            return "multibeam_sonar";
        case SensorType::kRosetteLidar:
            return "rosette_lidar";
        case SensorType::kStereoPoints:
            return "stereo_points";
        case SensorType::kRangeFinder:
            return "range_finder";
        case SensorType::kUwb:
            return "uwb";
        case SensorType::kPressure:
            return "pressure";
        case SensorType::kDvl:
            return "dvl";
        case SensorType::kWheelOdometry:
            return "wheel_odometry";
        case SensorType::kBarometer:
            return "barometer";
    }
    return "?";
}

std::string_view to_string(WorldType type) {
    switch (type) {
        case WorldType::kBallastTankMockup:
            return "ballast_tank_mockup";
        case WorldType::kBallastTankLarge:
            return "ballast_tank_large";
        case WorldType::kStorageTank:
            return "storage_tank";
        case WorldType::kDistillationColumn:
            return "distillation_column";
        case WorldType::kCylinder:
            return "cylinder";
        case WorldType::kPlate:
            return "plate";
        case WorldType::kMesh:
            return "mesh";
        case WorldType::kShipHull:
            return "ship_hull";
        case WorldType::kMoebius:
            return "moebius";
        case WorldType::kShipHullMesh:
            return "ship_hull_mesh";
        case WorldType::kUrban:
            return "urban";
    }
    return "?";
}

}  // namespace scantling::sim
