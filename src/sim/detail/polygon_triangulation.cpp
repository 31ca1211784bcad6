#include "polygon_triangulation.hpp"

#include <scantling/core/error.hpp>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace scantling::sim::detail {
namespace {

using V2 = Eigen::Vector2d;

double cross(const V2& o, const V2& a, const V2& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

double cross(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Orientation tests with a tolerance relative to the polygon size, so that exactly collinear
// input (shared with neighbouring geometry) is recognised despite rounding.
class Geometry {
  public:
    Geometry(std::vector<V2> points, double scale)
        : points_(std::move(points)), eps_(1e-12 * scale * scale) {}

    const V2& at(int id) const { return points_[id]; }

    int orient(int a, int b, int c) const { return orient(at(a), at(b), at(c)); }
    int orient(const V2& a, const V2& b, const V2& c) const {
        const double v = cross(a, b, c);
        return v > eps_ ? 1 : (v < -eps_ ? -1 : 0);
    }

    bool same(int a, int b) const { return at(a) == at(b); }

    // Closed segments [p1, p2] and [q1, q2] share a point.
    bool segments_touch(const V2& p1, const V2& p2, const V2& q1, const V2& q2) const {
        const int d1 = orient(q1, q2, p1), d2 = orient(q1, q2, p2);
        const int d3 = orient(p1, p2, q1), d4 = orient(p1, p2, q2);
        if (d1 * d2 < 0 && d3 * d4 < 0) return true;
        return (d1 == 0 && within_box(q1, q2, p1)) || (d2 == 0 && within_box(q1, q2, p2)) ||
               (d3 == 0 && within_box(p1, p2, q1)) || (d4 == 0 && within_box(p1, p2, q2));
    }

  private:
    static bool within_box(const V2& a, const V2& b, const V2& p) {
        return p.x() >= std::min(a.x(), b.x()) && p.x() <= std::max(a.x(), b.x()) &&
               p.y() >= std::min(a.y(), b.y()) && p.y() <= std::max(a.y(), b.y());
    }

    std::vector<V2> points_;
    double eps_;
};

using Ring = std::vector<int>;  // vertex ids in order; bridges repeat ids

// The direction from ring vertex k towards `target` enters the polygon's interior wedge at k.
bool locally_inside(const Geometry& g, const Ring& ring, std::size_t k, const V2& target) {
    const V2& p = g.at(ring[k]);
    const V2& a = g.at(ring[(k + ring.size() - 1) % ring.size()]);
    const V2& b = g.at(ring[(k + 1) % ring.size()]);
    const V2 d = target - p;
    if (cross(a, p, b) > 0.0) return cross(b - p, d) > 0.0 && cross(d, a - p) > 0.0;
    return !(cross(a - p, d) >= 0.0 && cross(d, b - p) >= 0.0);
}

bool crosses_loop(const Geometry& g, const Ring& loop, const V2& m, const V2& p) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const V2& c = g.at(loop[i]);
        const V2& d = g.at(loop[(i + 1) % loop.size()]);
        if (c == m || c == p || d == m || d == p) continue;  // edges at the bridge's ends
        if (g.segments_touch(m, p, c, d)) return true;
    }
    return false;
}

// Position in `ring` of the closest vertex that `hole[m]` can be joined to without crossing
// any edge of the ring or of the holes still to be merged.
std::size_t find_bridge(const Geometry& g, const Ring& ring, const std::vector<Ring>& holes,
                        int m) {
    const V2& target = g.at(m);
    std::vector<std::size_t> order(ring.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return (g.at(ring[a]) - target).squaredNorm() < (g.at(ring[b]) - target).squaredNorm();
    });
    for (const std::size_t k : order) {
        const V2& p = g.at(ring[k]);
        if (!locally_inside(g, ring, k, target) || crosses_loop(g, ring, target, p)) continue;
        const bool blocked = std::any_of(holes.begin(), holes.end(), [&](const Ring& h) {
            return crosses_loop(g, h, target, p);
        });
        if (!blocked) return k;
    }
    throw InputError("triangulate_polygon: a hole cannot be joined to the outline");
}

// Splices `hole` (clockwise) into `ring` through a bridge from its rightmost vertex.
void merge_hole(const Geometry& g, Ring& ring, const Ring& hole, const std::vector<Ring>& rest) {
    std::size_t m = 0;
    for (std::size_t i = 1; i < hole.size(); ++i) {
        if (g.at(hole[i]).x() > g.at(hole[m]).x()) m = i;
    }
    const std::size_t k = find_bridge(g, ring, rest, hole[m]);
    Ring merged(ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(k) + 1);
    for (std::size_t i = 0; i <= hole.size(); ++i) merged.push_back(hole[(m + i) % hole.size()]);
    merged.insert(merged.end(), ring.begin() + static_cast<std::ptrdiff_t>(k), ring.end());
    ring = std::move(merged);
}

class EarClipper {
  public:
    EarClipper(const Geometry& g, const Ring& ring) : g_(g), ring_(ring) {
        const std::size_t n = ring.size();
        prev_.resize(n);
        next_.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            prev_[i] = (i + n - 1) % n;
            next_[i] = (i + 1) % n;
        }
    }

    std::vector<std::array<int, 3>> run() {
        std::vector<std::array<int, 3>> triangles;
        std::size_t remaining = ring_.size();
        std::size_t cur = 0;
        std::size_t misses = 0;
        while (remaining > 3) {
            if (!is_ear(cur)) {
                cur = next_[cur];
                if (++misses > remaining) {
                    throw InputError("triangulate_polygon: no ear left (self-intersecting input)");
                }
                continue;
            }
            triangles.push_back({ring_[prev_[cur]], ring_[cur], ring_[next_[cur]]});
            next_[prev_[cur]] = next_[cur];
            prev_[next_[cur]] = prev_[cur];
            cur = next_[cur];
            --remaining;
            misses = 0;
        }
        if (g_.orient(ring_[prev_[cur]], ring_[cur], ring_[next_[cur]]) > 0) {
            triangles.push_back({ring_[prev_[cur]], ring_[cur], ring_[next_[cur]]});
        }
        return triangles;
    }

  private:
    bool is_ear(std::size_t i) const {
        const int a = ring_[prev_[i]], b = ring_[i], c = ring_[next_[i]];
        if (g_.orient(a, b, c) <= 0) return false;
        for (std::size_t j = next_[next_[i]]; j != prev_[i]; j = next_[j]) {
            const int p = ring_[j];
            if (g_.same(p, a) || g_.same(p, b) || g_.same(p, c)) continue;
            if (g_.orient(a, b, p) >= 0 && g_.orient(b, c, p) >= 0 && g_.orient(c, a, p) >= 0) {
                return false;
            }
        }
        return true;
    }

    const Geometry& g_;
    const Ring& ring_;
    std::vector<std::size_t> prev_;
    std::vector<std::size_t> next_;
};

Ring oriented_ring(std::span<const V2> loop, int first_id, bool counter_clockwise) {
    Ring ring(loop.size());
    std::iota(ring.begin(), ring.end(), first_id);
    if ((signed_area(loop) > 0.0) != counter_clockwise) std::reverse(ring.begin(), ring.end());
    return ring;
}

}  // namespace

double signed_area(std::span<const Eigen::Vector2d> loop) {
    double twice = 0.0;
    for (std::size_t i = 0; i < loop.size(); ++i) {
        twice += cross(loop[i], loop[(i + 1) % loop.size()]);
    }
    return 0.5 * twice;
}

std::vector<std::array<int, 3>> triangulate_polygon(std::span<const Eigen::Vector2d> outer,
                                                    const std::vector<Loop2>& holes) {
    if (outer.size() < 3) {
        throw InputError(
            fmt::format("triangulate_polygon: {} outline vertices, expected >= 3", outer.size()));
    }
    std::vector<V2> points(outer.begin(), outer.end());
    std::vector<Ring> hole_rings;
    for (const Loop2& hole : holes) {
        if (hole.size() < 3) throw InputError("triangulate_polygon: hole with < 3 vertices");
        hole_rings.push_back(oriented_ring(hole, static_cast<int>(points.size()), false));
        points.insert(points.end(), hole.begin(), hole.end());
    }
    Eigen::AlignedBox2d box;
    for (const V2& p : points) box.extend(p);
    const Geometry g(std::move(points), box.diagonal().norm());
    Ring ring = oriented_ring(outer, 0, true);
    // Rightmost holes first, so that bridges of later holes can see the earlier ones.
    auto max_x = [&](const Ring& h) {
        double x = -INFINITY;
        for (int id : h) x = std::max(x, g.at(id).x());
        return x;
    };
    std::stable_sort(hole_rings.begin(), hole_rings.end(),
                     [&](const Ring& a, const Ring& b) { return max_x(a) > max_x(b); });
    for (std::size_t h = 0; h < hole_rings.size(); ++h) {
        const std::vector<Ring> rest(hole_rings.begin() + static_cast<std::ptrdiff_t>(h),
                                     hole_rings.end());
        merge_hole(g, ring, hole_rings[h], rest);
    }
    return EarClipper(g, ring).run();
}

}  // namespace scantling::sim::detail
