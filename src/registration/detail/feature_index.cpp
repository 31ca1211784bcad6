#include "feature_index.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <limits>
#include <numeric>

namespace scantling::registration::detail {
namespace {

// Axes summed between two partial-distance tests: on FPFH the first four principal axes hold
// ~95 % of the variance, so most blocks stop after the first group.
constexpr std::size_t kCheckEvery = 4;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::uint32_t kPadding = std::numeric_limits<std::uint32_t>::max();

bool lexicographic_less(float d, std::uint32_t id, float other_d, std::uint32_t other_id) {
    return d < other_d || (d == other_d && id < other_id);
}

}  // namespace

/// The k best (distance, index) pairs so far, ordered lexicographically.
struct FeatureIndex::Best {
    int k = 1;
    FeatureNeighbors n;

    float bound() const {
        if (n.count < k) return kInf;
        return n.distance_sq[k - 1];
    }

    void offer(float d, std::uint32_t id) {
        int pos = n.count < k ? n.count : k - 1;
        if (n.count == k && !lexicographic_less(d, id, n.distance_sq[pos], n.index[pos])) return;
        for (; pos > 0 && lexicographic_less(d, id, n.distance_sq[pos - 1], n.index[pos - 1]);
             --pos) {
            n.distance_sq[pos] = n.distance_sq[pos - 1];
            n.index[pos] = n.index[pos - 1];
        }
        n.distance_sq[pos] = d;
        n.index[pos] = id;
        n.count = std::min(n.count + 1, k);
    }
};

Eigen::MatrixXf principal_axes(const FeatureMatrix& a, const FeatureMatrix& b) {
    const Eigen::Index dim = a.rows();
    const double n = static_cast<double>(a.cols() + b.cols());
    if (n == 0) return Eigen::MatrixXf::Identity(dim, dim);
    const Eigen::VectorXd mean =
        (a.cast<double>().rowwise().sum() + b.cast<double>().rowwise().sum()) / n;
    Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(dim, dim);
    for (const FeatureMatrix* f : {&a, &b}) {
        const Eigen::MatrixXd centred = f->cast<double>().colwise() - mean;
        cov.noalias() += centred * centred.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(cov / n);
    // Eigenvalues ascend: reverse so that the largest variance comes first.
    return es.eigenvectors().rowwise().reverse().transpose().cast<float>();
}

FeatureIndex::FeatureIndex(const FeatureMatrix& rotated)
    : dim_(static_cast<std::size_t>(rotated.rows())),
      padded_dim_((dim_ + kCheckEvery - 1) / kCheckEvery * kCheckEvery),
      size_(static_cast<std::size_t>(rotated.cols())) {
    std::vector<std::uint32_t> order(size_);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
        return rotated(0, x) < rotated(0, y);
    });
    const std::size_t blocks = (size_ + kLanes - 1) / kLanes;
    ids_.assign(blocks * kLanes, kPadding);
    blocks_.assign(blocks * padded_dim_ * kLanes, 0.0f);
    for (std::size_t r = 0; r < size_; ++r) {
        ids_[r] = order[r];
        const std::size_t b = r / kLanes;
        for (std::size_t a = 0; a < dim_; ++a) {
            blocks_[(b * padded_dim_ + a) * kLanes + r % kLanes] =
                rotated(static_cast<Eigen::Index>(a), order[r]);
        }
    }
    // Padding lanes sit at +infinity on the first axis: never within any finite bound.
    for (std::size_t r = size_; r < ids_.size(); ++r)
        blocks_[(r / kLanes) * padded_dim_ * kLanes + r % kLanes] = kInf;
}

std::size_t FeatureIndex::first_not_below(float x) const {
    std::size_t lo = 0;
    std::size_t hi = size_;
    while (lo < hi) {
        const std::size_t mid = (lo + hi) / 2;
        if (coordinate(mid / kLanes, 0, mid % kLanes) < x) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    return lo;
}

bool FeatureIndex::visit_block(const float* q, std::size_t b, int side, Best& best) const {
    if (side != 0) {  // the lane nearest the query on this side bounds the whole block
        const float gap = q[0] - coordinate(b, 0, side > 0 ? 0 : kLanes - 1);
        if (gap * gap > best.bound()) return false;
    }
    // All lanes are summed axis by axis (vectorised), in groups of kCheckEvery axes (the axes
    // are padded with zeros to a multiple of it); the block is abandoned as soon as every lane
    // exceeds the bound (partial distance search).
    float d[kLanes] = {};
    const float bound = best.bound();
    for (std::size_t a0 = 0; a0 < padded_dim_; a0 += kCheckEvery) {
        const float* group = &blocks_[(b * padded_dim_ + a0) * kLanes];
        for (std::size_t a = 0; a < kCheckEvery; ++a) {
            for (std::size_t l = 0; l < kLanes; ++l) {
                const float diff = q[a0 + a] - group[a * kLanes + l];
                d[l] += diff * diff;
            }
        }
        int within = 0;
        for (std::size_t l = 0; l < kLanes; ++l) within += d[l] <= bound ? 1 : 0;
        if (within == 0) return true;
    }
    for (std::size_t l = 0; l < kLanes; ++l) {
        const std::uint32_t id = ids_[b * kLanes + l];
        if (id != kPadding) best.offer(d[l], id);
    }
    return true;
}

void FeatureIndex::search(const float* query, Best& best) const {
    std::vector<float> q(padded_dim_, 0.0f);
    std::copy_n(query, dim_, q.begin());
    const std::size_t start = std::min(first_not_below(query[0]), size_ - 1) / kLanes;
    const std::size_t blocks = ids_.size() / kLanes;
    visit_block(q.data(), start, 0, best);
    std::size_t up = start + 1;
    std::size_t down = start;
    bool go_up = up < blocks;
    bool go_down = down > 0;
    while (go_up || go_down) {  // alternate sides so the bound shrinks early
        if (go_up) go_up = visit_block(q.data(), up++, +1, best) && up < blocks;
        if (go_down) go_down = visit_block(q.data(), --down, -1, best) && down > 0;
    }
}

FeatureNeighbors FeatureIndex::nearest(const float* query, int k) const {
    Best best;
    best.k = std::min<int>(k, static_cast<int>(size_));
    if (best.k > 0) search(query, best);
    return best.n;
}

bool FeatureIndex::is_nearest(const float* query, std::uint32_t candidate,
                              float distance_sq) const {
    // Seeded with the candidate, the search only visits what could beat it: a narrow window.
    Best best;
    best.n.count = 1;
    best.n.index[0] = candidate;
    best.n.distance_sq[0] = distance_sq;
    search(query, best);
    return best.n.index[0] == candidate;
}

}  // namespace scantling::registration::detail
