#pragma once
/// @file
/// LiODOM edge features (SPEC §2, [D4.2 §II.2], LOAM [Zhang & Singh, RSS 2014] §V-A).
///
/// Per sweep: rings (rings.hpp) → range gate [r_min, r_max] (|p| in the sensor frame; non-finite
/// points dropped) → LOAM curvature along each ring → per ring, `num_sectors` sectors of equal
/// index span, each keeping its `max_edges_per_sector` highest-curvature points above
/// `min_edge_curvature`, with neighbour suppression.
///
/// Neighbourhoods. The in-range points of a ring are cut into segments wherever two
/// consecutive ones are not neighbours on one surface: returns are missing between them (the
/// azimuth step exceeds `max_azimuth_gap_factor` × the ring's median step), returns outside
/// the gate lie between them, or the range jumps by more than `range_jump_ratio` × the nearer
/// range. The curvature of point i uses the h = `curvature_half_window` points on each side
/// within its segment (LOAM's full window; points with fewer get none):
///   c_i = |Σ_{j ∈ S} (x_j − x_i)|² / (|S| · |x_i|)²,   |S| = 2h,
/// the square of the LOAM paper's c: dimensionless and independent of range. LOAM's released
/// code and its descendants (A-LOAM, F-LOAM, LiODOM) use |Σ (x_j − x_i)|² in m² with threshold
/// 0.1, which grows with r²: a 90° corner reaches 0.1 m² only beyond ~5 m on an HDL-64E and
/// ~2.3 m on an OS1-1024, too far for a tank a few metres wide.
///
/// Each segment end faces what lies across its boundary: missing returns or a return farther
/// by more than the jump ratio make it a silhouette (the outline of an object against what is
/// behind it: poles, frames, flange edges, roof lines against the sky); a nearer one makes it
/// occluded; a return at about the same range (a surface leaving the gate) a plain cut. The
/// window of a silhouette runs across the boundary, as in LOAM, which is what makes it stand
/// out.
///
/// Measured on the 16 real sweeps ("matching": an edge of sweep i+1, moved by the GICP motion
/// between the sweeps, lies within 0.1 m of the line through its 5 nearest edges of sweep i,
/// which lie within 1 m and form a line, λ1 > 3 λ2): with the defaults 3180 edges per sweep,
/// 1041 matching (32.7 %); without silhouettes 685 (23.6 %).
///
/// Unreliable points (`reject_unreliable`, LOAM §V-A): occluded ends and the h points behind
/// them (the end moves with the viewpoint); and points of a receding surface whose range
/// changes towards both adjacent returns by more than tan(`max_incidence_rad`) · r · Δφ
/// (incidence above max_incidence: the beam nearly parallel to the surface).
///
/// Selection: within a sector, candidates by curvature (descending; ties by position), at most
/// N; a pick suppresses the h points on each side within its segment (LOAM: not across a large
/// jump). Output in ring order, then firing order within the ring; deterministic for any thread
/// count (rings are processed in parallel into per-ring buffers).
///
/// Thread-safety: pure function. Cost: O(n) plus a heap of each sector's candidates; ~6 ms of
/// one core for a 124k-point HDL-64 sweep, ring organisation (~2 ms) included.

#include <Eigen/Core>
#include <cstddef>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/odometry/rings.hpp>

namespace scantling::odometry {

struct EdgeExtractionConfig {
    /// Range gate r_min, r_max on |p| in the sensor frame, metres, 0 <= r_min < r_max. 3–75 m:
    /// LiODOM's defaults for 64-beam automotive sweeps (the KITTI preset); presets override.
    double min_range_m = 3.0;
    double max_range_m = 75.0;
    /// Neighbours on each side in the curvature (LOAM: 5), >= 1.
    int curvature_half_window = 5;
    /// Sectors per ring, of equal index span (LOAM: 6), >= 1.
    int num_sectors = 6;
    /// Most edges per sector, N (LiODOM: 10), >= 1.
    int max_edges_per_sector = 10;
    /// Smallest curvature c (see the file comment) of an edge, >= 0. A bend of interior angle
    /// α at azimuth step Δφ gives c ≈ 2.25 Δφ² (2 cos(α/2))² (90°: 4.5 Δφ²); flat surfaces give
    /// ≈ 1.1 (σ/r)² of noise σ. 2e-5 keeps 90° corners of an HDL-64E (Δφ = 0.17°, 4e-5) and is
    /// above the median of its flat surfaces (1.5e-6); on the real sweeps, 1e-5…1e-4 changed
    /// the edge count (3615…2658), not the matching share (32.5–33.1 %). Finer resolutions or
    /// short ranges (tanks, OS1: a 90° corner is 1.7e-4, noise at 2 m 6e-5) need more.
    double min_edge_curvature = 2e-5;
    /// A neighbour farther in azimuth than this many times the ring's median azimuth step is
    /// not adjacent (returns are missing between them), > 1. On the real sweeps 2.5, 5, 10 and
    /// 20 gave 31.7, 32.7, 33.4 and 33.7 % matching edges; 5 keeps a flat wall with a few
    /// missing returns from looking bent (a gap of g steps adds ≈ (g/2)² Δφ² to c).
    double max_azimuth_gap_factor = 5.0;
    /// A range change larger than this fraction of the nearer range is an occlusion boundary,
    /// > 0. 0.1: a surface must be within ~2° of the beam to change this much between adjacent
    /// returns of an OS1-1024 (4° for an HDL-64E), so this is a real depth discontinuity (real
    /// sweeps: 0.05, 0.1, 0.2 gave 33.1, 32.7, 31.8 % matching edges).
    double range_jump_ratio = 0.1;
    /// Reject occluded points and points on surfaces nearly parallel to the beam (LOAM).
    bool reject_unreliable = true;
    /// Incidence (angle between beam and surface normal, along the ring) above which a point on
    /// a receding surface is "parallel to the beam", radians, in (0, π/2). 80°: LOAM's test
    /// (neighbour distance > 1.4 % of the range) at an HDL-64E's azimuth step.
    double max_incidence_rad = 1.3962634015954636;
    /// Planar points per sector beside the edges (LOAM's "flat" points: the lowest curvature,
    /// registered point-to-plane), >= 0; 0 = edges only (LiODOM). Edges along rings are mostly
    /// vertical structure, which leaves height, roll and pitch weakly observed; planar points
    /// (the ground, walls) constrain exactly those.
    int max_planes_per_sector = 0;
    /// Largest curvature c of a planar point, >= 0 (flat surfaces of an HDL-64E: median 1.5e-6).
    double max_plane_curvature = 5e-6;
    RingOrganizerConfig rings{};
    ParallelConfig parallel{};  ///< threads over rings (ring organisation and extraction)

    /// Throws ConfigError naming the field ("features.min_range_m = 5, expected < max_range_m
    /// = 3").
    void validate(std::string_view prefix = "features") const;
};

struct EdgeFeatures {
    std::vector<Eigen::Vector3d> points;  ///< sensor frame, as in the sweep
    std::vector<double> ranges_m;         ///< |p| in the sensor frame (for the weight ω)
    std::vector<double> times_s;          ///< per-point time when the sweep has it, else empty
    std::vector<float> curvatures;        ///< c of each edge (dimensionless)
    /// Planar points (sensor frame) and their ranges, when max_planes_per_sector > 0.
    std::vector<Eigen::Vector3d> plane_points;
    std::vector<double> plane_ranges_m;
    std::size_t num_input = 0;     ///< points in the sweep
    std::size_t num_in_range = 0;  ///< finite points in a ring and in [r_min, r_max]
    std::size_t num_rings = 0;     ///< rings found (rings.hpp)

    std::size_t size() const { return points.size(); }
    bool empty() const { return points.empty(); }
};

/// Extracts the edges of one sweep (sensor frame). An empty or all-NaN sweep gives no edges.
/// Throws ConfigError for a bad config and InputError for an inconsistent cloud (or
/// rings.source = ring_field without a ring field).
EdgeFeatures extract_edges(const PointCloud& sweep, const EdgeExtractionConfig& config = {});

}  // namespace scantling::odometry
