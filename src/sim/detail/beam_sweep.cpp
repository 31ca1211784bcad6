#include "beam_sweep.hpp"

#include <scantling/core/error.hpp>

#include <fmt/format.h>

namespace scantling::sim::detail {
namespace {

std::vector<Ray> build_rays(const BeamSchedule& schedule, std::span<const Eigen::Isometry3d> poses,
                            double max_range_m) {
    const std::size_t n = schedule.directions_sensor.size();
    std::vector<Ray> rays(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Isometry3d& T =
            poses.size() == 1 ? poses[0] : poses[i / schedule.beams_per_firing];
        // Renormalise: a pose from an interpolated trajectory may carry rounding in R.
        rays[i] = Ray{T.translation(), (T.linear() * schedule.directions_sensor[i]).normalized(),
                      max_range_m, 0.0};
    }
    return rays;
}

void check_poses(const BeamSchedule& schedule, std::span<const Eigen::Isometry3d> poses) {
    const std::size_t firings = schedule.firing_times_s.size();
    if (poses.size() != 1 && poses.size() != firings) {
        throw InputError(fmt::format("sensor sweep: {} poses for {} firings, expected 1 or {}",
                                     poses.size(), firings, firings));
    }
    for (std::size_t f = 0; f < poses.size(); ++f) {
        if (!poses[f].matrix().allFinite()) {
            throw InputError(fmt::format("sensor sweep: pose of firing {} is not finite", f));
        }
    }
}

PointCloud empty_cloud(const BeamSchedule& schedule, double stamp_s) {
    PointCloud cloud;
    cloud.stamp_s = stamp_s;
    const std::size_t n = schedule.directions_sensor.size();
    cloud.points.reserve(n);
    cloud.intensities.reserve(n);
    cloud.times_s.reserve(n);
    if (!schedule.rings.empty()) cloud.rings.reserve(n);
    return cloud;
}

}  // namespace

PointCloud cast_schedule(const SceneView& scene, const BeamSchedule& schedule,
                         std::span<const Eigen::Isometry3d> T_world_sensor_per_firing,
                         const SweepSettings& settings, Rng& rng, double stamp_s,
                         const ParallelConfig& parallel) {
    check_poses(schedule, T_world_sensor_per_firing);
    const std::vector<Ray> rays =
        build_rays(schedule, T_world_sensor_per_firing, settings.max_range_m);
    const std::vector<RayHit> hits = scene.cast_batch(rays, parallel);
    PointCloud cloud = empty_cloud(schedule, stamp_s);
    for (std::size_t i = 0; i < hits.size(); ++i) {
        const RayHit& hit = hits[i];
        if (!hit.hit || hit.range_m < settings.min_range_m) continue;
        const double rho = lambertian_reflectivity(
            surface_of(scene.metadata, hit.surface_tag).albedo, rays[i].direction, hit.normal);
        const ReturnSample sample = sample_return(settings.returns, hit.range_m, rho, rng);
        if (!sample.kept) continue;
        cloud.points.push_back(sample.distance_m * schedule.directions_sensor[i]);
        cloud.intensities.push_back(static_cast<float>(rho));
        cloud.times_s.push_back(
            static_cast<float>(schedule.firing_times_s[i / schedule.beams_per_firing]));
        if (!schedule.rings.empty()) cloud.rings.push_back(schedule.rings[i]);
    }
    return cloud;
}

std::vector<Eigen::Isometry3d> firing_poses(const PoseAtTime& T_world_body_at, double sweep_start_s,
                                            std::span<const double> firing_times_s,
                                            const Eigen::Isometry3d& T_body_sensor) {
    if (!T_world_body_at) throw InputError("sensor sweep: the pose function is empty");
    std::vector<Eigen::Isometry3d> poses(firing_times_s.size());
    for (std::size_t f = 0; f < poses.size(); ++f) {
        poses[f] = T_world_body_at(sweep_start_s + firing_times_s[f]) * T_body_sensor;
    }
    return poses;
}

}  // namespace scantling::sim::detail
