// The sensors a scenario drives (detail/scenario_parts.hpp).
#include <cmath>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/sim/depth_camera.hpp>
#include <scantling/sim/imu.hpp>
#include <scantling/sim/pinhole_camera.hpp>
#include <scantling/sim/spinning_lidar.hpp>
#include <scantling/sim/vio.hpp>
#include <scantling/sim/vio_features.hpp>

#include <scantling/sim/sensor_configs.hpp>
#include "detail/scenario_parts.hpp"

namespace scantling::sim::detail {

namespace {

[[noreturn]] void bad_preset(const std::string& prefix) {
    throw ConfigError(prefix + ".preset does not apply to this sensor type");
}

}  // namespace

SpinningLidarConfig lidar_config(const SensorSpec& spec, const std::string& prefix) {
    SpinningLidarConfig config;
    if (spec.preset == SensorPreset::kDefault || spec.preset == SensorPreset::kOs1_64) {
        config = ouster_os1_64(spec.columns > 0 ? spec.columns : 1024,
                               spec.rate_hz > 0.0 ? spec.rate_hz : 10.0);
    } else if (spec.preset == SensorPreset::kOs0_64) {
        config = ouster_os0_64(spec.columns > 0 ? spec.columns : 1024,
                               spec.rate_hz > 0.0 ? spec.rate_hz : 10.0);
    } else if (spec.preset == SensorPreset::kHdl64e) {
        config = velodyne_hdl64e();
        if (spec.columns > 0) config.columns = spec.columns;
        if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    } else {
        bad_preset(prefix);
    }
    if (!spec.noise) config.returns = ReturnModel{};
    config.T_body_sensor = spec.T_body_sensor.to_isometry();
    config.validate(prefix);
    return config;
}

ImuConfig imu_config(const SensorSpec& spec, const std::string& prefix) {
    ImuConfig config;
    if (spec.preset == SensorPreset::kDefault || spec.preset == SensorPreset::kConsumerMems) {
        config = consumer_mems_imu();
    } else if (spec.preset == SensorPreset::kIndustrialMems) {
        config = industrial_mems_imu();
    } else {
        bad_preset(prefix);
    }
    if (!spec.noise) config = noiseless(config);
    if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    config.T_body_sensor = spec.T_body_sensor.to_isometry();
    config.validate(prefix);
    return config;
}

VioConfig vio_config(const SensorSpec& spec, const std::string& prefix) {
    if (spec.preset != SensorPreset::kDefault && spec.preset != SensorPreset::kT265) {
        bad_preset(prefix);
    }
    VioConfig config = spec.noise ? VioConfig{} : noiseless(VioConfig{});
    if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    config.validate(prefix);
    return config;
}

DepthCameraConfig depth_config(const SensorSpec& spec, const std::string& prefix) {
    DepthCameraConfig config;
    if (spec.preset == SensorPreset::kDefault || spec.preset == SensorPreset::kL515) {
        config = intel_l515(spec.width > 0 ? spec.width : 640);
    } else if (spec.preset == SensorPreset::kAzureNfov ||
               spec.preset == SensorPreset::kAzureNfovBinned) {
        config = azure_kinect_nfov(spec.preset == SensorPreset::kAzureNfovBinned);
    } else {
        bad_preset(prefix);
    }
    if (!spec.noise) config.depth_noise = ReturnModel{};
    if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    config.T_body_sensor = spec.T_body_sensor.to_isometry();
    config.validate(prefix);
    return config;
}

PinholeCameraConfig camera_config(const SensorSpec& spec, const std::string& prefix) {
    PinholeCameraConfig config;
    if (spec.preset == SensorPreset::kDefault || spec.preset == SensorPreset::kUav3d) {
        config = uav3d_camera();
    } else if (spec.preset == SensorPreset::kRov) {
        config = rov_camera();
    } else {
        bad_preset(prefix);
    }
    if (spec.width > 0) {
        const PinholeIntrinsics& k = config.intrinsics;
        const int height =
            spec.height > 0 ? spec.height
                            : static_cast<int>(std::lround(1.0 * spec.width * k.height / k.width));
        config.intrinsics =
            PinholeIntrinsics::from_fov(spec.width, height, k.hfov_rad(), k.vfov_rad());
    }
    if (!spec.noise) config.pixel_noise_dn = 0.0;
    if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    config.T_body_sensor = spec.T_body_sensor.to_isometry();
    config.lasers = spec.lasers;
    config.validate(prefix);
    return config;
}

namespace {

class LidarSensor : public ScenarioSensor {
  public:
    LidarSensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : lidar_(lidar_config(spec, prefix)),
          rng_(std::move(rng)),
          motion_distortion_(spec.motion_distortion),
          write_ply_(spec.write_ply || spec.motion_distortion) {}
    double rate_hz() const override { return lidar_.config().rate_hz; }
    double lookahead_s() const override {
        return motion_distortion_ ? 1.0 / lidar_.config().rate_hz : 0.0;
    }
    SensorData fire(const FireContext& c) override {
        const Eigen::Isometry3d T_world_body = c.vehicle.pose_at(c.stamp_s);
        LidarReading reading{.sweep = {},
                             .T_world_sensor = T_world_body * lidar_.config().T_body_sensor,
                             .T_body_sensor = lidar_.config().T_body_sensor,
                             .write_ply = write_ply_};
        if (motion_distortion_) {
            const auto pose_at = [&c](double t_s) { return c.vehicle.pose_at(t_s); };
            reading.sweep = lidar_.scan_moving(c.scene, pose_at, c.stamp_s, rng_, c.parallel);
            reading.sweep.stamp_s = c.stamp_s;
        } else {
            reading.sweep = lidar_.scan(c.scene, T_world_body, rng_, c.stamp_s, c.parallel);
        }
        return reading;
    }

  private:
    SpinningLidar lidar_;
    Rng rng_;
    bool motion_distortion_;
    bool write_ply_;
};

class ImuSensor : public ScenarioSensor {
  public:
    ImuSensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : rng_(std::move(rng)), imu_(imu_config(spec, prefix), rng_) {}
    double rate_hz() const override { return imu_.config().rate_hz; }
    SensorData fire(const FireContext& c) override {
        return imu_.measure(c.vehicle.at_tick(c.tick), rng_);
    }

  private:
    Rng rng_;
    ImuSimulator imu_;
};

VioFeatureConfig vio_features(const SensorSpec& spec, const std::string& prefix) {
    VioFeatureConfig config;
    config.ambient_light = spec.ambient_light;
    // An unset mount looks forward (identity would put the optical axis along body z).
    const PoseSpec& mount = spec.T_body_sensor;
    const bool unset = mount.xyz.isZero() && mount.rpy_deg.isZero();
    config.T_body_sensor = unset ? PoseSpec{.xyz = Eigen::Vector3d::Zero(),
                                            .rpy_deg = Eigen::Vector3d(-90.0, 0.0, -90.0)}
                                       .to_isometry()
                                 : mount.to_isometry();
    config.validate(prefix);
    return config;
}

class VioSensor : public ScenarioSensor {
  public:
    VioSensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : vio_(vio_config(spec, prefix)),
          features_(vio_features(spec, prefix)),
          rng_(std::move(rng)) {}
    double rate_hz() const override { return vio_.config().rate_hz; }
    SensorData fire(const FireContext& c) override {
        const MotionState& state = c.vehicle.at_tick(c.tick);
        const double quality = vio_feature_quality(c.scene, state.T_world_body, features_);
        return vio_.step(state, quality, rng_);
    }

  private:
    VioSimulator vio_;
    VioFeatureConfig features_;
    Rng rng_;
};

class DepthSensor : public ScenarioSensor {
  public:
    DepthSensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : camera_(depth_config(spec, prefix)), rng_(std::move(rng)) {}
    double rate_hz() const override { return camera_.config().rate_hz; }
    SensorData fire(const FireContext& c) override {
        const Eigen::Isometry3d T_world_body = c.vehicle.pose_at(c.stamp_s);
        return DepthReading{
            .frame = camera_.scan(c.scene, T_world_body, rng_, c.stamp_s, c.parallel),
            .T_world_sensor = T_world_body * camera_.config().T_body_sensor,
            .T_body_sensor = camera_.config().T_body_sensor};
    }

  private:
    DepthCamera camera_;
    Rng rng_;
};

class CameraSensor : public ScenarioSensor {
  public:
    CameraSensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : camera_(camera_config(spec, prefix)), rng_(std::move(rng)) {}
    double rate_hz() const override { return camera_.config().rate_hz; }
    SensorData fire(const FireContext& c) override {
        const Eigen::Isometry3d T_world_body = c.vehicle.pose_at(c.stamp_s);
        return ImageReading{.image = camera_.render(c.scene, T_world_body, rng_, c.parallel),
                            .stamp_s = c.stamp_s,
                            .T_world_sensor = T_world_body * camera_.config().T_body_sensor,
                            .intrinsics = camera_.config().intrinsics,
                            .T_body_sensor = camera_.config().T_body_sensor,
                            .sightings = camera_.sight_defects(c.scene, T_world_body),
                            .laser_spots = camera_.laser_spots(c.scene, T_world_body)};
    }

  private:
    PinholeCamera camera_;
    Rng rng_;
};

}  // namespace

std::unique_ptr<ScenarioSensor> make_sensor(const SensorSpec& spec, Rng rng,
                                            const std::string& prefix) {
    switch (spec.type) {
        case SensorType::kSpinningLidar:
            return std::make_unique<LidarSensor>(spec, std::move(rng), prefix);
        case SensorType::kImu:
            return std::make_unique<ImuSensor>(spec, std::move(rng), prefix);
        case SensorType::kVio:
            return std::make_unique<VioSensor>(spec, std::move(rng), prefix);
        case SensorType::kDepthCamera:
            return std::make_unique<DepthSensor>(spec, std::move(rng), prefix);
        case SensorType::kCamera:
            return std::make_unique<CameraSensor>(spec, std::move(rng), prefix);
        default:
            return make_imaging_sensor(spec, std::move(rng), prefix);
    }
}

}  // namespace scantling::sim::detail
