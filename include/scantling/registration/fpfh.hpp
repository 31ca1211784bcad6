#pragma once
/// @file
/// Fast Point Feature Histograms (FPFH, Rusu, Blodow & Beetz, ICRA 2009), computed as in
/// Open3D's ComputeFPFHFeature and PCL's FPFHEstimation.
///
/// For a point p with normal n and each neighbour q (normal m) within `radius_m`, the Darboux
/// frame of the pair gives three angle features: alpha = v·m, phi = u·(q − p)/|q − p| and
/// theta = atan2(w·m, u·m), with u = n (or m, whichever makes the smaller angle with the line
/// between them), v = (q − p) × u normalised, w = u × v. Each feature is binned into 11 bins;
/// the 3 × 11 histogram normalised to 100 per feature is the point's SPFH. The FPFH of p is its
/// SPFH plus the weighted mean of its neighbours' SPFHs, weight 1/distance (paper, PCL) or
/// 1/distance² (Open3D), each 11-bin block renormalised to 100.
///
/// Invariance: the features depend only on distances and angles between points and normals, so
/// they are invariant to rigid transforms of the cloud (normals transformed with it). One
/// deviation from Open3D makes that hold exactly: when both normals make the same angle with
/// the line (|cos| equal within 1e-12, typical of neighbours with bit-identical normals), p stays
/// the frame's source, where Open3D's choice (and the sign of phi) follows rounding noise. With
/// FpfhWeighting::kInverseSquaredDistance the values otherwise equal Open3D's (0.03 % of the
/// pairs differ on the 3DMatch pair, all such ties).
///
/// Cost: one radius search per point (O(log n + k)) and 2k pair evaluations, k <= max_neighbors.
/// Thread-safety: pure function of its inputs.
/// @note Deterministic: each point's histogram depends only on its own neighbourhood, so 1 and
/// N threads give bit-identical features.

#include <Eigen/Core>
#include <string_view>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>

namespace scantling::registration {

/// Descriptors of a cloud, one column per point (33 rows for FPFH; any other descriptor, e.g. a
/// learned one, can be stored the same way for matching). Floats: descriptors are compared by
/// distance only, and half the memory makes the feature-space search faster.
using FeatureMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic>;

/// Rows of an FPFH descriptor: 3 angle features × 11 bins.
inline constexpr int kFpfhDimension = 33;

/// How neighbours' SPFHs are weighted in the FPFH sum.
enum class FpfhWeighting {
    kInverseDistance,         ///< 1/|q − p|: Rusu 2009 and PCL
    kInverseSquaredDistance,  ///< 1/|q − p|²: Open3D (to reproduce its values exactly)
};

struct FpfhConfig {
    /// Neighbourhood radius, metres, > 0. Typically 5× the voxel size the cloud was downsampled
    /// with (Open3D's and TEASER++'s examples; 0.25 m for SPEC §7's 0.05 m voxels): the
    /// neighbourhood must hold enough points (~50–100) for stable histograms, and the surface
    /// patch must be larger than the noise yet smaller than the structures that distinguish
    /// places.
    double radius_m = 0.25;
    /// Most neighbours per point, the point itself included (Open3D's KDTreeSearchParamHybrid
    /// max_nn), >= 2: the nearest ones are kept. Bounds the cost on dense clouds; 100 as in
    /// Open3D's and TEASER++'s examples.
    int max_neighbors = 100;
    FpfhWeighting weighting = FpfhWeighting::kInverseDistance;  ///< see FpfhWeighting
    ParallelConfig parallel;  ///< threads for the per-point histograms

    /// Throws ConfigError("<prefix>.radius_m = 0, expected finite > 0").
    void validate(std::string_view prefix = "fpfh") const;
};

/// FPFH of every point of `cloud`, which must carry unit normals (core/normals.hpp) in the same
/// frame as the points. Returns a 33 × n matrix; a point without neighbours within the radius
/// gets an all-zero column. Neighbours at distance 0 (duplicates) are skipped.
/// Throws InputError when the cloud is empty, inconsistent, non-finite or has no normals;
/// ConfigError on a bad config.
FeatureMatrix compute_fpfh(const PointCloud& cloud, const FpfhConfig& config = {});

/// Same, reusing `tree`, built over exactly `cloud.points` (InputError if the sizes differ).
FeatureMatrix compute_fpfh(const PointCloud& cloud, const KdTree& tree, const FpfhConfig& config);

}  // namespace scantling::registration
