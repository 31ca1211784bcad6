#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/perception/camera_coverage.hpp>

#include "detail/angles.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include <fmt/format.h>

namespace scantling::perception {
namespace {

// Rotations and axes come from normalised quaternions or cross products (errors ~1e-15);
// 1e-6 still catches a wrong axis or a scaled matrix.
constexpr double kUnitTolerance = 1e-6;
// A side that is a whole number of cells up to rounding (3.0 / 0.05 = 60.000000000000007)
// must not get an extra sliver column.
constexpr double kWholeCellsTolerance = 1e-9;

/// An axis-aligned box in the rectangle's (u, v) coordinates, metres.
struct BoxUv {
    Eigen::Vector2d lo;
    Eigen::Vector2d hi;
};

std::string format_vector(const Eigen::Vector3d& x) {
    return fmt::format("({}, {}, {})", x.x(), x.y(), x.z());
}

void require_vector(bool ok, std::string_view prefix, std::string_view field,
                    const Eigen::Vector3d& x, std::string_view expected) {
    if (!ok) {
        throw ConfigError(
            fmt::format("{}.{} = {}, expected {}", prefix, field, format_vector(x), expected));
    }
}

bool is_unit(const Eigen::Vector3d& x) {
    return x.allFinite() && std::abs(x.norm() - 1.0) <= kUnitTolerance;
}

/// Cells along a side: the fewest of at most cell_m each (at least one).
double cells_along(double length_m, double cell_m) {
    return std::max(1.0, std::ceil(length_m / cell_m - kWholeCellsTolerance));
}

void require_cell_count(const InspectionRectangle& r, double cell_m, std::string_view prefix) {
    const double cells = cells_along(r.width_m, cell_m) * cells_along(r.height_m, cell_m);
    if (cells > kMaxCoverageCells) {
        throw ConfigError(fmt::format(
            "{}.rectangle.width_m × height_m = {} × {} m at {}.cell_size_m = {} gives {} cells, "
            "expected <= {} (a larger cell or a smaller rectangle)",
            prefix, r.width_m, r.height_m, prefix, cell_m, cells, kMaxCoverageCells));
    }
}

void require_pose(const Eigen::Isometry3d& T_world_camera) {
    const Eigen::Matrix3d R = T_world_camera.linear();
    if (!T_world_camera.matrix().allFinite()) {
        throw InputError("camera_coverage.add_view: T_world_camera is not finite");
    }
    const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (error > kUnitTolerance || R.determinant() < 0.0) {
        throw InputError(
            fmt::format("camera_coverage.add_view: T_world_camera's rotation is not orthonormal "
                        "(|RᵀR − I| = {}, det = {}), expected a rotation",
                        error, R.determinant()));
    }
}

double min_focal_px(const PinholeIntrinsics& intrinsics) {
    return std::min(intrinsics.fx, intrinsics.fy);
}

/// Radius, in the plane around the camera's foot, of the disc where the range, incidence and
/// resolution limits hold for a camera height_m in front; negative when there is none. With
/// cos i = h / r the resolution limit 1000 r / (f cos i) <= m is r² <= m f h / 1000, a range.
double seen_radius_m(double height_m, const CameraCoverageConfig& config, double focal_px) {
    double range_m = config.max_range_m;
    if (config.max_mm_per_px > 0.0) {
        range_m = std::min(range_m, std::sqrt(config.max_mm_per_px * focal_px * height_m / 1000.0));
    }
    if (range_m <= height_m) return -1.0;
    const double tan_incidence = std::tan(detail::radians(config.max_incidence_deg));
    return std::min(std::sqrt(range_m * range_m - height_m * height_m), height_m * tan_incidence);
}

/// Where the image's corner rays meet the plane, (u, v) box; nullopt when a corner ray misses
/// it (the footprint then reaches the horizon and only the disc bounds it). The frustum is
/// convex, so when its four edge rays meet the plane the footprint is their quadrilateral.
std::optional<BoxUv> image_footprint_uv(const Eigen::Isometry3d& T_world_camera,
                                        const PinholeIntrinsics& k, const InspectionRectangle& r,
                                        double height_m) {
    const Eigen::Vector3d n = r.normal_world();
    const std::array<Eigen::Vector2d, 4> corners_px = {
        Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(k.width - 0.5, -0.5),
        Eigen::Vector2d(-0.5, k.height - 0.5), Eigen::Vector2d(k.width - 0.5, k.height - 0.5)};
    constexpr double kInf = std::numeric_limits<double>::infinity();
    BoxUv box{Eigen::Vector2d::Constant(kInf), Eigen::Vector2d::Constant(-kInf)};
    for (const Eigen::Vector2d& pixel : corners_px) {
        const Eigen::Vector3d d_world = T_world_camera.linear() * k.unproject(pixel, 1.0);
        const double approach = -n.dot(d_world);  // > 0: the ray runs towards the plane
        if (!(approach > 0.0)) return std::nullopt;
        const Eigen::Vector3d hit_from_corner_world =
            T_world_camera.translation() + (height_m / approach) * d_world - r.corner_world;
        const Eigen::Vector2d hit_uv_m(hit_from_corner_world.dot(r.u_world),
                                       hit_from_corner_world.dot(r.v_world));
        box.lo = box.lo.cwiseMin(hit_uv_m);
        box.hi = box.hi.cwiseMax(hit_uv_m);
    }
    return box;
}

/// Indices of the cells whose centres may lie in [lo, hi] along one side: first and one past
/// the last, clamped to [0, count].
std::pair<std::size_t, std::size_t> index_span(double lo_m, double hi_m, double cell_m,
                                               std::size_t count) {
    // Half a cell of margin: the box only bounds the search, each centre is tested exactly.
    const double first = std::floor(lo_m / cell_m - 0.5);
    const double last = std::floor(hi_m / cell_m + 0.5);
    const double n = static_cast<double>(count);
    const double begin = std::clamp(first, 0.0, n);
    const double end = std::clamp(last + 1.0, 0.0, n);
    return {static_cast<std::size_t>(begin), static_cast<std::size_t>(std::max(begin, end))};
}

/// A 4-connected patch of uncovered cells, in grid terms.
struct HoleCells {
    std::size_t cells = 0;
    Eigen::Vector2d sum_index = Eigen::Vector2d::Zero();  ///< Σ (column, row)
    Eigen::Vector2d min_index = Eigen::Vector2d::Constant(std::numeric_limits<double>::max());
    Eigen::Vector2d max_index = Eigen::Vector2d::Zero();
};

/// The patch of `open` cells 4-connected to `start`, which it closes (flood fill with an
/// explicit stack: a hole may have 10⁵ cells, too deep to recurse).
HoleCells flood(std::vector<std::uint8_t>& open, std::size_t start, std::size_t columns,
                std::vector<std::size_t>& stack) {
    HoleCells hole;
    open[start] = 0;
    stack.assign(1, start);
    while (!stack.empty()) {
        const std::size_t i = stack.back();
        stack.pop_back();
        const std::size_t column = i % columns;
        const Eigen::Vector2d index(static_cast<double>(column), static_cast<double>(i / columns));
        ++hole.cells;
        hole.sum_index += index;
        hole.min_index = hole.min_index.cwiseMin(index);
        hole.max_index = hole.max_index.cwiseMax(index);
        const auto push = [&](std::size_t j) {
            if (!open[j]) return;
            open[j] = 0;
            stack.push_back(j);
        };
        if (column > 0) push(i - 1);
        if (column + 1 < columns) push(i + 1);
        if (i >= columns) push(i - columns);
        if (i + columns < open.size()) push(i + columns);
    }
    return hole;
}

}  // namespace

/// One camera pose, in the terms the cell test needs.
struct CameraCoverage::View {
    Eigen::Isometry3d T_world_camera;
    Eigen::Isometry3d T_camera_world;
    Eigen::Vector3d p_world_camera;  ///< camera centre
    Eigen::Vector2d camera_uv_m;     ///< camera centre projected onto the rectangle's plane
    double height_m = 0.0;           ///< signed distance in front of the plane, along n
};

/// Cells [column_begin, column_end) × [row_begin, row_end); empty when a begin >= its end.
struct CameraCoverage::CellRange {
    std::size_t column_begin = 0;
    std::size_t column_end = 0;
    std::size_t row_begin = 0;
    std::size_t row_end = 0;
};

void CameraCoverageConfig::validate(std::string_view prefix) const {
    config_checks::require_positive(cell_size_m, prefix, "cell_size_m");
    config_checks::require_positive(max_range_m, prefix, "max_range_m");
    config_checks::require(max_incidence_deg > 0.0 && max_incidence_deg <= 90.0, prefix,
                           "max_incidence_deg", max_incidence_deg, "in (0, 90]");
    config_checks::require_non_negative(max_mm_per_px, prefix, "max_mm_per_px");
    config_checks::require_at_least(min_views, 1, prefix, "min_views");
}

void InspectionRectangle::validate(std::string_view prefix) const {
    require_vector(corner_world.allFinite(), prefix, "corner_world", corner_world, "finite");
    require_vector(is_unit(u_world), prefix, "u_world", u_world, "a unit vector");
    require_vector(is_unit(v_world), prefix, "v_world", v_world, "a unit vector");
    require_vector(std::abs(u_world.dot(v_world)) <= kUnitTolerance, prefix, "v_world", v_world,
                   fmt::format("orthogonal to u_world = {}", format_vector(u_world)));
    config_checks::require_positive(width_m, prefix, "width_m");
    config_checks::require_positive(height_m, prefix, "height_m");
}

CameraCoverage::CameraCoverage(const InspectionRectangle& rectangle,
                               const PinholeIntrinsics& intrinsics,
                               const CameraCoverageConfig& config)
    : rectangle_(rectangle), intrinsics_(intrinsics), config_(config) {
    constexpr std::string_view kPrefix = "camera_coverage";
    config_.validate(kPrefix);
    rectangle_.validate("camera_coverage.rectangle");
    intrinsics_.validate("camera_coverage.intrinsics");
    require_cell_count(rectangle_, config_.cell_size_m, kPrefix);
    columns_ = static_cast<std::size_t>(cells_along(rectangle_.width_m, config_.cell_size_m));
    rows_ = static_cast<std::size_t>(cells_along(rectangle_.height_m, config_.cell_size_m));
    cell_u_m_ = rectangle_.width_m / static_cast<double>(columns_);
    cell_v_m_ = rectangle_.height_m / static_cast<double>(rows_);
    cos_max_incidence_ = std::cos(detail::radians(config_.max_incidence_deg));
    view_counts_.assign(columns_ * rows_, 0);
}

void CameraCoverage::add_view(const Eigen::Isometry3d& T_world_camera,
                              const OcclusionTest& occluded) {
    require_pose(T_world_camera);
    const Eigen::Vector3d offset_world = T_world_camera.translation() - rectangle_.corner_world;
    const View view{T_world_camera,
                    T_world_camera.inverse(),
                    T_world_camera.translation(),
                    {offset_world.dot(rectangle_.u_world), offset_world.dot(rectangle_.v_world)},
                    offset_world.dot(rectangle_.normal_world())};
    if (!(view.height_m > 0.0)) return;  // behind the rectangle or in its plane
    const CellRange range = cells_to_test(view);
    for (std::size_t row = range.row_begin; row < range.row_end; ++row) {
        for (std::size_t column = range.column_begin; column < range.column_end; ++column) {
            if (!sees(view, cell_centre_world(column, row), occluded)) continue;
            std::uint32_t& count = view_counts_[row * columns_ + column];
            if (count < std::numeric_limits<std::uint32_t>::max()) ++count;
        }
    }
}

CameraCoverage::CellRange CameraCoverage::cells_to_test(const View& view) const {
    const double radius_m = seen_radius_m(view.height_m, config_, min_focal_px(intrinsics_));
    if (!(radius_m >= 0.0)) return {};
    BoxUv box{view.camera_uv_m.array() - radius_m, view.camera_uv_m.array() + radius_m};
    if (const auto footprint =
            image_footprint_uv(view.T_world_camera, intrinsics_, rectangle_, view.height_m)) {
        box = {box.lo.cwiseMax(footprint->lo), box.hi.cwiseMin(footprint->hi)};
    }
    if ((box.lo.array() > box.hi.array()).any()) return {};
    const auto [column_begin, column_end] = index_span(box.lo.x(), box.hi.x(), cell_u_m_, columns_);
    const auto [row_begin, row_end] = index_span(box.lo.y(), box.hi.y(), cell_v_m_, rows_);
    return {column_begin, column_end, row_begin, row_end};
}

bool CameraCoverage::sees(const View& view, const Eigen::Vector3d& p_world,
                          const OcclusionTest& occluded) const {
    const Eigen::Vector3d p_camera = view.T_camera_world * p_world;
    if (!intrinsics_.project(p_camera)) return false;
    const double range_m = p_camera.norm();
    if (range_m > config_.max_range_m) return false;
    const double cos_incidence = view.height_m / range_m;
    if (cos_incidence < cos_max_incidence_) return false;
    if (config_.max_mm_per_px > 0.0) {
        const double mm_per_px = 1000.0 * range_m / (min_focal_px(intrinsics_) * cos_incidence);
        if (mm_per_px > config_.max_mm_per_px) return false;
    }
    return !occluded || !occluded(view.p_world_camera, p_world);
}

Eigen::Vector2d CameraCoverage::cell_centre_uv(std::size_t column, std::size_t row) const {
    return {(static_cast<double>(column) + 0.5) * cell_u_m_,
            (static_cast<double>(row) + 0.5) * cell_v_m_};
}

Eigen::Vector3d CameraCoverage::uv_to_world(const Eigen::Vector2d& uv_m) const {
    return rectangle_.corner_world + uv_m.x() * rectangle_.u_world + uv_m.y() * rectangle_.v_world;
}

Eigen::Vector3d CameraCoverage::cell_centre_world(std::size_t column, std::size_t row) const {
    return uv_to_world(cell_centre_uv(column, row));
}

std::vector<CoverageHole> CameraCoverage::find_holes() const {
    const auto min_views = static_cast<std::uint32_t>(config_.min_views);
    std::vector<std::uint8_t> open(view_counts_.size());
    std::transform(view_counts_.begin(), view_counts_.end(), open.begin(),
                   [&](std::uint32_t c) { return c < min_views ? 1 : 0; });
    std::vector<CoverageHole> holes;
    std::vector<std::size_t> stack;
    const Eigen::Vector2d cell_m(cell_u_m_, cell_v_m_);
    for (std::size_t i = 0; i < open.size(); ++i) {
        if (!open[i]) continue;
        const HoleCells h = flood(open, i, columns_, stack);
        const double cells = static_cast<double>(h.cells);
        const Eigen::Vector2d centroid_uv_m =
            (h.sum_index / cells).array().cwiseProduct(cell_m.array()) + 0.5 * cell_m.array();
        holes.push_back({h.cells, cells * cell_u_m_ * cell_v_m_, uv_to_world(centroid_uv_m),
                         h.min_index.cwiseProduct(cell_m),
                         (h.max_index.array() + 1.0).matrix().cwiseProduct(cell_m)});
    }
    // Stable: equal holes keep the order of their first cell (row-major), so runs agree.
    std::stable_sort(holes.begin(), holes.end(), [](const CoverageHole& a, const CoverageHole& b) {
        return a.cells > b.cells;
    });
    return holes;
}

CoverageResult CameraCoverage::result() const {
    CoverageResult result;
    result.cells = view_counts_.size();
    const auto min_views = static_cast<std::uint32_t>(config_.min_views);
    result.covered_cells = static_cast<std::size_t>(std::count_if(
        view_counts_.begin(), view_counts_.end(), [&](std::uint32_t c) { return c >= min_views; }));
    result.covered_fraction =
        static_cast<double>(result.covered_cells) / static_cast<double>(result.cells);
    result.covered_area_m2 = static_cast<double>(result.covered_cells) * cell_u_m_ * cell_v_m_;
    result.holes = find_holes();
    return result;
}

}  // namespace scantling::perception
