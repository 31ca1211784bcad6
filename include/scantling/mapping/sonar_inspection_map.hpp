#pragma once
/// @file
/// The ROV's sonar inspection map (SPEC §5; issue 14 item 4): the reliable sonar features of
/// every ping, already in the world frame, accumulated into cubic voxels. A voxel "exists" only
/// when enough reliable points fell into it; each existing voxel carries its mean, covariance and
/// an uncertainty for the operator. `coverage_of` (hull_coverage.hpp) grids a planar rectangle of
/// the hull and finds the holes the planner re-inspects.
///
/// Frame: world (metres). Voxel key = floor(p / voxel_size_m) per axis (mapping::CellKey).
/// Thread-safety: const members may run concurrently; add and clear need exclusive access.
/// @note Deterministic: voxels() is sorted by voxel key,
/// independent of the hash table. Per-voxel statistics are running (Welford) sums, so the same
/// points in another order give the same counts and the same means up to rounding (~1e-15 m).

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <scantling/mapping/cell_hash.hpp>

namespace scantling::mapping {

struct SonarInspectionMapConfig {
    /// Voxel edge, metres, finite > 0. 0.2 m: a few sonar beams' footprint at the 1-1.3 m
    /// stand-off of SPEC §5, small against the hull's curvature (locally flat, SPEC §5).
    double voxel_size_m = 0.2;
    /// A voxel exists only with at least this many reliable points (SPEC §5), >= 3 (a plane's
    /// normal needs three points). 5: two pings' worth at the beam density of a 0.2 m voxel.
    std::size_t min_points_per_voxel = 5;
    /// Points whose 1σ exceeds this are rejected as unreliable (counted, never stored), metres,
    /// finite > 0. Half a voxel: a less certain point cannot be trusted to fall in its voxel.
    double max_point_sigma_m = 0.1;
    /// Memory bound: voxels stored (existing or still short of min_points_per_voxel), >= 1.
    /// A reliable point that would open a voxel beyond it is refused and counted. 2e5 voxels
    /// (~40 MB) hold 50 surveys of a 30 × 5 m hull section at 0.2 m.
    std::size_t max_voxels = 200'000;

    /// Throws ConfigError("<prefix>.voxel_size_m = -1, expected finite > 0").
    void validate(std::string_view prefix = "sonar_map") const;
};

/// What one add() did; added + rejected_unreliable + refused_memory = points given.
struct SonarAddResult {
    std::size_t added = 0;                ///< points accumulated into voxels
    std::size_t rejected_unreliable = 0;  ///< sigma_m > max_point_sigma_m, not counted
    std::size_t refused_memory = 0;       ///< would have opened a voxel beyond max_voxels
    std::size_t voxels_created = 0;       ///< voxels stored for the first time
};

/// One existing voxel, for reports and for coverage.
struct SonarVoxel {
    CellKey key;
    std::size_t num_points = 0;
    Eigen::Vector3d mean_world_m = Eigen::Vector3d::Zero();
    /// Sample covariance S of the points (divided by n − 1), m².
    Eigen::Matrix3d covariance_m2 = Eigen::Matrix3d::Zero();
    /// Covariance of the mean position, S / n (the standard error, squared), m².
    Eigen::Matrix3d mean_covariance_m2 = Eigen::Matrix3d::Zero();
    /// Unit eigenvector of S's smallest eigenvalue λ_min: the local hull normal (sign arbitrary).
    Eigen::Vector3d normal_world = Eigen::Vector3d::UnitZ();
    /// sqrt(λ_min): the points' scatter across the locally flat hull (≈ the range noise), m.
    double normal_spread_m = 0.0;
    double mean_point_sigma_m = 0.0;  ///< mean of the points' 1σ, m
    /// Uncertainty of the hull position in this voxel, along its normal, metres:
    ///   sqrt(λ_min / n + mean_point_sigma_m²).
    /// The first term is the standard error of the mean across the surface (the random scatter
    /// averages down with n); the point sigma is added undivided because its main part, the
    /// vehicle pose error, is shared by the points of a pass and does not average down.
    double uncertainty_m = 0.0;
    double first_stamp_s = 0.0;  ///< earliest stamp of the voxel's points
    double last_stamp_s = 0.0;   ///< latest stamp of the voxel's points
};

class SonarInspectionMap {
  public:
    /// Throws ConfigError for an invalid config.
    explicit SonarInspectionMap(const SonarInspectionMapConfig& config = {});

    const SonarInspectionMapConfig& config() const { return config_; }

    /// Accumulates one ping's features. `sigma_m[i]` is the 1σ of `points_world[i]`, metres.
    /// Throws InputError, before changing anything, naming the field ("points_world[3]",
    /// "sigma_m", "stamp_s") for a size mismatch, a non-finite point, sigma or stamp, a negative
    /// sigma or a point whose voxel index overflows int32. O(n) expected.
    SonarAddResult add(std::span<const Eigen::Vector3d> points_world,
                       std::span<const double> sigma_m, double stamp_s);

    /// Voxel of a finite point (floor per axis). Throws InputError as add().
    CellKey key_of(const Eigen::Vector3d& p_world) const;

    /// The existing voxels (>= min_points_per_voxel points), sorted by key. O(v log v).
    std::vector<SonarVoxel> voxels() const;

    std::size_t num_existing_voxels() const;                          ///< O(v)
    std::size_t num_stored_voxels() const { return voxels_.size(); }  ///< memory bound counts
    std::size_t num_points() const { return num_points_; }            ///< reliable points added

    /// Removes every voxel; keeps the configuration.
    void clear();

  private:
    struct Accumulator {
        std::size_t n = 0;
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        Eigen::Matrix3d m2 = Eigen::Matrix3d::Zero();  ///< Σ (p − mean)(p − mean)ᵀ (Welford)
        double sigma_sum_m = 0.0;
        double first_stamp_s = 0.0;
        double last_stamp_s = 0.0;
    };

    void check_input(std::span<const Eigen::Vector3d> points_world, std::span<const double> sigma_m,
                     double stamp_s) const;

    SonarInspectionMapConfig config_;
    std::unordered_map<CellKey, Accumulator, CellKeyHash> voxels_;
    std::size_t num_points_ = 0;
};

}  // namespace scantling::mapping
