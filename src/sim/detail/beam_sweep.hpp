#pragma once
// Shared engine of the scanning LiDARs: a schedule of beams (directions in the sensor frame,
// grouped into firings that share a time and a pose), cast in parallel, then turned into a
// sensor-frame cloud in beam order with the return model applied serially (deterministic).

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/core/random.hpp>
#include <scantling/sim/return_model.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::sim::detail {

// A view: the sensor owns the arrays.
struct BeamSchedule {
    std::span<const Eigen::Vector3d> directions_sensor;  // unit, in firing order
    std::span<const double> firing_times_s;              // from the sweep start, one per firing
    std::size_t beams_per_firing = 1;
    std::span<const std::uint16_t> rings;  // one per beam, or empty (no ring field)
};

struct SweepSettings {
    double min_range_m = 0.0;  // nearer returns are dropped (they still occlude)
    double max_range_m = 100.0;
    ReturnModel returns{};
};

// `T_world_sensor_per_firing` holds one pose (static sweep) or one per firing.
// Points: noisy range along the beam direction in the sensor frame at the firing time;
// `stamp_s` becomes the cloud's stamp, times_s are the firing times.
PointCloud cast_schedule(const SceneView& scene, const BeamSchedule& schedule,
                         std::span<const Eigen::Isometry3d> T_world_sensor_per_firing,
                         const SweepSettings& settings, Rng& rng, double stamp_s,
                         const ParallelConfig& parallel);

// Poses at each firing of a moving sweep: T_world_body_at(sweep_start_s + t) * T_body_sensor.
std::vector<Eigen::Isometry3d> firing_poses(const PoseAtTime& T_world_body_at, double sweep_start_s,
                                            std::span<const double> firing_times_s,
                                            const Eigen::Isometry3d& T_body_sensor);

}  // namespace scantling::sim::detail
