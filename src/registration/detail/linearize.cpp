#include "linearize.hpp"

#include <cmath>
#include <optional>
#include <span>
#include <vector>

#include <scantling/registration/factors.hpp>

#include "back_faces.hpp"

namespace scantling::registration::detail {
namespace {

// Source points per reduction chunk. Fixed (not derived from the thread count) so the summation
// order, hence every bit of the result, is the same for 1 and N threads.
constexpr std::size_t kGrain = 256;

struct Match {
    Eigen::Vector3d q;  ///< source point in the target frame
    std::size_t j;      ///< target index
    double distance_sq_m2;
};

/// Adds w Jᵀ J (J a 1×6 row) without forming the product of generic matrices. With `out`,
/// also writes the score w r Jᵀ and the sensitivity w Jᵀ (as do the two below, there w Jᵀ Ω).
void add_row(LinearSystem& s, const RowVector6d& J, double r, double w, CellScore* out) {
    s.H.noalias() += (w * J.transpose()) * J;
    const Vector6d g = (w * r) * J.transpose();
    s.b += g;
    s.cost += w * r * r;
    if (out) {
        out->score = g;
        out->sensitivity.setZero();
        out->sensitivity.col(0) = w * J.transpose();
    }
}

/// Adds w Jᵀ Ω J and w Jᵀ Ω r for J = [I, −hat(q)] block by block: with Q = hat(q) (Qᵀ = −Q),
/// Jᵀ Ω J = [[Ω, −Ω Q], [Q Ω, −Q Ω Q]] and Jᵀ Ω r = [Ω r, q × (Ω r)]. Several times cheaper
/// than the generic 6×3 products, and this runs once per correspondence.
void add_block(LinearSystem& s, const Eigen::Vector3d& q, const Eigen::Matrix3d& Omega,
               const Eigen::Vector3d& r, double w, CellScore* out) {
    const Eigen::Matrix3d wOmega = w * Omega;
    const Eigen::Matrix3d Q = hat(q);
    const Eigen::Matrix3d wOmegaQ = wOmega * Q;
    s.H.topLeftCorner<3, 3>() += wOmega;
    s.H.topRightCorner<3, 3>() -= wOmegaQ;
    s.H.bottomLeftCorner<3, 3>() -= wOmegaQ.transpose();
    s.H.bottomRightCorner<3, 3>().noalias() -= Q * wOmegaQ;
    const Eigen::Vector3d wOmega_r = wOmega * r;
    Vector6d g;
    g << wOmega_r, q.cross(wOmega_r);
    s.b += g;
    s.cost += r.dot(wOmega_r);
    if (out) {
        out->score = g;
        out->sensitivity << wOmega, Q * wOmega;  // Jᵀ = [I; Q]
    }
}

/// Point-to-point: Ω = I, so Jᵀ J = [[I, −Q], [Q, |q|² I − q qᵀ]].
void add_point(LinearSystem& s, const Eigen::Vector3d& q, const Eigen::Vector3d& r, double w,
               CellScore* out) {
    const Eigen::Matrix3d wQ = w * hat(q);
    s.H.topLeftCorner<3, 3>().diagonal().array() += w;
    s.H.topRightCorner<3, 3>() -= wQ;
    s.H.bottomLeftCorner<3, 3>() += wQ;
    s.H.bottomRightCorner<3, 3>() +=
        w * (q.squaredNorm() * Eigen::Matrix3d::Identity() - q * q.transpose());
    Vector6d g;
    g << w * r, w * q.cross(r);
    s.b += g;
    s.cost += w * r.squaredNorm();
    if (out) {
        out->score = g;
        out->sensitivity << w * Eigen::Matrix3d::Identity(), wQ;
    }
}

template <IcpMethod M>
void accumulate(LinearSystem& s, const Problem& p, const Eigen::Matrix3d& R, std::size_t i,
                const Match& m, CellScore* out) {
    const Eigen::Vector3d& t = p.target_tree->points()[m.j];
    if constexpr (M == IcpMethod::kPointToPlane) {
        const Eigen::Vector3d& n = (*p.target_normals)[m.j];
        const double r = point_to_plane_residual(m.q, t, n);
        const double w = robust_weight(p.kernel, r, p.kernel_scale_m);
        add_row(s, point_to_plane_jacobian(m.q, n), r, w, out);
    } else {
        const Eigen::Vector3d r = point_to_point_residual(m.q, t);
        const double w = robust_weight(p.kernel, std::sqrt(m.distance_sq_m2), p.kernel_scale_m);
        if constexpr (M == IcpMethod::kPointToPoint) {
            add_point(s, m.q, r, w, out);
        } else {
            const Eigen::Matrix3d Omega =
                gicp_weight((*p.target_covariances)[m.j], (*p.source_covariances)[i], R);
            add_block(s, m.q, Omega, r, w, out);
        }
    }
}

/// The target point to pair with `q` per the problem's back-face handling; nullopt: none.
std::optional<Neighbor> correspondent(const Problem& p, const Eigen::Vector3d& q,
                                      const Eigen::Vector3d& origin, double max_sq,
                                      FaceSearchBuffers& buffers) {
    const std::span<const Eigen::Vector3d> normals =
        p.front_normals != nullptr ? std::span<const Eigen::Vector3d>(*p.front_normals)
                                   : std::span<const Eigen::Vector3d>();
    return face_aware_nearest(*p.target_tree, normals, q, origin, max_sq, p.back_faces, buffers);
}

std::array<std::int64_t, 3> cell_of(const Eigen::Vector3d& q, double cell_size_m) {
    return {static_cast<std::int64_t>(std::floor(q.x() / cell_size_m)),
            static_cast<std::int64_t>(std::floor(q.y() / cell_size_m)),
            static_cast<std::int64_t>(std::floor(q.z() / cell_size_m))};
}

template <IcpMethod M>
LinearSystem linearize_chunk(const Problem& p, const Eigen::Isometry3d& T, ScoreRecord* record,
                             std::size_t begin, std::size_t end) {
    LinearSystem s;
    const Eigen::Matrix3d R = T.linear();
    const Eigen::Vector3d tr = T.translation();
    const double max_sq = p.max_correspondence_distance_m * p.max_correspondence_distance_m;
    FaceSearchBuffers buffers;
    for (std::size_t i = begin; i < end; ++i) {
        const Eigen::Vector3d q = R * (*p.source_points)[i] + tr;
        const std::optional<Neighbor> nn = correspondent(p, q, tr, max_sq, buffers);
        if (!nn) continue;
        // Each chunk writes only its own indices: no race, and the order is the source order.
        CellScore* out = record ? &record->scores[i] : nullptr;
        accumulate<M>(s, p, R, i, Match{q, nn->index, nn->distance_sq_m2}, out);
        if (out) {
            out->cell = cell_of(q, record->cell_size_m);
            out->valid = true;
        }
        s.distance_sq_sum_m2 += nn->distance_sq_m2;
        s.q_sum += q;
        s.q_norm_sq_sum += q.squaredNorm();
        ++s.count;
    }
    return s;
}

template <IcpMethod M>
LinearSystem linearize_as(const Problem& p, const Eigen::Isometry3d& T, ScoreRecord* record) {
    return parallel_reduce_ordered(
        p.parallel, p.source_points->size(), kGrain, LinearSystem{},
        [&](std::size_t begin, std::size_t end) {
            return linearize_chunk<M>(p, T, record, begin, end);
        },
        [](LinearSystem a, const LinearSystem& b) { return a += b; });
}

}  // namespace

LinearSystem& LinearSystem::operator+=(const LinearSystem& other) {
    H += other.H;
    b += other.b;
    cost += other.cost;
    distance_sq_sum_m2 += other.distance_sq_sum_m2;
    q_sum += other.q_sum;
    q_norm_sq_sum += other.q_norm_sq_sum;
    count += other.count;
    return *this;
}

LinearSystem linearize(const Problem& problem, const Eigen::Isometry3d& T_target_source,
                       ScoreRecord* record) {
    if (record) record->scores.assign(problem.source_points->size(), CellScore{});
    switch (problem.method) {
        case IcpMethod::kPointToPoint:
            return linearize_as<IcpMethod::kPointToPoint>(problem, T_target_source, record);
        case IcpMethod::kPointToPlane:
            return linearize_as<IcpMethod::kPointToPlane>(problem, T_target_source, record);
        case IcpMethod::kGeneralized:
            return linearize_as<IcpMethod::kGeneralized>(problem, T_target_source, record);
    }
    return {};
}

}  // namespace scantling::registration::detail
