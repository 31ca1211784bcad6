// The ranging and odometry sensors a scenario drives: single-beam ranger, UWB, pressure, DVL
// and wheel odometry (detail/scenario_parts.hpp).
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/sim/barometer.hpp>
#include <scantling/sim/dvl.hpp>
#include <scantling/sim/pressure.hpp>
#include <scantling/sim/range_finder.hpp>
#include <scantling/sim/uwb.hpp>
#include <scantling/sim/wheel_odometry.hpp>

#include <scantling/sim/sensor_configs.hpp>
#include "detail/scenario_parts.hpp"

namespace scantling::sim::detail {

RangeFinderConfig range_config(const SensorSpec& spec, const std::string& prefix) {
    RangeFinderConfig config;
    switch (spec.preset) {
        case SensorPreset::kDefault:
        case SensorPreset::kLidarLiteV3:
            config = down_looking_lidar_lite_v3();
            break;
        case SensorPreset::kTerarangerEvo60m:
            config = up_looking_teraranger_evo_60m();
            break;
        case SensorPreset::kHcSr04:
            config = ultrasonic_hc_sr04();
            break;
        default:
            throw ConfigError(prefix + ".preset does not apply to this sensor type");
    }
    if (spec.max_range_m > 0.0) config.max_range_m = spec.max_range_m;
    if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    if (!spec.noise) config.range_sigma_m = config.range_sigma_fraction = 0.0;
    config.T_body_sensor = spec.T_body_sensor.to_isometry();
    config.validate(prefix);
    return config;
}

UwbConfig uwb_config(const SensorSpec& spec, const std::string& prefix) {
    UwbConfig config;
    config.anchors = spec.anchors;
    if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    if (!spec.noise) config = noiseless(config);
    config.T_body_sensor = spec.T_body_sensor.to_isometry();
    config.validate(prefix);
    return config;
}

PressureConfig pressure_config(const SensorSpec& spec, const std::string& prefix) {
    PressureConfig config;
    config.surface_z_m = spec.surface_z_m;
    if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    if (!spec.noise) config.pressure_sigma_pa = 0.0;
    config.T_body_sensor = spec.T_body_sensor.to_isometry();
    config.validate(prefix);
    return config;
}

DvlConfig dvl_config(const SensorSpec& spec, const std::string& prefix) {
    DvlConfig config = spec.noise ? DvlConfig{} : noiseless(DvlConfig{});
    if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    // An unset mount keeps the model's down-looking default (identity would look up).
    const PoseSpec& mount = spec.T_body_sensor;
    if (!mount.xyz.isZero() || !mount.rpy_deg.isZero()) config.T_body_sensor = mount.to_isometry();
    config.validate(prefix);
    return config;
}

BarometerConfig barometer_config(const SensorSpec& spec, const std::string& prefix) {
    BarometerConfig config = spec.noise ? BarometerConfig{} : noiseless(BarometerConfig{});
    if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    config.T_body_sensor = spec.T_body_sensor.to_isometry();
    config.validate(prefix);
    return config;
}

WheelOdometryConfig wheel_config(const SensorSpec& spec, const std::string& prefix) {
    WheelOdometryConfig config =
        spec.noise ? WheelOdometryConfig{} : noiseless(WheelOdometryConfig{});
    if (spec.rate_hz > 0.0) config.rate_hz = spec.rate_hz;
    config.validate(prefix);
    return config;
}

namespace {

class RangeSensor : public ScenarioSensor {
  public:
    RangeSensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : ranger_(range_config(spec, prefix)), rng_(std::move(rng)) {}
    double rate_hz() const override { return ranger_.config().rate_hz; }
    SensorData fire(const FireContext& c) override {
        return ranger_.measure(c.scene, c.vehicle.pose_at(c.stamp_s), rng_, c.stamp_s);
    }

  private:
    RangeFinder ranger_;
    Rng rng_;
};

class UwbSensor : public ScenarioSensor {
  public:
    UwbSensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : tag_(uwb_config(spec, prefix)), rng_(std::move(rng)) {}
    double rate_hz() const override { return tag_.config().rate_hz; }
    SensorData fire(const FireContext& c) override {
        return tag_.measure(c.scene, c.vehicle.pose_at(c.stamp_s), rng_, c.stamp_s);
    }

  private:
    UwbTag tag_;
    Rng rng_;
};

class PressureSensorPart : public ScenarioSensor {
  public:
    PressureSensorPart(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : sensor_(pressure_config(spec, prefix)), rng_(std::move(rng)) {}
    double rate_hz() const override { return sensor_.config().rate_hz; }
    SensorData fire(const FireContext& c) override {
        return sensor_.measure(c.vehicle.pose_at(c.stamp_s), rng_, c.stamp_s);
    }

  private:
    PressureSensor sensor_;
    Rng rng_;
};

class DvlSensor : public ScenarioSensor {
  public:
    DvlSensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : dvl_(dvl_config(spec, prefix)), rng_(std::move(rng)) {}
    double rate_hz() const override { return dvl_.config().rate_hz; }
    SensorData fire(const FireContext& c) override {
        return dvl_.measure(c.scene, c.vehicle.at_tick(c.tick), rng_);
    }

  private:
    Dvl dvl_;
    Rng rng_;
};

class WheelOdometrySensor : public ScenarioSensor {
  public:
    WheelOdometrySensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : rng_(std::move(rng)), odometry_(wheel_config(spec, prefix), rng_) {}
    double rate_hz() const override { return odometry_.config().rate_hz; }
    SensorData fire(const FireContext& c) override {
        return odometry_.measure(c.vehicle.at_tick(c.tick), rng_);
    }

  private:
    Rng rng_;
    WheelOdometrySimulator odometry_;
};

class BarometerSensor : public ScenarioSensor {
  public:
    BarometerSensor(const SensorSpec& spec, Rng rng, const std::string& prefix)
        : rng_(std::move(rng)), barometer_(barometer_config(spec, prefix), rng_) {}
    double rate_hz() const override { return barometer_.config().rate_hz; }
    SensorData fire(const FireContext& c) override {
        return barometer_.measure(c.vehicle.pose_at(c.stamp_s), rng_, c.stamp_s);
    }

  private:
    Rng rng_;
    Barometer barometer_;
};

}  // namespace

std::unique_ptr<ScenarioSensor> make_ranging_sensor(const SensorSpec& spec, Rng rng,
                                                    const std::string& prefix) {
    switch (spec.type) {
        case SensorType::kRangeFinder:
            return std::make_unique<RangeSensor>(spec, std::move(rng), prefix);
        case SensorType::kUwb:
            return std::make_unique<UwbSensor>(spec, std::move(rng), prefix);
        case SensorType::kPressure:
            return std::make_unique<PressureSensorPart>(spec, std::move(rng), prefix);
        case SensorType::kDvl:
            return std::make_unique<DvlSensor>(spec, std::move(rng), prefix);
        case SensorType::kWheelOdometry:
            return std::make_unique<WheelOdometrySensor>(spec, std::move(rng), prefix);
        case SensorType::kBarometer:
            return std::make_unique<BarometerSensor>(spec, std::move(rng), prefix);
        default:
            throw ConfigError(prefix + ".type: unknown sensor type");
    }
}

}  // namespace scantling::sim::detail
