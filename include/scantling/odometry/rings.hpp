#pragma once
/// @file
/// Splits a LiDAR sweep into rings (one laser's scan line over the sweep), the first step of
/// LiODOM's feature extraction (SPEC §2: "an unstructured cloud must first be organised into
/// rings").
///
/// Three sources of the ring of a point:
/// - the cloud's ring field (simulator, Ouster and Velodyne drivers);
/// - the scan order, for clouds stored ring after ring in firing order (KITTI velodyne files
///   and the PCD sweeps made from them): a ring ends where the azimuth, counted from the sweep
///   start in the direction of rotation, falls back by more than half a turn. This is exact
///   even for the HDL-64E, whose lasers have per-laser vertical offsets of ~0.2 m (the
///   elevation seen from the origin drifts by h / r, 1° at 10 m) and whose KITTI sweeps are
///   motion-compensated (near returns of one laser shift by degrees): elevation bins mix rings
///   there. The sweep start is `scan_start_azimuth_rad` when set (KITTI cuts every ring at
///   azimuth 0), else the first return's azimuth; a ring whose first returns lie before it
///   (the first laser saw nothing there) loses them to the end of the previous ring. Rings
///   are numbered in file order, reversed when the file goes top to bottom; kAuto accepts
///   the order when it gives at least two segments (exactly num_rings if set) whose file
///   order follows their median elevations (|Kendall's τ| >= 0.8: a rank test, since vertical
///   beam offsets can swap neighbouring medians);
/// - clustering of the elevation angles (any order): rings are the elevation bands separated
///   by empty gaps wider than `min_ring_gap_rad`. Exact when every beam starts on the sensor
///   axis (Ouster, the simulator), approximate for sensors with vertical beam offsets.
///
/// Within a ring the points are in firing order: the cloud's own order when it sweeps the ring
/// monotonically in azimuth (as drivers, KITTI files and the simulator store it), else sorted by
/// azimuth counter-clockwise from −π. Ring 0 is the lowest elevation (core convention).
///
/// Thread-safety: pure function. Deterministic for any thread count. Cost: O(n) plus a sort of
/// each ring whose order is not a sweep; ~2 ms of one core for a 124k-point HDL-64 sweep.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>

namespace scantling::odometry {

enum class RingSource {
    kAuto,       ///< ring field if present, else scan order if the cloud keeps it, else elevation
    kRingField,  ///< the cloud's ring field (InputError when absent)
    kScanOrder,  ///< ring-major firing order, unchecked (a cloud in another order gives nonsense)
    kElevation,  ///< clustering of elevation angles
};

/// "auto", "ring_field", "scan_order", "elevation".
std::string_view to_string(RingSource source);

/// Inverse of to_string; throws ConfigError naming `field` and listing the accepted names.
RingSource ring_source_from_string(std::string_view name, std::string_view field = "source");

struct RingOrganizerConfig {
    /// Rings of the sensor, >= 0. 0 = unknown: the ring field is used when present, else the
    /// rings are detected and counted. > 0: ring field values >= num_rings are dropped; scan
    /// order is accepted (kAuto) only when it finds exactly this many rings; elevation
    /// clustering merges the closest bands or splits the widest ones to reach it.
    int num_rings = 0;
    RingSource source = RingSource::kAuto;
    /// Elevation clustering: an empty elevation band at least this wide separates two rings,
    /// radians, > 0 (one narrower than 3/4 of it never does). 0.1°: below the closest ring
    /// spacing of common sensors (HDL-64E 1/3°, Pandar64 1/6°, OS1-128 0.35°) and far above
    /// the spread of one ring of a sensor whose beams start on its axis.
    double min_ring_gap_rad = 1.7453292519943295e-3;
    /// Scan order: the azimuth where every ring starts, radians in [−π, π]; NaN = the first
    /// return's. KITTI sweeps are cut at 0: in 7 of the 16 real sweeps the top laser's first
    /// return is at 8.7°, and with NaN the other rings' returns from 0 to 8.7° (~50 each) end
    /// up at the end of the ring above.
    double scan_start_azimuth_rad = std::numeric_limits<double>::quiet_NaN();
    /// Rings (elevation bands, scan-order segments) with fewer points are outliers and are
    /// dropped, >= 1. 5: isolated returns at odd elevations are not a laser.
    int min_ring_points = 5;

    /// Throws ConfigError naming the field ("rings.num_rings = -1, expected >= 0").
    void validate(std::string_view prefix = "rings") const;
};

struct RingLayout {
    /// Per ring (0 = lowest elevation), the indices of its points in firing order.
    std::vector<std::vector<std::uint32_t>> rings;
    /// Points in no ring: non-finite, on the sensor axis (x = y = 0), ring field out of range,
    /// or in an outlier band/segment.
    std::size_t num_dropped = 0;
    /// The source actually used (never kAuto).
    RingSource source = RingSource::kRingField;
    /// atan2(y, x) of every input point (within 2e-6 rad), radians; NaN where dropped for being
    /// non-finite or on the axis. Kept because feature extraction needs it too.
    std::vector<float> azimuths_rad;
};

/// Organises `sweep` into rings. An empty or all-non-finite sweep gives no rings (no throw).
/// Throws InputError for an inconsistent cloud or kRingField without a ring field, ConfigError
/// for a bad config.
RingLayout organize_rings(const PointCloud& sweep, const RingOrganizerConfig& config = {},
                          const ParallelConfig& parallel = {});

}  // namespace scantling::odometry
