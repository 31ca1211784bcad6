// RecordingWriter::add: one sensor reading to the add_* of its type (recording_writer.hpp).
#include <scantling/sim/recording_writer.hpp>

#include <type_traits>
#include <variant>

namespace scantling::sim {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
    using Ts::operator()...;
};
// Needed by clang < 17 (the fuzzers' compiler), which lacks CTAD for aggregates.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace

void RecordingWriter::add(const SensorReading& reading) {
    std::visit(
        Overloaded{
            [this](const LidarReading& r) {
                if (counts_.lidar_sweeps == 0) set_lidar_extrinsic(r.T_body_sensor);
                add_lidar_sweep(r.sweep, r.T_world_sensor, r.write_ply);
            },
            [this](const DepthReading& r) {
                if (counts_.depth_frames == 0) set_depth_extrinsic(r.T_body_sensor);
                add_depth_frame(r.frame, r.T_world_sensor);
            },
            [this](const ImageReading& r) {
                if (counts_.images == 0) set_image_camera(r.intrinsics, r.T_body_sensor);
                add_image(r.image, r.stamp_s, r.T_world_sensor, r.sightings);
            },
            [this](const SonarReading& r) { add_sonar(r.image, r.T_world_sensor); },
            [this](const RosetteReading& r) { add_rosette_frame(r.frame, r.T_world_sensor); },
            [this](const StereoReading& r) { add_stereo_frame(r.frame, r.T_world_sensor); },
            [this](const ImuSample& s) { add_imu(s); },
            [this](const VioSample& s) { add_vio(s); },
            [this](const RangeMeasurement& m) { add_range(m); },
            [this](const UwbMeasurement& m) { add_uwb(m); },
            [this](const PressureSample& s) { add_pressure(s); },
            [this](const DvlSample& s) { add_dvl(s); },
            [this](const WheelOdometrySample& s) { add_wheel_odometry(s); },
            [this](const BarometerSample& s) { add_barometer(s); },
        },
        reading.data);
}

}  // namespace scantling::sim
