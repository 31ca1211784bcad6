#pragma once
/// @file
/// Ray casting against a triangle mesh (Embree 3 inside; no Embree type leaks out of here).
///
/// Frames and units: rays, hits and the mesh share one frame (the world frame of the simulator),
/// metres. Embree works in single precision; to keep that error small the scene is stored
/// relative to the centre of the mesh bounds, and every hit range is then recomputed in double
/// precision against the plane of the hit triangle, so `point` lies on the triangle to ~1e-12 m
/// relative to the world size.
///
/// Triangles are double-sided: a ray hits a triangle from either side (Debian's Embree is built
/// without back-face culling), and `RayHit::normal` is turned to face the ray.
///
/// Thread-safety: all queries are const and may run concurrently from any number of threads.
/// Determinism: a query depends only on the mesh and the ray. Where two coplanar triangles
/// overlap (members welded onto walls) either may be reported, with the same range and normal.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include <scantling/core/bounds.hpp>
#include <scantling/core/parallel.hpp>
#include <scantling/core/triangle_mesh.hpp>

namespace scantling::sim {

/// A ray: `origin + t * direction` for t in [min_range_m, max_range_m].
struct Ray {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();      ///< metres
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< unit length (checked to 1e-6)
    double max_range_m = 100.0;  ///< farther surfaces are misses; may be +infinity
    double min_range_m = 0.0;    ///< nearer surfaces are ignored (e.g. a sensor on a surface)
};

/// The first surface along a ray.
struct RayHit {
    static constexpr std::uint32_t kNoTriangle = std::numeric_limits<std::uint32_t>::max();

    bool hit = false;  ///< false: nothing within [min_range_m, max_range_m]
    double range_m = std::numeric_limits<double>::infinity();  ///< distance along the ray
    Eigen::Vector3d point = Eigen::Vector3d::Zero();           ///< origin + range_m * direction
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit geometric normal, facing the ray
    std::uint32_t triangle = kNoTriangle;              ///< index into the mesh's triangles
    int surface_tag = -1;  ///< the triangle's tag (World::surface_tags), 0 when none were given
};

/// Embree BVH build quality: `High` builds ~2x slower and traces a few % faster.
enum class BuildQuality { Medium, High };

struct RayCasterConfig {
    /// BVH quality; worlds are static, so the slower, better build pays off.
    BuildQuality build_quality = BuildQuality::High;
    /// RTC_SCENE_FLAG_ROBUST: robust traversal, so that rays through the shared edge of two
    /// triangles do not slip through a closed tank wall. Measured on the 116k-triangle hull:
    /// ~15 % slower for single-ray `cast`, within noise for the packets of `cast_batch`.
    bool robust = true;
    /// Threads used by the BVH build (queries take their own ParallelConfig).
    ParallelConfig build_parallel{};

    /// Throws ConfigError naming the field ("<prefix>.build_parallel.num_threads = -1, ...").
    void validate(std::string_view prefix = "ray_caster") const;
};

/// An immutable acceleration structure over a mesh. Movable, not copyable; a moved-from
/// RayCaster may only be destroyed or assigned to.
class RayCaster {
  public:
    /// Builds the scene. `surface_tags` is empty (every tag 0) or one integer per triangle.
    /// Throws InputError for an invalid mesh (bad index, non-finite vertex) or a tag count
    /// that is neither 0 nor `mesh.num_triangles()`, ConfigError for a bad config, and Error
    /// with Embree's message when Embree fails. An empty mesh is allowed: every ray misses.
    /// Cost: O(T log T) build, memory ~100 bytes per triangle.
    explicit RayCaster(const TriangleMesh& mesh, std::span<const int> surface_tags = {},
                       const RayCasterConfig& config = {});
    ~RayCaster();
    RayCaster(RayCaster&&) noexcept;
    RayCaster& operator=(RayCaster&&) noexcept;
    RayCaster(const RayCaster&) = delete;
    RayCaster& operator=(const RayCaster&) = delete;

    /// First hit along the ray from `origin` in `unit_direction` within `max_range_m`.
    /// Throws InputError for a non-finite origin, a direction whose norm differs from 1 by more
    /// than 1e-6, or max_range_m not > 0 (NaN included). O(log T) typical.
    RayHit cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& unit_direction,
                double max_range_m) const;

    /// As above for a full Ray (also checks 0 <= min_range_m < max_range_m).
    RayHit cast(const Ray& ray) const;

    /// Casts every ray into `out[i]` (sizes must match), in parallel over chunks of rays.
    /// Consecutive rays are traced as 16-ray Embree packets (rtcIntersect16), which pays off
    /// when neighbouring rays are coherent (a sensor sweep in scan order: ~1.5x a loop of
    /// rtcIntersect1). Packets are fixed groups of 16 consecutive indices, so results (tie
    /// breaks included) do not depend on the thread count. All rays are checked first
    /// (InputError names the index).
    void cast_batch(std::span<const Ray> rays, std::span<RayHit> out,
                    const ParallelConfig& parallel = {}) const;

    /// Convenience form of `cast_batch` returning the hits.
    std::vector<RayHit> cast_batch(std::span<const Ray> rays,
                                   const ParallelConfig& parallel = {}) const;

    /// True when a surface crosses the segment from `from` to `to`, ignoring the first and
    /// last kLineOfSightMargin_m so that end points lying on surfaces (a defect, a landmark)
    /// do not block themselves. Segments shorter than twice the margin are never occluded.
    /// Throws InputError for non-finite end points.
    bool occluded(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

    /// End margin of `occluded`, metres.
    static constexpr double kLineOfSightMargin_m = 1e-4;

    std::size_t num_triangles() const;
    /// Bounds of the mesh (empty box for an empty mesh).
    const Aabb& bounds() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace scantling::sim
