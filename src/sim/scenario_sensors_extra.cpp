// The imaging sensors a scenario drives besides LiDAR and cameras: multibeam sonar, rosette
// LiDAR and sparse stereo (detail/scenario_parts.hpp).
#include <cmath>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/sim/multibeam_sonar.hpp>
#include <scantling/sim/rosette_lidar.hpp>
#include <scantling/sim/stereo_points.hpp>

#include <scantling/sim/sensor_configs.hpp>
#include "detail/scenario_parts.hpp"

namespace scantling::sim::detail {

MultibeamSonarConfig sonar_config(const SensorSpec& spec, const std::string& prefix) {
    MultibeamSonarConfig config;
    if (spec.num_beams > 0) config.num_beams = spec.num_beams;
    if (spec.num_bins > 0) config.num_bins = spec.num_bins;
    if (spec.max_range_m > 0.0) config.max_range_m = spec.max_range_m;
    if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    if (!spec.noise) {
        config.speckle = false;
        config.noise_floor = 0.0;
    }
    config.T_body_sensor = spec.T_body_sensor.to_isometry();
    config.validate(prefix);
    return config;
}

RosetteLidarConfig rosette_config(const SensorSpec& spec, const std::string& prefix) {
    if (spec.preset != SensorPreset::kDefault && spec.preset != SensorPreset::kLivoxMid70) {
        throw ConfigError(prefix + ".preset does not apply to this sensor type");
    }
    RosetteLidarConfig config = livox_mid70();
    if (spec.rate_hz > 0.0) config.frame_rate_hz = spec.rate_hz;
    if (!spec.noise) config.returns = ReturnModel{};
    config.T_body_sensor = spec.T_body_sensor.to_isometry();
    config.validate(prefix);
    return config;
}

StereoPointsConfig stereo_config(const SensorSpec& spec, const std::string& prefix) {
    StereoPointsConfig config;
    if (spec.width > 0) {
        // Same field of view at the new width; the focal length scales with it.
        const PinholeIntrinsics& k = config.intrinsics;
        const int height = static_cast<int>(std::lround(1.0 * spec.width * k.height / k.width));
        config.intrinsics =
            PinholeIntrinsics::from_fov(spec.width, height, k.hfov_rad(), k.vfov_rad());
        config.feature_spacing_px *= static_cast<double>(spec.width) / k.width;
    }
    if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    if (!spec.noise) config.disparity_sigma_px = 0.0;
    config.T_body_sensor = spec.T_body_sensor.to_isometry();
    config.validate(prefix);
    return config;
}

namespace {

class SonarSensor : public ScenarioSensor {
  public:
    SonarSensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : sonar_(sonar_config(spec, prefix)), rng_(std::move(rng)) {}
    double rate_hz() const override { return sonar_.config().rate_hz; }
    SensorData fire(const FireContext& c) override {
        const Eigen::Isometry3d T_world_body = c.vehicle.pose_at(c.stamp_s);
        return SonarReading{
            .image = sonar_.scan(c.scene, T_world_body, rng_, c.stamp_s, c.parallel),
            .T_world_sensor = T_world_body * sonar_.config().T_body_sensor};
    }

  private:
    MultibeamSonar sonar_;
    Rng rng_;
};

class RosetteSensor : public ScenarioSensor {
  public:
    RosetteSensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : lidar_(rosette_config(spec, prefix)), rng_(std::move(rng)) {}
    double rate_hz() const override { return lidar_.config().frame_rate_hz; }
    SensorData fire(const FireContext& c) override {
        const Eigen::Isometry3d T_world_body = c.vehicle.pose_at(c.stamp_s);
        return RosetteReading{
            .frame = lidar_.scan(c.scene, T_world_body, rng_, c.stamp_s, c.parallel),
            .T_world_sensor = T_world_body * lidar_.config().T_body_sensor};
    }

  private:
    RosetteLidar lidar_;
    Rng rng_;
};

class StereoSensor : public ScenarioSensor {
  public:
    StereoSensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : stereo_(stereo_config(spec, prefix)), rng_(std::move(rng)) {}
    double rate_hz() const override { return stereo_.config().rate_hz; }
    SensorData fire(const FireContext& c) override {
        const Eigen::Isometry3d T_world_body = c.vehicle.pose_at(c.stamp_s);
        return StereoReading{
            .frame = stereo_.scan(c.scene, T_world_body, rng_, c.stamp_s, c.parallel),
            .T_world_sensor = T_world_body * stereo_.config().T_body_sensor};
    }

  private:
    StereoPoints stereo_;
    Rng rng_;
};

}  // namespace

std::unique_ptr<ScenarioSensor> make_imaging_sensor(const SensorSpec& spec, Rng rng,
                                                    const std::string& prefix) {
    switch (spec.type) {
        case SensorType::kMultibeamSonar:
            return std::make_unique<SonarSensor>(spec, std::move(rng), prefix);
        case SensorType::kRosetteLidar:
            return std::make_unique<RosetteSensor>(spec, std::move(rng), prefix);
        case SensorType::kStereoPoints:
            return std::make_unique<StereoSensor>(spec, std::move(rng), prefix);
        default:
            return make_ranging_sensor(spec, std::move(rng), prefix);
    }
}

}  // namespace scantling::sim::detail
