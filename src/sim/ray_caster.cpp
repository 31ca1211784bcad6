#include <scantling/core/error.hpp>
#include <scantling/sim/ray_caster.hpp>

#include "detail/embree_scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace scantling::sim {
namespace {

constexpr double kUnitNormTolerance = 1e-6;
constexpr std::size_t kPacketSize = detail::EmbreeScene::kPacketSize;
// Packets per parallel chunk (256 rays): hides the scheduling cost (~1 µs) behind ~20 µs of
// tracing.
constexpr std::size_t kPacketsPerChunk = 16;

bool is_finite(const Eigen::Vector3d& v) { return v.allFinite(); }

// Empty when the ray is usable, else what is wrong with it (formatted only on failure, so that
// checking a million-ray batch stays cheap).
std::string ray_problem(const Ray& ray) {
    if (!is_finite(ray.origin)) return "origin is not finite";
    const double norm = ray.direction.norm();
    if (!std::isfinite(norm) || std::abs(norm - 1.0) > kUnitNormTolerance) {
        return fmt::format("|direction| = {}, expected 1", norm);
    }
    if (!(ray.min_range_m >= 0.0) || !std::isfinite(ray.min_range_m)) {
        return fmt::format("min_range_m = {}, expected finite >= 0", ray.min_range_m);
    }
    if (!(ray.max_range_m > ray.min_range_m)) {
        return fmt::format("max_range_m = {}, expected > min_range_m = {}", ray.max_range_m,
                           ray.min_range_m);
    }
    return {};
}

bool ray_ok(const Ray& ray) {
    return is_finite(ray.origin) && std::abs(ray.direction.norm() - 1.0) <= kUnitNormTolerance &&
           ray.min_range_m >= 0.0 && std::isfinite(ray.min_range_m) &&
           ray.max_range_m > ray.min_range_m;
}

}  // namespace

void RayCasterConfig::validate(std::string_view prefix) const {
    if (build_quality != BuildQuality::Medium && build_quality != BuildQuality::High) {
        throw ConfigError(fmt::format("{}.build_quality = {}, expected medium or high", prefix,
                                      static_cast<int>(build_quality)));
    }
    build_parallel.validate(fmt::format("{}.build_parallel", prefix));
}

struct RayCaster::Impl : detail::EmbreeScene {
    using EmbreeScene::EmbreeScene;
};

RayCaster::RayCaster(const TriangleMesh& mesh, std::span<const int> surface_tags,
                     const RayCasterConfig& config) {
    config.validate();
    check_valid(mesh, "RayCaster mesh");
    if (!surface_tags.empty() && surface_tags.size() != mesh.num_triangles()) {
        throw InputError(
            fmt::format("RayCaster: {} surface tags for {} triangles, expected 0 or "
                        "one per triangle",
                        surface_tags.size(), mesh.num_triangles()));
    }
    impl_ = std::make_unique<Impl>(mesh, surface_tags, config);
}

RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

RayHit RayCaster::cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& unit_direction,
                       double max_range_m) const {
    return cast(Ray{origin, unit_direction, max_range_m, 0.0});
}

RayHit RayCaster::cast(const Ray& ray) const {
    if (!ray_ok(ray)) throw InputError("RayCaster::cast: " + ray_problem(ray));
    return impl_->cast(ray);
}

void RayCaster::cast_batch(std::span<const Ray> rays, std::span<RayHit> out,
                           const ParallelConfig& parallel) const {
    if (rays.size() != out.size()) {
        throw InputError(
            fmt::format("RayCaster::cast_batch: {} rays but {} outputs", rays.size(), out.size()));
    }
    parallel.validate("cast_batch.parallel");
    // Checked in parallel chunks too (a serial pre-pass over every ray would cap the batch's
    // 2-thread speed-up); the first bad ray is named whatever the thread count.
    const std::size_t first_bad = parallel_reduce_ordered(
        parallel, rays.size(), kPacketSize * kPacketsPerChunk, rays.size(),
        [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
                if (!ray_ok(rays[i])) return i;
            }
            return rays.size();
        },
        [](std::size_t a, std::size_t b) { return std::min(a, b); });
    if (first_bad < rays.size()) {
        throw InputError(fmt::format("RayCaster::cast_batch: ray {}: {}", first_bad,
                                     ray_problem(rays[first_bad])));
    }
    const Impl& impl = *impl_;
    // Work is split into fixed packets of consecutive rays, so which rays share a packet (and
    // hence any tie-break between coplanar overlapping triangles) never depends on threads.
    const std::size_t packets = (rays.size() + kPacketSize - 1) / kPacketSize;
    parallel_for(parallel, packets, kPacketsPerChunk, [&](std::size_t begin, std::size_t end) {
        for (std::size_t p = begin; p < end; ++p) {
            const std::size_t first = p * kPacketSize;
            const std::size_t n = std::min(kPacketSize, rays.size() - first);
            impl.cast_packet(rays.subspan(first, n), out.subspan(first, n));
        }
    });
}

std::vector<RayHit> RayCaster::cast_batch(std::span<const Ray> rays,
                                          const ParallelConfig& parallel) const {
    std::vector<RayHit> out(rays.size());
    cast_batch(rays, out, parallel);
    return out;
}

bool RayCaster::occluded(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
    if (!is_finite(from) || !is_finite(to)) {
        throw InputError("RayCaster::occluded: end point is not finite");
    }
    return impl_->occluded(from, to);
}

std::size_t RayCaster::num_triangles() const { return impl_->num_triangles(); }

const Aabb& RayCaster::bounds() const { return impl_->bounds(); }

}  // namespace scantling::sim
