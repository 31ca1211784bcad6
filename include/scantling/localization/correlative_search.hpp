#pragma once
/// @file
/// Global 4-DoF search of a gravity-aligned scan in a known map (x, y, z, yaw), by exhaustive
/// correlation against a likelihood field: the re-localisation that works where descriptors do
/// not. In a tank of flat plates and repeated stiffeners FPFH finds almost no correct matches
/// (0 of ~30 mutual matches on the mock-up frames; docs/results.md), while the shape of the
/// whole view still tells places apart — or says honestly that several places look alike.
///
/// Likelihood field: on a grid over the map's bounds, each cell holds the distance to the
/// nearest map point and the score exp(−d² / 2σ²); σ wider than the search step makes the
/// score smooth, so a coarse grid of poses lands in the right basin and ICP finishes.
/// Search: for every yaw step (in parallel) and every body position on a grid over the search
/// box that is at least min_clearance_m from the map (a robot is not inside a wall), the mean
/// score of the subsampled scan; the best poses, one per neighbourhood (non-maximum
/// suppression in position and yaw), are returned for verification.
///
/// Cost: O(yaws × free positions × scan points) cell lookups (~10⁷ for a 2.7 × 2.9 × 1.75 m
/// compartment at 0.2 m and 6° with 100 points: 35–90 ms on 2 threads). Deterministic for any
/// thread count.

#include <Eigen/Geometry>
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include <scantling/core/bounds.hpp>
#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>

namespace scantling::localization {

struct LikelihoodFieldConfig {
    double resolution_m = 0.1;  ///< cell edge, > 0
    double sigma_m = 0.15;      ///< score width, > 0 (about the search's translation step)
    double margin_m = 0.5;      ///< the grid covers the map's bounds grown by this, >= 0
    /// Most cells, >= 1: a map too large for the resolution is refused, not allocated.
    std::size_t max_cells = 50'000'000;
    ParallelConfig parallel;

    void validate(std::string_view prefix = "likelihood_field") const;
};

class LikelihoodField {
  public:
    LikelihoodField() = default;
    /// Throws InputError for an empty or non-finite map, ConfigError for a bad config or a
    /// grid above max_cells.
    LikelihoodField(const PointCloud& map, const LikelihoodFieldConfig& config);

    /// Score in [0, 1] at p (0 outside the grid).
    float score(const Eigen::Vector3d& p) const;
    /// Distance to the nearest map point at p, metres (0 outside the grid: treated as a wall).
    float distance(const Eigen::Vector3d& p) const;
    const Aabb& bounds() const { return bounds_; }
    bool empty() const { return size_.prod() == 0; }

  private:
    std::ptrdiff_t cell(const Eigen::Vector3d& p) const;

    Aabb bounds_;
    double inverse_resolution_ = 0.0;
    Eigen::Array3i size_ = Eigen::Array3i::Zero();
    std::vector<float> score_;
    std::vector<float> distance_;
};

struct CorrelativeSearchConfig {
    double translation_step_m = 0.2;            ///< > 0
    double yaw_step_rad = 0.10471975511965977;  ///< 6°, > 0
    /// The scan is voxel-downsampled at this size, metres, > 0, then evenly thinned to at most
    /// max_scan_points (>= 10): the view's shape, not its detail, decides the place.
    double scan_voxel_m = 0.15;
    std::size_t max_scan_points = 100;
    double min_clearance_m = 0.15;   ///< body positions closer to the map are skipped, >= 0
    std::size_t num_candidates = 8;  ///< best distinct poses returned, >= 1
    /// Two poses closer than both of these are one candidate (the better one is kept).
    double separation_m = 0.3;
    double separation_yaw_rad = 0.2617993877991494;  ///< 15°
    ParallelConfig parallel;

    void validate(std::string_view prefix = "correlative") const;
};

struct SearchCandidate {
    /// T_world_gravity: the scan's gravity-aligned frame in the world (yaw about z only).
    Eigen::Isometry3d T_world_gravity = Eigen::Isometry3d::Identity();
    double score = 0.0;  ///< mean likelihood of the scan's points, in [0, 1]
};

/// The best poses of `scan_gravity` (points in a gravity-aligned frame whose origin is the
/// body) with the body inside `search_box`, best first. Empty scan or box: no candidates.
std::vector<SearchCandidate> correlative_search(const LikelihoodField& field,
                                                const PointCloud& scan_gravity,
                                                const Aabb& search_box,
                                                const CorrelativeSearchConfig& config);

}  // namespace scantling::localization
