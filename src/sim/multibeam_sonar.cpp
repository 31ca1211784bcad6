#include <scantling/sim/multibeam_sonar.hpp>

#include "detail/sensor_checks.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scantling::sim {
namespace {

// Beams that share one speckle sub-stream: fixed, so streams do not depend on thread counts;
// large enough that seeding a stream (a Mersenne Twister state) costs little per cell.
constexpr std::size_t kBeamsPerStream = 16;

// Angle of sample k of n spread evenly over [−fov/2, fov/2] (sample centres).
double sample_angle(double fov_rad, int k, int n) {
    return -0.5 * fov_rad + fov_rad * (k + 0.5) / n;
}

// Usable length of a ray before it leaves the water (the surface reflects nothing back here).
double in_water_range(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                      double max_range_m, double surface_z_m) {
    if (origin.z() >= surface_z_m) return 0.0;
    if (direction.z() <= 0.0) return max_range_m;
    return std::min(max_range_m, (surface_z_m - origin.z()) / direction.z());
}

}  // namespace

void MultibeamSonarConfig::validate(std::string_view prefix) const {
    detail::require(num_beams >= 1 && num_beams <= 4096, prefix, "num_beams", num_beams,
                    "in [1, 4096]");
    detail::require(num_bins >= 1 && num_bins <= 8192, prefix, "num_bins", num_bins,
                    "in [1, 8192]");
    detail::require(rays_per_beam >= 1 && rays_per_beam <= 256, prefix, "rays_per_beam",
                    rays_per_beam, "in [1, 256]");
    detail::require(horizontal_fov_rad > 0.0 && horizontal_fov_rad <= std::numbers::pi, prefix,
                    "horizontal_fov_rad", horizontal_fov_rad, "in (0, pi]");
    detail::require_angle(prefix, "vertical_fov_rad", vertical_fov_rad, std::numbers::pi / 2.0);
    detail::require_range_window(prefix, min_range_m, max_range_m);
    detail::require_positive(prefix, "rate_hz", rate_hz);
    detail::require_non_negative(prefix, "gain", gain);
    detail::require_non_negative(prefix, "noise_floor", noise_floor);
    detail::require_non_negative(prefix, "incidence_exponent", incidence_exponent);
    detail::require_non_negative(prefix, "spreading_exponent", spreading_exponent);
    detail::require_non_negative(prefix, "absorption_db_per_m", absorption_db_per_m);
    detail::require(!std::isnan(water_surface_z_m) && water_surface_z_m > -1e300, prefix,
                    "water_surface_z_m", water_surface_z_m, "a number or +inf");
    validate_mount(T_body_sensor, prefix);
}

MultibeamSonar::MultibeamSonar(MultibeamSonarConfig config) : config_(std::move(config)) {
    config_.validate();
    rays_sensor_.reserve(static_cast<std::size_t>(config_.num_beams) * config_.rays_per_beam);
    for (int b = 0; b < config_.num_beams; ++b) {
        const double bearing = sample_angle(config_.horizontal_fov_rad, b, config_.num_beams);
        for (int k = 0; k < config_.rays_per_beam; ++k) {
            const double elevation =
                sample_angle(config_.vertical_fov_rad, k, config_.rays_per_beam);
            rays_sensor_.emplace_back(std::cos(elevation) * std::cos(bearing),
                                      std::cos(elevation) * std::sin(bearing), std::sin(elevation));
        }
    }
}

double MultibeamSonar::echo_power(double albedo, double cos_incidence, double range_m) const {
    const double spreading = std::pow(1.0 / range_m, config_.spreading_exponent);
    const double absorption = std::pow(10.0, -config_.absorption_db_per_m * 2.0 * range_m / 10.0);
    return albedo * std::pow(std::max(0.0, cos_incidence), config_.incidence_exponent) * spreading *
           absorption;
}

std::vector<double> MultibeamSonar::signal_power(const SceneView& scene,
                                                 const Eigen::Isometry3d& T_world_sensor,
                                                 const ParallelConfig& parallel) const {
    std::vector<Ray> rays;
    std::vector<std::size_t> ray_index;  // into rays_sensor_ (rays out of the water skipped)
    rays.reserve(rays_sensor_.size());
    ray_index.reserve(rays_sensor_.size());
    for (std::size_t i = 0; i < rays_sensor_.size(); ++i) {
        const Eigen::Vector3d d = (T_world_sensor.linear() * rays_sensor_[i]).normalized();
        const double range_m = in_water_range(T_world_sensor.translation(), d, config_.max_range_m,
                                              config_.water_surface_z_m);
        if (range_m <= config_.min_range_m) continue;
        rays.push_back(Ray{T_world_sensor.translation(), d, range_m, 0.0});
        ray_index.push_back(i);
    }
    const std::vector<RayHit> hits = scene.cast_batch(rays, parallel);
    const double bin_m = (config_.max_range_m - config_.min_range_m) / config_.num_bins;
    std::vector<double> power(static_cast<std::size_t>(config_.num_beams) * config_.num_bins, 0.0);
    for (std::size_t h = 0; h < hits.size(); ++h) {
        const RayHit& hit = hits[h];
        if (!hit.hit || hit.range_m < config_.min_range_m) continue;
        const int bin = std::min(config_.num_bins - 1,
                                 static_cast<int>((hit.range_m - config_.min_range_m) / bin_m));
        const std::size_t beam = ray_index[h] / config_.rays_per_beam;
        const double albedo = surface_of(scene.metadata, hit.surface_tag).albedo;
        power[beam * config_.num_bins + bin] +=
            echo_power(albedo, -rays[h].direction.dot(hit.normal), hit.range_m) /
            config_.rays_per_beam;
    }
    return power;
}

SonarImage MultibeamSonar::empty_image(double stamp_s) const {
    SonarImage image;
    image.stamp_s = stamp_s;
    image.num_beams = config_.num_beams;
    image.num_bins = config_.num_bins;
    image.min_range_m = config_.min_range_m;
    image.max_range_m = config_.max_range_m;
    image.horizontal_fov_rad = config_.horizontal_fov_rad;
    for (int b = 0; b < config_.num_beams; ++b) {
        image.bearings_rad.push_back(
            sample_angle(config_.horizontal_fov_rad, b, config_.num_beams));
    }
    const double bin_m = (config_.max_range_m - config_.min_range_m) / config_.num_bins;
    for (int j = 0; j < config_.num_bins; ++j) {
        image.ranges_m.push_back(config_.min_range_m + (j + 0.5) * bin_m);
    }
    return image;
}

SonarImage MultibeamSonar::scan(const SceneView& scene, const Eigen::Isometry3d& T_world_body,
                                Rng& rng, double stamp_s, const ParallelConfig& parallel) const {
    const Eigen::Isometry3d T_world_sensor = T_world_body * config_.T_body_sensor;
    const std::vector<double> signal = signal_power(scene, T_world_sensor, parallel);
    SonarImage image = empty_image(stamp_s);
    image.intensity.resize(signal.size());
    // One draw per ping seeds one sub-stream per fixed group of beams, so groups can be filled
    // in parallel and the result does not depend on the thread count.
    const Rng ping(rng.next_u64());
    const std::size_t cells_per_stream = kBeamsPerStream * config_.num_bins;
    const std::size_t streams = (signal.size() + cells_per_stream - 1) / cells_per_stream;
    const float floor_amplitude = amplitude(0.0, 1.0);
    parallel_for(parallel, streams, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t stream = begin; stream < end; ++stream) {
            Rng stream_rng = ping.split(stream);
            const std::size_t last = std::min(signal.size(), (stream + 1) * cells_per_stream);
            for (std::size_t i = stream * cells_per_stream; i < last; ++i) {
                const double speckle =
                    config_.speckle ? -std::log(1.0 - stream_rng.uniform()) : 1.0;
                image.intensity[i] = signal[i] == 0.0 && !config_.speckle
                                         ? floor_amplitude
                                         : amplitude(signal[i], speckle);
            }
        }
    });
    return image;
}

io::SonarPing to_sonar_ping(const SonarImage& image) {
    io::SonarPing ping;
    ping.stamp_s = image.stamp_s;
    ping.num_beams = image.num_beams;
    ping.num_bins = image.num_bins;
    ping.intensity = image.intensity;
    ping.bearings_rad = image.bearings_rad;
    ping.ranges_m = image.ranges_m;
    ping.min_range_m = image.min_range_m;
    ping.max_range_m = image.max_range_m;
    ping.horizontal_fov_rad = image.horizontal_fov_rad;
    return ping;
}

float MultibeamSonar::amplitude(double signal_power, double speckle) const {
    return static_cast<float>(config_.gain *
                              std::sqrt((signal_power + config_.noise_floor) * speckle));
}

}  // namespace scantling::sim
