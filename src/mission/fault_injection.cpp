// Sensor faults between the simulator and the stack (fault_injection.hpp).
#include <scantling/mission/fault_injection.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/sim/scenario_schema.hpp>

#include "detail/mission_schemas.hpp"

namespace scantling::mission {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

/// The sensors whose readings the stacks consume as measurements (the drone's, the ROV's and
/// the crawler's),
/// hence the ones a NaN fault can poison (poisoned() below).
bool poisonable(sim::SensorType type) {
    using T = sim::SensorType;
    return type == T::kSpinningLidar || type == T::kImu || type == T::kRangeFinder ||
           type == T::kBarometer || type == T::kUwb || type == T::kDvl || type == T::kPressure ||
           type == T::kMultibeamSonar || type == T::kWheelOdometry;
}

bool inside(const SensorFault& f, double t_s) {
    return t_s >= f.start_s && t_s < f.start_s + f.duration_s;
}

}  // namespace

std::string_view to_string(FaultKind kind) { return kind == FaultKind::kNan ? "nan" : "dropout"; }

void SensorFault::validate(std::string_view prefix) const {
    config_checks::require(std::isfinite(start_s) && start_s >= 0.0, prefix, "start_s", start_s,
                           "finite >= 0 (seconds of simulated time)");
    config_checks::require(std::isfinite(duration_s) && duration_s > 0.0, prefix, "duration_s",
                           duration_s, "finite > 0 (seconds)");
    if (kind == FaultKind::kNan && !poisonable(sensor)) {
        throw ConfigError(fmt::format(
            "{}.kind = nan for a {} sensor: NaN faults apply to the stacks' measurements "
            "(spinning_lidar, imu, range_finder, barometer, uwb, dvl, pressure, "
            "multibeam_sonar); use dropout",
            prefix, sim::to_string(sensor)));
    }
}

FaultInjector::FaultInjector(std::vector<SensorFault> faults,
                             std::vector<sim::SensorType> sensor_types)
    : faults_(std::move(faults)), sensor_types_(std::move(sensor_types)), phase_(faults_.size()) {
    for (std::size_t i = 0; i < faults_.size(); ++i) {
        faults_[i].validate(fmt::format("faults[{}]", i));
    }
}

const SensorFault* FaultInjector::fault_of(const sim::SensorReading& reading) const {
    if (reading.sensor_index >= sensor_types_.size()) return nullptr;
    const sim::SensorType type = sensor_types_[reading.sensor_index];
    const auto it = std::find_if(faults_.begin(), faults_.end(), [&](const SensorFault& f) {
        return f.sensor == type && inside(f, reading.stamp_s);
    });
    return it == faults_.end() ? nullptr : &*it;
}

std::vector<FaultChange> FaultInjector::changes(double t_s) {
    std::vector<FaultChange> out;
    for (std::size_t i = 0; i < faults_.size(); ++i) {
        if (phase_[i] == 0 && t_s >= faults_[i].start_s) {
            phase_[i] = 1;
            out.push_back({i, true});
        }
        if (phase_[i] == 1 && t_s >= faults_[i].start_s + faults_[i].duration_s) {
            phase_[i] = 2;
            out.push_back({i, false});
        }
    }
    return out;
}

sim::SensorReading poisoned(sim::SensorReading reading) {
    if (auto* imu = std::get_if<sim::ImuSample>(&reading.data)) {
        imu->specific_force_mps2.setConstant(kNan);
        imu->angular_rate_radps.setConstant(kNan);
    } else if (auto* range = std::get_if<sim::RangeMeasurement>(&reading.data)) {
        range->range_m = kNan;
    } else if (auto* baro = std::get_if<sim::BarometerSample>(&reading.data)) {
        baro->altitude_m = kNan;
    } else if (auto* uwb = std::get_if<sim::UwbMeasurement>(&reading.data)) {
        for (sim::UwbRange& r : uwb->ranges) r.range_m = kNan;
    } else if (auto* lidar = std::get_if<sim::LidarReading>(&reading.data)) {
        for (Eigen::Vector3d& p : lidar->sweep.points) p.setConstant(kNan);
    } else if (auto* dvl = std::get_if<sim::DvlSample>(&reading.data)) {
        dvl->v_body_mps.setConstant(kNan);
    } else if (auto* pressure = std::get_if<sim::PressureSample>(&reading.data)) {
        pressure->depth_m = kNan;
        pressure->pressure_pa = kNan;
    } else if (auto* wheel = std::get_if<sim::WheelOdometrySample>(&reading.data)) {
        wheel->forward_speed_mps = kNan;
        wheel->yaw_rate_radps = kNan;
    } else if (auto* sonar = std::get_if<sim::SonarReading>(&reading.data)) {
        std::fill(sonar->image.intensity.begin(), sonar->image.intensity.end(),
                  std::numeric_limits<float>::quiet_NaN());
    }
    return reading;
}

namespace detail {

const io::ConfigSchema<SensorFault>& fault_schema() {
    using S = SensorFault;
    static const io::ConfigSchema<S> schema = [] {
        io::ConfigSchema<S> s;
        s.enum_field("sensor", &S::sensor, sim::detail::sensor_type_choices(),
                     "every simulated sensor of this type")
            .enum_field("kind", &S::kind,
                        {{"dropout", FaultKind::kDropout}, {"nan", FaultKind::kNan}},
                        "no readings, or readings of NaNs")
            .field("start_s", &S::start_s, "simulated time, s", io::Range{.min = 0.0})
            .field("duration_s", &S::duration_s, "s", io::kPositive);
        return s;
    }();
    return schema;
}

}  // namespace detail

}  // namespace scantling::mission
