// Replanning around the obstacle that stopped the crawler (detour.hpp): a trapezoid beside the
// old path, laid on the surface, checked against every known footprint.
#include <scantling/planning/detour.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

#include "detail/surface_geometry.hpp"

namespace scantling::planning {
namespace {

using detail::point_text;

// Rounding allowed on a clearance: a passing leg laid exactly at radius + clearance on a plate
// lands there to ~1e-15 m; a micrometre is far below any crawler's margin.
constexpr double kClearanceTolerance_m = 1e-6;
// Pieces shorter than this are dropped, as mesh_path.hpp does (the follower's shortest).
constexpr double kMinPiece_m = 1e-6;
// Sums of offsets and lengths equal up to this are equal (0.3 + 14 × 0.05 lands a hair above
// 1.0; the two sides' lengths of a symmetric case differ in the last bits): ties go left.
constexpr double kRounding_m = 1e-9;

double length_of(const MeshPathSegment& s) { return (s.end_world_m - s.begin_world_m).norm(); }

/// Where on `s` (0 = begin, 1 = end) the point closest to `p` is.
double closest_t(const MeshPathSegment& s, const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = s.end_world_m - s.begin_world_m;
    if (d.squaredNorm() == 0.0) return 0.0;
    return std::clamp((p - s.begin_world_m).dot(d) / d.squaredNorm(), 0.0, 1.0);
}

/// The old path as a polyline with arc lengths.
class OldPath {
  public:
    explicit OldPath(const std::vector<MeshPathSegment>& segments) : segments_(segments) {
        start_s_.push_back(0.0);
        for (const MeshPathSegment& s : segments)
            start_s_.push_back(start_s_.back() + length_of(s));
    }

    double length_m() const { return start_s_.back(); }

    /// The segment holding arc length `s` (at a joint, the one beginning there).
    std::size_t segment_at(double s) const {
        const auto end = std::upper_bound(start_s_.begin() + 1, start_s_.end() - 1, s);
        return static_cast<std::size_t>(end - start_s_.begin()) - 1;
    }

    Eigen::Vector3d point_at(double s) const { return point_on(segment_at(s), s); }

    /// Left of the direction of travel at `s`: normal × forward, unit.
    Eigen::Vector3d lateral_at(double s) const {
        const MeshPathSegment& seg = segments_[segment_at(s)];
        const Eigen::Vector3d forward = seg.end_world_m - seg.begin_world_m;
        return seg.normal_world.cross(forward).normalized();
    }

    /// Arc length of the point of segments [first, last) closest to `p` (ties: the earliest).
    double closest_s(const Eigen::Vector3d& p, std::size_t first, std::size_t last) const {
        double best_s = start_s_[first];
        double best_d2 = std::numeric_limits<double>::infinity();
        for (std::size_t i = first; i < last; ++i) {
            const double s = start_s_[i] + closest_t(segments_[i], p) * length_of(segments_[i]);
            const double d2 = (point_on(i, s) - p).squaredNorm();
            if (d2 < best_d2) {
                best_s = s;
                best_d2 = d2;
            }
        }
        return best_s;
    }

    /// The old path between arc lengths s0 < s1, its pieces keeping their normals and faces.
    std::vector<MeshPathSegment> slice(double s0, double s1) const {
        std::vector<MeshPathSegment> pieces;
        for (std::size_t i = 0; i < segments_.size(); ++i) {
            const double a = std::max(s0, start_s_[i]);
            const double b = std::min(s1, start_s_[i + 1]);
            if (b - a < kMinPiece_m) continue;
            pieces.push_back(
                {point_on(i, a), point_on(i, b), segments_[i].normal_world, segments_[i].face});
        }
        return pieces;
    }

  private:
    Eigen::Vector3d point_on(std::size_t i, double s) const {
        const double length = start_s_[i + 1] - start_s_[i];
        const double t = length > 0.0 ? std::clamp((s - start_s_[i]) / length, 0.0, 1.0) : 0.0;
        return segments_[i].begin_world_m +
               t * (segments_[i].end_world_m - segments_[i].begin_world_m);
    }

    const std::vector<MeshPathSegment>& segments_;
    std::vector<double> start_s_;  ///< arc length at each segment's begin; back() = the total
};

/// Arc lengths of the detour's stations on the old path (detour.hpp's "Shape").
struct Stations {
    double crawler = 0.0, leave = 0.0, a = 0.0, b = 0.0, c = 0.0;
};

Stations stations_for(double s_crawler, double s_obstacle, double radius_m, double length_m,
                      double rejoin_m) {
    Stations st;
    st.crawler = s_crawler;
    // Nearer than the leave point, the crawler steps sideways: a diagonal from a crawler
    // stopped at the clearance would cut into it.
    const bool sideways = s_obstacle - radius_m - rejoin_m <= s_crawler;
    st.leave = sideways ? s_crawler : s_obstacle - radius_m - rejoin_m;
    st.a = sideways ? s_crawler : s_obstacle - radius_m - 0.5 * rejoin_m;
    const double footprint_end = s_obstacle + radius_m;
    st.c = std::max(st.a, std::min(length_m, footprint_end + rejoin_m));
    st.b = st.c > footprint_end ? 0.5 * (footprint_end + st.c) : st.c;
    st.b = std::max(st.b, st.a);
    return st;
}

/// Everything a side's try needs, computed once.
struct Context {
    const SurfaceProjector& surface;
    const SurfaceWalkConfig& walk;
    const DetourConfig& config;
    const OldPath& old;
    Eigen::Vector3d start;                      ///< the crawler, snapped onto the surface
    std::vector<ObstacleFootprint> footprints;  ///< centres projected onto the surface
    double s_crawler = 0.0;                     ///< the crawler's arc length on the old path
    double s_obstacle = 0.0;                    ///< the blocking footprint's
    double radius_m = 0.0;                      ///< the blocking footprint's radius

    /// The stations for a rejoin distance (detour.hpp's "Shape").
    Stations stations(double rejoin_m) const {
        return stations_for(s_crawler, s_obstacle, radius_m, old.length_m(), rejoin_m);
    }
};

/// Appends `pieces`, the first begun where `path` ends so the path is contiguous.
void append_joined(std::vector<MeshPathSegment>& path, std::vector<MeshPathSegment> pieces) {
    for (MeshPathSegment& piece : pieces) {
        if (!path.empty()) piece.begin_world_m = path.back().end_world_m;
        if (length_of(piece) >= kMinPiece_m) path.push_back(piece);
    }
}

/// The old path's point at `s`, `offset_m` to `side` along the surface.
Eigen::Vector3d beside(const Context& ctx, double s, int side, double offset_m) {
    const Eigen::Vector3d from = ctx.surface.project(ctx.old.point_at(s)).point;
    return walk_on_surface(ctx.surface, from, static_cast<double>(side) * ctx.old.lateral_at(s),
                           offset_m, ctx.walk, "the offset");
}

/// The new path for one side and offset, and the part of it that is new (checked against the
/// footprints: the old path's pieces before the leave and after the rejoin were the plan
/// already, and an obstacle beside them that did not stop the crawler (outside its corridor,
/// inside the detour's clearance) would otherwise forbid every detour). InputError when a leg
/// leaves the surface.
struct Candidate {
    std::vector<MeshPathSegment> path;
    std::vector<MeshPathSegment> fresh;
};

Candidate candidate_path(const Context& ctx, const Stations& st, int side, double offset_m) {
    Candidate out;
    std::vector<MeshPathSegment>& path = out.path;
    append_joined(path, ctx.old.slice(st.crawler, st.leave));  // empty when stepping sideways
    if (!path.empty()) path.front().begin_world_m = ctx.start;
    const Eigen::Vector3d from = path.empty() ? ctx.start : path.back().end_world_m;
    const Eigen::Vector3d a = beside(ctx, st.a, side, offset_m);
    const Eigen::Vector3d b = beside(ctx, st.b, side, offset_m);
    const Eigen::Vector3d c = ctx.old.point_at(st.c);
    append_joined(out.fresh, surface_line(ctx.surface, from, a, ctx.walk));
    append_joined(out.fresh, surface_line(ctx.surface, a, b, ctx.walk));
    append_joined(out.fresh, surface_line(ctx.surface, b, c, ctx.walk));
    append_joined(path, out.fresh);
    append_joined(path, ctx.old.slice(st.c, ctx.old.length_m()));
    return out;
}

double distance_to_segment(const Eigen::Vector3d& p, const MeshPathSegment& s) {
    const double t = closest_t(s, p);
    return (s.begin_world_m + t * (s.end_world_m - s.begin_world_m) - p).norm();
}

/// The first footprint `path` passes too near, described; nullopt when it is clear.
std::optional<std::string> first_conflict(const Context& ctx,
                                          const std::vector<MeshPathSegment>& path) {
    for (std::size_t k = 0; k < ctx.footprints.size(); ++k) {
        const ObstacleFootprint& o = ctx.footprints[k];
        double nearest_m = std::numeric_limits<double>::infinity();
        for (const MeshPathSegment& s : path) {
            nearest_m = std::min(nearest_m, distance_to_segment(o.centre_world_m, s));
        }
        // A crawler already within the clearance of a footprint passes it at the smaller one.
        const double clear_m = o.radius_m + ctx.config.clearance_m;
        const bool inside = (ctx.start - o.centre_world_m).norm() < clear_m;
        const double needed_m = inside ? o.radius_m + ctx.config.inside_clearance_m : clear_m;
        if (nearest_m < needed_m - kClearanceTolerance_m) {
            return fmt::format("obstacles[{}] at {:.4f} m, needs {:.4f} m", k, nearest_m, needed_m);
        }
    }
    return std::nullopt;
}

/// One side's outcome: its first clear path, or what failed at its last offset.
struct SideResult {
    std::optional<std::vector<MeshPathSegment>> path;
    double offset_m = 0.0;
    Stations stations;  ///< the clear path's
    std::string failure;
};

/// The rejoin distances tried at each offset, in rejoin_m: an obstacle near the first rejoin
/// point (beside the old path, outside the crawler's corridor) is passed by rejoining later
/// (measured in the loop: a bolt 0.2 m beside a transect, 0.15 m past a bracket across it,
/// forbade both sides at every offset).
constexpr std::array<double, 3> kRejoinFactors{1.0, 2.0, 3.0};

SideResult try_side(const Context& ctx, int side, double first_offset_m) {
    SideResult result;
    result.failure = fmt::format("needs an offset of {:.3f} m, more than max_offset_m = {} m",
                                 first_offset_m, ctx.config.max_offset_m);
    for (int k = 0;; ++k) {
        const double offset_m = first_offset_m + k * ctx.config.offset_step_m;
        if (offset_m > ctx.config.max_offset_m + kRounding_m) return result;
        for (const double factor : kRejoinFactors) {
            const Stations st = ctx.stations(factor * ctx.config.rejoin_m);
            try {
                Candidate candidate = candidate_path(ctx, st, side, offset_m);
                const std::optional<std::string> conflict = first_conflict(ctx, candidate.fresh);
                if (!conflict) return {std::move(candidate.path), offset_m, st, ""};
                result.failure = fmt::format("at offset {:.3f} m: passes {}", offset_m, *conflict);
            } catch (const InputError& error) {
                // A wider offset leaves the surface as surely: this side is done.
                result.failure = fmt::format("at offset {:.3f} m: {}", offset_m, error.what());
                return result;
            }
        }
    }
}

void validate_path(const Eigen::Vector3d& p_world_m,
                   const std::vector<MeshPathSegment>& remaining) {
    if (!p_world_m.allFinite()) {
        throw InputError(fmt::format("p_world_m = {} is not finite", point_text(p_world_m)));
    }
    if (remaining.empty()) throw InputError("remaining is empty: no path to detour from");
    for (std::size_t i = 0; i < remaining.size(); ++i) {
        const MeshPathSegment& s = remaining[i];
        if (!(s.begin_world_m.allFinite() && s.end_world_m.allFinite() &&
              s.normal_world.allFinite())) {
            throw InputError(fmt::format("remaining[{}] is not finite", i));
        }
    }
}

void validate_obstacles(std::span<const ObstacleFootprint> obstacles, std::size_t blocking) {
    if (blocking >= obstacles.size()) {
        throw InputError(fmt::format("blocking = {}, expected < obstacles.size() = {}", blocking,
                                     obstacles.size()));
    }
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
        if (!obstacles[k].centre_world_m.allFinite() ||
            !(std::isfinite(obstacles[k].radius_m) && obstacles[k].radius_m >= 0.0)) {
            throw InputError(fmt::format(
                "obstacles[{}] = centre {}, radius_m {}, expected finite, radius_m >= 0", k,
                point_text(obstacles[k].centre_world_m), obstacles[k].radius_m));
        }
    }
}

/// The footprints on the surface (an obstacle mapped by its top, a bolt's head, counts where it
/// stands).
void add_footprints(Context& ctx, std::span<const ObstacleFootprint> obstacles) {
    for (const ObstacleFootprint& o : obstacles) {
        ctx.footprints.push_back({ctx.surface.project(o.centre_world_m).point, o.radius_m});
    }
}

/// Why no detour can reach the goal, when the blocking footprint covers it.
std::optional<std::string> goal_covered(const Context& ctx, std::size_t blocking) {
    const ObstacleFootprint& o = ctx.footprints[blocking];
    const Eigen::Vector3d goal = ctx.old.point_at(ctx.old.length_m());
    const double goal_m = (goal - o.centre_world_m).norm();
    const double needed_m = o.radius_m + ctx.config.clearance_m;
    if (goal_m >= needed_m - kClearanceTolerance_m) return std::nullopt;
    return fmt::format(
        "obstacles[{}] covers the goal: the path's end {} is {:.3f} m from its centre, within "
        "radius + clearance = {:.3f} m; no detour can reach it, ask the operator",
        blocking, point_text(goal), goal_m, needed_m);
}

double path_length(const std::vector<MeshPathSegment>& path) {
    double length_m = 0.0;
    for (const MeshPathSegment& s : path) length_m += length_of(s);
    return length_m;
}

Detour not_found(std::string reason) {
    Detour detour;
    detour.reason = std::move(reason);
    return detour;
}

Detour chosen(const Context& ctx, SideResult result, int side) {
    Detour detour;
    detour.found = true;
    detour.side = side;
    detour.offset_m = result.offset_m;
    detour.path = std::move(*result.path);
    detour.length_m = path_length(detour.path);
    detour.rejoin_world_m = ctx.old.point_at(result.stations.c);
    return detour;
}

}  // namespace

void DetourConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    require_positive(clearance_m, prefix, "clearance_m");
    require_positive(rejoin_m, prefix, "rejoin_m");
    require_positive(max_offset_m, prefix, "max_offset_m");
    require_positive(offset_step_m, prefix, "offset_step_m");
    require(std::isfinite(inside_clearance_m) && inside_clearance_m > 0.0 &&
                inside_clearance_m <= clearance_m,
            prefix, "inside_clearance_m", inside_clearance_m, "> 0 and <= clearance_m");
}

Detour plan_detour(const SurfaceProjector& surface, const Eigen::Vector3d& p_world_m,
                   const std::vector<MeshPathSegment>& remaining,
                   std::span<const ObstacleFootprint> obstacles, std::size_t blocking,
                   const SurfaceWalkConfig& walk, const DetourConfig& config) {
    config.validate();
    walk.validate();
    validate_path(p_world_m, remaining);
    validate_obstacles(obstacles, blocking);
    const OldPath old(remaining);
    const Eigen::Vector3d start =
        snap_to_surface(surface, p_world_m, walk.max_start_distance_m, "p_world_m").point;
    Context ctx{surface, walk, config, old, start, {}, 0.0, 0.0, 0.0};
    add_footprints(ctx, obstacles);
    if (auto covered = goal_covered(ctx, blocking)) return not_found(std::move(*covered));
    const ObstacleFootprint& o = ctx.footprints[blocking];
    ctx.s_crawler = old.closest_s(ctx.start, 0, 1);
    ctx.s_obstacle = old.closest_s(o.centre_world_m, 0, remaining.size());
    ctx.radius_m = o.radius_m;
    const double first_offset_m = o.radius_m + config.clearance_m;
    SideResult left = try_side(ctx, +1, first_offset_m);
    SideResult right = try_side(ctx, -1, first_offset_m);
    if (!left.path && !right.path) {
        return not_found(
            fmt::format("no detour around obstacles[{}]: left {}; right {}; ask the operator",
                        blocking, left.failure, right.failure));
    }
    const bool take_left = left.path && (!right.path || path_length(*left.path) <=
                                                            path_length(*right.path) + kRounding_m);
    return take_left ? chosen(ctx, std::move(left), +1) : chosen(ctx, std::move(right), -1);
}

}  // namespace scantling::planning
