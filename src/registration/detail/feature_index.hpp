#pragma once
/// @file
/// Exact nearest-neighbour search in descriptor space (private to registration).
///
/// High-dimensional descriptors defeat k-d trees (33-D FPFH: a tree query visits most leaves),
/// but their variance is concentrated: on FPFH the first principal axis holds ~90 % of it. So
/// the descriptors are rotated into their principal axes (a rotation keeps distances), sorted
/// by the first coordinate, and a query scans outward from its own first coordinate until the
/// squared gap alone exceeds its k-th best distance; each candidate's distance is summed axis
/// by axis (largest variance first) and abandoned once it exceeds that bound (partial distance
/// search). Both prunings are exact, so the result is the exact nearest neighbour in the
/// rotated frame, where distances equal the descriptor distances up to float rounding.
/// Measured on the 3DMatch pair at 0.05 m voxels (4k × 5k FPFH): ~2× faster than nanoflann's
/// k-d tree.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <scantling/registration/fpfh.hpp>

namespace scantling::registration::detail {

/// The (at most 2) nearest neighbours of one query, nearest first: indices into the indexed
/// descriptors and squared distances. Ties in distance: lower index first.
struct FeatureNeighbors {
    std::uint32_t index[2] = {0, 0};
    float distance_sq[2] = {0.0f, 0.0f};
    int count = 0;
};

/// Rotation into the principal axes of the union of `a` and `b` (rows: axes by decreasing
/// variance). Both must have the same number of rows; either may be empty.
Eigen::MatrixXf principal_axes(const FeatureMatrix& a, const FeatureMatrix& b);

/// Static index over the columns of `rotated` (descriptors already rotated by principal_axes).
/// Queries are const and thread-safe; results are deterministic.
class FeatureIndex {
  public:
    /// Descriptors per block, compared with the query together (vectorised).
    static constexpr std::size_t kLanes = 8;

    explicit FeatureIndex(const FeatureMatrix& rotated);

    /// The min(k, size) nearest indexed descriptors to `rotated_query` (rows() floats), k in
    /// {1, 2}.
    FeatureNeighbors nearest(const float* rotated_query, int k) const;

    /// True when no indexed descriptor is closer to `rotated_query` than `distance_sq` (ties:
    /// none with a lower index than `candidate`); `candidate` must be indexed, at exactly that
    /// squared distance as nearest() computes it. Much cheaper than nearest(): the search starts
    /// with the candidate's distance as its bound.
    bool is_nearest(const float* rotated_query, std::uint32_t candidate, float distance_sq) const;

    std::size_t size() const { return size_; }

  private:
    struct Best;

    /// Offers every descriptor that can beat `best` to it.
    void search(const float* rotated_query, Best& best) const;

    /// First sorted position whose first coordinate is >= x.
    std::size_t first_not_below(float x) const;
    /// Offers the descriptors of block `b` to `best`. `side` > 0: the block lies above the
    /// query's first coordinate, < 0: below, 0: the block holding the query's position. Returns
    /// false when the block, and so every block farther out on that side, is out of reach.
    bool visit_block(const float* q, std::size_t b, int side, Best& best) const;
    float coordinate(std::size_t b, std::size_t axis, std::size_t lane) const {
        return blocks_[(b * padded_dim_ + axis) * kLanes + lane];
    }

    std::size_t dim_ = 0;
    std::size_t padded_dim_ = 0;  ///< dim_ rounded up to a multiple of the check interval
    std::size_t size_ = 0;
    /// Descriptors sorted by first coordinate, in blocks of kLanes stored axis-major
    /// ([block][axis][lane]); axes padded with zeros, the last block's spare lanes with +infinity
    /// on the first axis.
    std::vector<float> blocks_;
    std::vector<std::uint32_t> ids_;  ///< original index of each sorted descriptor
};

}  // namespace scantling::registration::detail
